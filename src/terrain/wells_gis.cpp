// Wells from OGR, the in-memory layers of a terrain run and the GeoPackage wells layer (wells_gis.hpp).
#include "terrain/wells_gis.hpp"
#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <cpl_vsi.h>
#include <gdal_priv.h>
#include <ogrsf_frmts.h>
#include "base/error.hpp"
#include "gis/gdal_util.hpp"

namespace fdr::terrain {
namespace {

std::string num(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

// A fresh /vsimem/ path: one per call in the process.
std::string mem_path(const std::string& stem, const std::string& ext) {
  static std::atomic<unsigned long> counter{0};
  return "/vsimem/fdrmesh_" + stem + "_" + std::to_string(counter++) + "." + ext;
}

// One feature as read, in the layer's CRS.
struct RawWell {
  std::int64_t fid = -1;
  std::string name, where;
  std::vector<Point3> pts;  // a point, or a line's vertices
  WellRangeKind kind = WellRangeKind::kElevation;
  double upper = 0, lower = 0;
};

struct RawWells {
  OGRSpatialReference srs;
  std::vector<RawWell> wells;
};

std::optional<double> field(const OGRFeature& f, const char* name) {
  const int i = f.GetFieldIndex(name);  // case-insensitive
  if (i < 0 || !f.IsFieldSetAndNotNull(i)) return std::nullopt;
  return f.GetFieldAsDouble(i);
}

// The range of a point well from its attributes; throws naming the feature.
void point_range(const OGRFeature& f, RawWell& w) {
  const auto top = field(f, "top"), bottom = field(f, "bottom");
  const auto from = field(f, "depth_from"), to = field(f, "depth_to");
  if (top && bottom) {
    w.kind = WellRangeKind::kElevation;
    w.upper = *top, w.lower = *bottom;
    if (!(w.upper > w.lower))
      throw Error(ExitCode::kInvalidGeometry, w.where + ": top " + num(w.upper) + " must lie above bottom " + num(w.lower));
  } else if (from && to) {
    w.kind = WellRangeKind::kDepth;
    w.upper = *from, w.lower = *to;
    if (!(w.lower > w.upper))
      throw Error(ExitCode::kInvalidGeometry, w.where + ": depth_to " + num(w.lower) + " must exceed depth_from " + num(w.upper));
  } else {
    throw Error(ExitCode::kInvalidGeometry, w.where + ": a point well needs the fields top and bottom (elevations) or "
                                                      "depth_from and depth_to (depths below the DEM)");
  }
}

RawWells read_raw(const WellsSource& src) {
  gis::ensure_gdal_registered();
  gis::GdalQuiet quiet;
  const gis::OpenedLayer opened = gis::open_layer(src.path, src.layer);
  OGRLayer* lyr = opened.layer;
  const std::string label = "--wells " + opened.source + ": layer '" + lyr->GetName() + "'";
  RawWells out;
  if (const OGRSpatialReference* s = lyr->GetSpatialRef()) out.srs = *s;
  else if (src.s_srs.empty() || out.srs.SetFromUserInput(src.s_srs.c_str()) != OGRERR_NONE)
    throw Error(ExitCode::kCrsError, label + " has no CRS; give --s_srs");
  out.srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  lyr->ResetReading();
  for (auto& f : *lyr) {
    const OGRGeometry* g = f->GetGeometryRef();
    if (!g || g->IsEmpty()) continue;
    RawWell w;
    w.fid = f->GetFID();
    const int ni = f->GetFieldIndex("name");
    w.name = ni >= 0 && f->IsFieldSetAndNotNull(ni) ? f->GetFieldAsString(ni) : "FID " + std::to_string(w.fid);
    OGREnvelope env;
    g->getEnvelope(&env);
    w.where = label + ", feature FID " + std::to_string(w.fid) + " (" + w.name + ") at (" + num(env.MinX) + ", " +
              num(env.MinY) + ")";
    const auto type = wkbFlatten(g->getGeometryType());
    if (type == wkbPoint) {
      const OGRPoint* p = g->toPoint();
      w.pts.push_back({p->getX(), p->getY(), 0.0});
      point_range(*f, w);
    } else if (type == wkbLineString && g->Is3D()) {
      const OGRLineString* l = g->toLineString();
      double zmax = -std::numeric_limits<double>::infinity(), zmin = -zmax;
      for (int i = 0; i < l->getNumPoints(); ++i) {
        w.pts.push_back({l->getX(i), l->getY(i), l->getZ(i)});
        zmax = std::max(zmax, l->getZ(i)), zmin = std::min(zmin, l->getZ(i));
      }
      w.kind = WellRangeKind::kElevation;
      w.upper = zmax, w.lower = zmin;
      if (!(zmax > zmin)) throw Error(ExitCode::kInvalidGeometry, w.where + ": a well line needs vertices at two elevations");
    } else {
      throw Error(ExitCode::kInvalidGeometry, w.where + ": geometry is " + g->getGeometryName() +
                                                  ", expected a Point (with a depth range) or a LineString Z");
    }
    for (const Point3& p : w.pts)
      if (!std::isfinite(p.x) || !std::isfinite(p.y))
        throw Error(ExitCode::kInvalidGeometry, w.where + ": a coordinate is not a finite number");
    out.wells.push_back(std::move(w));
  }
  if (out.wells.empty()) throw Error(ExitCode::kUsage, label + " has no features");
  return out;
}

struct DatasetWriter {
  GDALDataset* ds = nullptr;
  ~DatasetWriter() { if (ds) GDALClose(GDALDataset::ToHandle(ds)); }
};

}  // namespace

MemLayer::~MemLayer() {
  if (!path_.empty()) VSIUnlink(path_.c_str());
}

MemLayer& MemLayer::operator=(MemLayer&& o) noexcept {
  if (this != &o) {
    if (!path_.empty()) VSIUnlink(path_.c_str());
    path_ = std::move(o.path_);
    o.path_.clear();
  }
  return *this;
}

std::vector<Well> read_wells(const WellsSource& src, const gis::Frame& frame, double max_offset) {
  RawWells raw = read_raw(src);
  std::vector<Point2> xy;
  for (const RawWell& w : raw.wells)
    for (const Point3& p : w.pts) xy.push_back({p.x, p.y});
  frame.to_local_batch(xy, raw.srs, "--wells " + src.path);
  std::vector<Well> out;
  std::size_t k = 0;
  for (const RawWell& r : raw.wells) {
    Well w;
    w.name = r.name;
    w.where = r.where;
    w.kind = r.kind;
    w.upper = r.upper;
    w.lower = r.lower;
    w.xy = xy[k];
    for (std::size_t i = 0; i < r.pts.size(); ++i, ++k)
      if (std::hypot(xy[k].x - w.xy.x, xy[k].y - w.xy.y) > max_offset)
        throw Error(ExitCode::kInvalidGeometry, r.where + ": the line's vertex " + std::to_string(i) + " lies " +
                                                    num(std::hypot(xy[k].x - w.xy.x, xy[k].y - w.xy.y)) +
                                                    " m from its first in plan (more than " + num(max_offset) +
                                                    " m): only vertical wells are modelled");
    out.push_back(std::move(w));
  }
  return out;
}

MemLayer wells_point_layer(const WellsSource& src) {
  const RawWells raw = read_raw(src);
  gis::GdalQuiet quiet;
  GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("FlatGeobuf");
  if (!drv) throw Error(ExitCode::kInternal, "GDAL has no FlatGeobuf driver");
  MemLayer mem(mem_path("wells", "fgb"));
  DatasetWriter w;
  w.ds = drv->Create(mem.path().c_str(), 0, 0, 0, GDT_Unknown, nullptr);
  OGRSpatialReference srs(raw.srs);
  OGRLayer* lyr = w.ds ? w.ds->CreateLayer("wells", &srs, wkbPoint, nullptr) : nullptr;
  if (!lyr) throw Error(ExitCode::kInternal, "cannot make the in-memory wells layer: " + std::string(CPLGetLastErrorMsg()));
  for (const RawWell& r : raw.wells) {
    OGRFeature f(lyr->GetLayerDefn());
    OGRPoint p(r.pts.front().x, r.pts.front().y);  // binary doubles: the 2D run reads them back exactly
    f.SetGeometry(&p);
    if (lyr->CreateFeature(&f) != OGRERR_NONE)
      throw Error(ExitCode::kInternal, "cannot write the in-memory wells layer: " + std::string(CPLGetLastErrorMsg()));
  }
  return mem;
}

std::pair<std::size_t, double> nearest_vertex(const std::vector<Point2>& xy, Point2 p) {
  std::pair<std::size_t, double> best{xy.size(), std::numeric_limits<double>::infinity()};
  for (std::size_t i = 0; i < xy.size(); ++i) {
    const double dx = xy[i].x - p.x, dy = xy[i].y - p.y, d2 = dx * dx + dy * dy;
    if (d2 < best.second) best = {i, d2};
  }
  return best;
}

void write_wells_layer(const std::string& path, const std::string& crs_wkt, const std::vector<WellLine>& wells) {
  gis::ensure_gdal_registered();
  gis::GdalQuiet quiet;
  auto fail = [&](const std::string& what) {
    throw Error(ExitCode::kOutputError, path + ": " + what + ": " + CPLGetLastErrorMsg());
  };
  DatasetWriter w;
  w.ds = GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_UPDATE);
  if (!w.ds) fail("cannot open the GeoPackage to add the wells");
  OGRSpatialReference srs;
  if (srs.SetFromUserInput(crs_wkt.c_str()) != OGRERR_NONE) fail("unknown CRS of the wells layer");
  srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  char* opts[] = {const_cast<char*>("OVERWRITE=YES"), nullptr};
  OGRLayer* lyr = w.ds->CreateLayer("wells", &srs, wkbLineString25D, opts);
  if (!lyr) fail("cannot create the layer wells");
  OGRFieldDefn name("name", OFTString), top("top", OFTReal), bottom("bottom", OFTReal);
  if (lyr->CreateField(&name) != OGRERR_NONE || lyr->CreateField(&top) != OGRERR_NONE ||
      lyr->CreateField(&bottom) != OGRERR_NONE)
    fail("cannot create the fields of the layer wells");
  if (lyr->StartTransaction() != OGRERR_NONE) fail("cannot write the layer wells");
  for (const WellLine& wl : wells) {
    OGRFeature f(lyr->GetLayerDefn());
    OGRLineString l;
    l.addPoint(wl.line[0].x, wl.line[0].y, wl.line[0].z);
    l.addPoint(wl.line[1].x, wl.line[1].y, wl.line[1].z);
    f.SetGeometry(&l);
    f.SetField("name", wl.name.c_str());
    f.SetField("top", wl.line[0].z);
    f.SetField("bottom", wl.line[1].z);
    if (lyr->CreateFeature(&f) != OGRERR_NONE) fail("cannot write a well");
  }
  if (lyr->CommitTransaction() != OGRERR_NONE) fail("cannot write the layer wells");
}

MemLayer dem_extent_layer(const std::string& dem, const std::string& option) {
  gis::ensure_gdal_registered();
  gis::GdalQuiet quiet;
  const std::string label = option + " " + dem;
  gis::DatasetPtr src = gis::open_raster(dem);
  if (src->GetRasterCount() < 1) throw Error(ExitCode::kInputUnreadable, label + ": raster has no band");
  const OGRSpatialReference* rs = src->GetSpatialRef();
  if (!rs || rs->IsEmpty()) throw Error(ExitCode::kCrsError, label + ": the raster has no CRS");
  double gt[6];
  if (src->GetGeoTransform(gt) != CE_None) throw Error(ExitCode::kInputUnreadable, label + ": raster has no geotransform");
  GDALRasterBand* band = src->GetRasterBand(1);
  const int nx = src->GetRasterXSize(), ny = src->GetRasterYSize();
  int has_nodata = 0;
  const double nodata = band->GetNoDataValue(&has_nodata);
  int i0 = nx, i1 = -1, j0 = ny, j1 = -1;
  std::vector<double> row(static_cast<std::size_t>(nx));
  for (int j = 0; j < ny; ++j) {
    if (band->RasterIO(GF_Read, 0, j, nx, 1, row.data(), nx, 1, GDT_Float64, 0, 0) != CE_None)
      throw Error(ExitCode::kInputUnreadable, label + ": cannot read row " + std::to_string(j));
    for (int i = 0; i < nx; ++i) {
      const double v = row[static_cast<std::size_t>(i)];
      if (!std::isfinite(v) || (has_nodata && v == nodata)) continue;
      i0 = std::min(i0, i), i1 = std::max(i1, i), j0 = std::min(j0, j), j1 = std::max(j1, j);
    }
  }
  if (i1 < 0) throw Error(ExitCode::kInvalidSpacing, label + ": the raster has no valid cell (all nodata)");
  if (i1 == i0 || j1 == j0)
    throw Error(ExitCode::kInvalidSpacing, label + ": the valid data is one cell wide; no domain to mesh");
  auto at = [&](double pi, double pj) {  // pixel/line (cell corners at integers) -> georeferenced
    return std::array<double, 2>{gt[0] + pi * gt[1] + pj * gt[2], gt[3] + pi * gt[4] + pj * gt[5]};
  };
  const double a = i0 + 0.5, b = i1 + 0.5, c = j0 + 0.5, d = j1 + 0.5;  // cell centres
  OGRLinearRing ring;
  for (const auto& [pi, pj] : std::array<std::array<double, 2>, 5>{{{a, c}, {b, c}, {b, d}, {a, d}, {a, c}}}) {
    const auto p = at(pi, pj);
    ring.addPoint(p[0], p[1]);
  }
  OGRPolygon poly;
  poly.addRing(&ring);
  GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("FlatGeobuf");
  if (!drv) throw Error(ExitCode::kInternal, "GDAL has no FlatGeobuf driver");
  MemLayer mem(mem_path("dem_extent", "fgb"));
  DatasetWriter w;
  w.ds = drv->Create(mem.path().c_str(), 0, 0, 0, GDT_Unknown, nullptr);
  OGRSpatialReference srs(*rs);
  OGRLayer* lyr = w.ds ? w.ds->CreateLayer("dem_extent", &srs, wkbPolygon, nullptr) : nullptr;
  if (!lyr) throw Error(ExitCode::kInternal, "cannot make the DEM's extent layer: " + std::string(CPLGetLastErrorMsg()));
  OGRFeature f(lyr->GetLayerDefn());
  if (f.SetGeometry(&poly) != OGRERR_NONE || lyr->CreateFeature(&f) != OGRERR_NONE)
    throw Error(ExitCode::kInternal, "cannot make the DEM's extent layer: " + std::string(CPLGetLastErrorMsg()));
  return mem;
}

}  // namespace fdr::terrain
