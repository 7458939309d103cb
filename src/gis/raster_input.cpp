// Raster input: GDAL open helpers, warping band 1 into the frame, depth sampling, cell size hint.
#include "gis/raster_input.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <mutex>
#include <numbers>

#include <gdal_alg.h>
#include <gdal_priv.h>
#include <gdalwarper.h>
#include <ogr_spatialref.h>

#include "base/error.hpp"
#include "gis/gdal_util.hpp"

namespace fdr::gis {

void ensure_gdal_registered() {
  static std::once_flag once;
  std::call_once(once, [] { GDALAllRegister(); });
}

namespace {

DatasetPtr open_any(const std::string& path, unsigned flags, const char* kind) {
  ensure_gdal_registered();
  // VSIStatL: plain files and GDAL virtual paths (/vsimem/, /vsizip/, ...) alike.
  VSIStatBufL st;
  if (VSIStatL(path.c_str(), &st) != 0)
    throw Error(ExitCode::kInputUnreadable, path + ": cannot open (no such file)");
  GdalQuiet quiet;
  CPLErrorReset();
  DatasetPtr ds(GDALDataset::Open(path.c_str(), flags | GDAL_OF_READONLY));
  if (!ds) {
    std::string msg = CPLGetLastErrorMsg();
    throw Error(ExitCode::kInputUnreadable,
                path + ": cannot open as a " + kind + " dataset" + (msg.empty() ? "" : ": " + msg));
  }
  return ds;
}

std::string num(double v, int prec = 6) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", prec, v);
  return buf;
}

OGRSpatialReference raster_srs(GDALDataset& ds, const std::string& path) {
  const OGRSpatialReference* s = ds.GetSpatialRef();
  if (!s || s->IsEmpty()) throw Error(ExitCode::kCrsError, path + ": raster has no CRS");
  OGRSpatialReference out(*s);
  out.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  return out;
}

// Warps band 1 of src into the (MEM, Float64, NaN-nodata) dataset dst, bilinear; cells that
// no source pixel reaches stay NaN.
void warp_band1(GDALDataset& src_ds, GDALDataset& dst_ds, const std::string& path, const std::string& target) {
  GDALRasterBand* sb = src_ds.GetRasterBand(1);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  dst_ds.GetRasterBand(1)->SetNoDataValue(nan);
  {
    GdalQuiet quiet;
    CPLErrorReset();
    GDALWarpOptions* wo = GDALCreateWarpOptions();
    wo->hSrcDS = GDALDataset::ToHandle(&src_ds);
    wo->hDstDS = GDALDataset::ToHandle(&dst_ds);
    wo->nBandCount = 1;
    wo->panSrcBands = static_cast<int*>(CPLMalloc(sizeof(int)));
    wo->panDstBands = static_cast<int*>(CPLMalloc(sizeof(int)));
    wo->panSrcBands[0] = 1;
    wo->panDstBands[0] = 1;
    wo->eResampleAlg = GRA_Bilinear;
    wo->eWorkingDataType = GDT_Float64;
    int has_nodata = 0;
    const double nd = sb->GetNoDataValue(&has_nodata);
    if (has_nodata) {
      wo->padfSrcNoDataReal = static_cast<double*>(CPLMalloc(sizeof(double)));
      wo->padfSrcNoDataReal[0] = nd;
    }
    wo->padfDstNoDataReal = static_cast<double*>(CPLMalloc(sizeof(double)));
    wo->padfDstNoDataReal[0] = nan;
    wo->papszWarpOptions = CSLSetNameValue(wo->papszWarpOptions, "INIT_DEST", "NO_DATA");
    wo->pTransformerArg = GDALCreateGenImgProjTransformer2(wo->hSrcDS, wo->hDstDS, nullptr);
    if (!wo->pTransformerArg) {
      GDALDestroyWarpOptions(wo);
      throw Error(ExitCode::kCrsError, path + ": cannot build a transformation to " + target + ": " +
                                           CPLGetLastErrorMsg());
    }
    wo->pfnTransformer = GDALGenImgProjTransform;
    GDALWarpOperation op;
    CPLErr err = op.Initialize(wo);
    if (err == CE_None) err = op.ChunkAndWarpImage(0, 0, dst_ds.GetRasterXSize(), dst_ds.GetRasterYSize());
    GDALDestroyGenImgProjTransformer(wo->pTransformerArg);
    GDALDestroyWarpOptions(wo);
    if (err != CE_None)
      throw Error(ExitCode::kInputUnreadable, path + ": warping to " + target + " failed: " + CPLGetLastErrorMsg());
  }

}

}  // namespace

DatasetPtr open_vector(const std::string& path) { return open_any(path, GDAL_OF_VECTOR, "vector"); }
DatasetPtr open_raster(const std::string& path) { return open_any(path, GDAL_OF_RASTER, "raster"); }

sizing::Grid read_raster_to_frame(const std::string& path, const Frame& frame, Box2 box, double cell_m,
                                  const std::vector<Point2>* must_cover) {
  if (!(cell_m > 0) || !std::isfinite(cell_m))
    throw Error(ExitCode::kInvalidSpacing, path + ": raster cell size must be > 0 (got " + num(cell_m) + ")");
  if (box.empty()) throw Error(ExitCode::kInternal, "read_raster_to_frame: empty domain box");
  DatasetPtr src = open_raster(path);
  if (src->GetRasterCount() < 1) throw Error(ExitCode::kInputUnreadable, path + ": raster has no band");
  OGRSpatialReference rs = raster_srs(*src, path);
  double gt[6];
  if (src->GetGeoTransform(gt) != CE_None)
    throw Error(ExitCode::kInputUnreadable, path + ": raster has no geotransform");
  double inv[6];
  if (!GDALInvGeoTransform(gt, inv)) throw Error(ExitCode::kInputUnreadable, path + ": singular geotransform");
  const double W = src->GetRasterXSize(), H = src->GetRasterYSize();

  // Coverage: map the probes (the given points, or the box outline with 33 points per side,
  // corners first) to pixel coordinates and require them inside the raster's pixel-edge extent.
  {
    GdalQuiet quiet;
    std::unique_ptr<OGRCoordinateTransformation, void (*)(OGRCoordinateTransformation*)> ct(
        OGRCreateCoordinateTransformation(&frame.srs(), &rs), OGRCoordinateTransformation::DestroyCT);
    if (!ct) throw Error(ExitCode::kCrsError, path + ": no transformation from " + frame.name() + " to the raster's CRS");
    const bool corners = must_cover == nullptr;
    std::vector<Point2> probe;
    if (corners) {
      probe = {box.lo, {box.hi.x, box.lo.y}, box.hi, {box.lo.x, box.hi.y}};
      const int n = 32;
      for (int k = 0; k < 4; ++k)
        for (int s = 1; s < n; ++s) probe.push_back(probe[k] + (double(s) / n) * (probe[(k + 1) % 4] - probe[k]));
    } else {
      probe = *must_cover;
    }
    std::vector<double> x(probe.size()), y(probe.size());
    std::vector<int> ok(probe.size(), 0);
    for (std::size_t i = 0; i < probe.size(); ++i) {
      const Point2 w = frame.to_world(probe[i]);
      x[i] = w.x;
      y[i] = w.y;
    }
    if (!probe.empty()) ct->Transform(static_cast<int>(probe.size()), x.data(), y.data(), nullptr, ok.data());
    std::string bad;
    std::size_t n_bad = 0, n_named = 0;
    const double tol = 1e-6;  // pixels
    static const char* kCorner[4] = {"south-west", "south-east", "north-east", "north-west"};
    for (std::size_t i = 0; i < probe.size(); ++i) {
      bool inside = ok[i] && std::isfinite(x[i]) && std::isfinite(y[i]);
      if (inside) {
        const double px = inv[0] + inv[1] * x[i] + inv[2] * y[i], py = inv[3] + inv[4] * x[i] + inv[5] * y[i];
        inside = px >= -tol && px <= W + tol && py >= -tol && py <= H + tol;
      }
      if (inside) continue;
      ++n_bad;
      // Name every uncovered corner; other points only while fewer than 3 places are named.
      if ((corners && i < 4) || n_named < 3) {
        const LonLat ll = frame.to_lonlat(probe[i]);
        const std::string what = corners ? (i < 4 ? kCorner[i] : "edge point") : "domain vertex " + std::to_string(i);
        bad += (bad.empty() ? "" : "; ") + what + " (" + num(ll.lon_deg) + ", " + num(ll.lat_deg) + ")";
        ++n_named;
      }
    }
    if (n_bad > 0)
      throw Error(ExitCode::kInvalidSpacing, path + ": raster does not cover the domain; uncovered: " + bad +
                                                 (corners ? "" : " (" + std::to_string(n_bad) + " of " +
                                                                     std::to_string(probe.size()) + " vertices)"));
  }

  sizing::Grid g;
  g.dx = g.dy = cell_m;
  const double nxd = std::ceil(box.width() / cell_m) + 2, nyd = std::ceil(box.height() / cell_m) + 2;
  if (nxd * nyd > 16e6)
    throw Error(ExitCode::kWorkLimit, path + ": a " + num(cell_m, 3) + " m grid over the domain would have " +
                                          num(nxd * nyd, 0) + " cells (limit 16M); use a larger cell size");
  g.nx = static_cast<std::size_t>(nxd);
  g.ny = static_cast<std::size_t>(nyd);
  // Centre the grid on the box: one extra cell beyond each side.
  g.x0 = box.center().x - 0.5 * nxd * cell_m;
  g.y0 = box.center().y - 0.5 * nyd * cell_m;

  GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
  if (!mem) throw Error(ExitCode::kInternal, "GDAL MEM driver missing");
  DatasetPtr dst(mem->Create("", static_cast<int>(g.nx), static_cast<int>(g.ny), 1, GDT_Float64, nullptr));
  const Point2 o = frame.origin();
  double dgt[6] = {o.x + g.x0, cell_m, 0, o.y + g.y0 + nyd * cell_m, 0, -cell_m};
  dst->SetGeoTransform(dgt);
  dst->SetSpatialRef(&frame.srs());
  GDALRasterBand* sb = src->GetRasterBand(1);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  warp_band1(*src, *dst, path, frame.name());

  std::vector<double> buf(g.nx * g.ny);
  if (dst->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, static_cast<int>(g.nx), static_cast<int>(g.ny), buf.data(),
                                      static_cast<int>(g.nx), static_cast<int>(g.ny), GDT_Float64, 0, 0) != CE_None)
    throw Error(ExitCode::kInternal, path + ": reading the warped grid failed");
  int has_scale = 0, has_offset = 0;
  double scale = sb->GetScale(&has_scale), offset = sb->GetOffset(&has_offset);
  if (!has_scale) scale = 1;
  if (!has_offset) offset = 0;
  g.v.resize(buf.size());
  std::size_t n_valid = 0;
  // GDAL row 0 is the northern edge; Grid row 0 is the southern one.
  for (std::size_t r = 0; r < g.ny; ++r)
    for (std::size_t i = 0; i < g.nx; ++i) {
      double v = buf[r * g.nx + i];
      if (std::isfinite(v)) { v = v * scale + offset; ++n_valid; } else { v = nan; }
      g.at(i, g.ny - 1 - r) = v;
    }
  if (n_valid == 0) {
    const LonLat a = frame.to_lonlat(box.lo), b = frame.to_lonlat(box.hi);
    throw Error(ExitCode::kInvalidSpacing, path + ": nodata everywhere over the domain (" + num(a.lon_deg) + ", " +
                                               num(a.lat_deg) + ") - (" + num(b.lon_deg) + ", " + num(b.lat_deg) + ")");
  }
  return g;
}

namespace {

// Reads band 1 of a north-up dataset into a Grid (row 0 = south) and applies scale/offset.
// Scale and offset come from `meta` (the original band when ds is a resampled copy).
sizing::Grid read_north_up(GDALDataset& ds, const std::string& path, const double gt[6], Point2 origin,
                           GDALRasterBand& meta) {
  const std::size_t nx = static_cast<std::size_t>(ds.GetRasterXSize()), ny = static_cast<std::size_t>(ds.GetRasterYSize());
  if (double(nx) * double(ny) > 16e6)
    throw Error(ExitCode::kWorkLimit, path + ": " + std::to_string(nx) + " x " + std::to_string(ny) +
                                          " cells (limit 16M); resample the raster first");
  GDALRasterBand* b = ds.GetRasterBand(1);
  std::vector<double> buf(nx * ny);
  {
    GdalQuiet quiet;
    if (b->RasterIO(GF_Read, 0, 0, static_cast<int>(nx), static_cast<int>(ny), buf.data(), static_cast<int>(nx),
                    static_cast<int>(ny), GDT_Float64, 0, 0) != CE_None)
      throw Error(ExitCode::kInputUnreadable, path + ": cannot read band 1: " + CPLGetLastErrorMsg());
  }
  int has_nd = 0, has_scale = 0, has_offset = 0;
  const double nd = b->GetNoDataValue(&has_nd);
  double scale = meta.GetScale(&has_scale), offset = meta.GetOffset(&has_offset);
  if (!has_scale) scale = 1;
  if (!has_offset) offset = 0;
  sizing::Grid g;
  g.nx = nx;
  g.ny = ny;
  g.dx = gt[1];
  g.dy = std::abs(gt[5]);
  g.x0 = gt[0] - origin.x;
  const bool north_up = gt[5] < 0;
  g.y0 = (north_up ? gt[3] + gt[5] * double(ny) : gt[3]) - origin.y;
  g.v.resize(nx * ny);
  std::size_t n_valid = 0;
  for (std::size_t r = 0; r < ny; ++r)
    for (std::size_t i = 0; i < nx; ++i) {
      double v = buf[r * nx + i];
      // Float nodata equality is exact on purpose: GDAL stores the very value it compares.
      if (!std::isfinite(v) || (has_nd && v == nd)) v = std::numeric_limits<double>::quiet_NaN();
      else { v = v * scale + offset; ++n_valid; }
      g.at(i, north_up ? ny - 1 - r : r) = v;
    }
  if (n_valid == 0) throw Error(ExitCode::kInvalidSpacing, path + ": nodata everywhere");
  return g;
}

// Value of the valid cell nearest to p (cell centres, Euclidean in cell units scaled by dx, dy).
// Why the search continues past the first hit: a ring of Chebyshev radius r can hold a cell at
// Euclidean distance up to r*sqrt(2), so rings up to that radius may still hold a closer one.
double nearest_valid(const sizing::Grid& g, Point2 p) {
  const long nx = static_cast<long>(g.nx), ny = static_cast<long>(g.ny);
  const long ic = std::clamp(static_cast<long>(std::floor((p.x - g.x0) / g.dx)), 0L, nx - 1);
  const long jc = std::clamp(static_cast<long>(std::floor((p.y - g.y0) / g.dy)), 0L, ny - 1);
  double best = std::numeric_limits<double>::infinity(), best_v = std::nan("");
  long stop = std::max(nx, ny);
  for (long r = 0; r <= stop; ++r) {
    for (long j = jc - r; j <= jc + r; ++j) {
      if (j < 0 || j >= ny) continue;
      const bool edge_row = (j == jc - r || j == jc + r);
      for (long i = ic - r; i <= ic + r; i += (edge_row ? 1 : 2 * r)) {
        if (i >= 0 && i < nx) {
          const double v = g.at(static_cast<std::size_t>(i), static_cast<std::size_t>(j));
          if (std::isfinite(v)) {
            const double d = norm2(g.center(static_cast<std::size_t>(i), static_cast<std::size_t>(j)) - p);
            if (d < best) { best = d; best_v = v; }
          }
        }
        if (r == 0) break;
      }
    }
    if (std::isfinite(best) && stop == std::max(nx, ny)) stop = static_cast<long>(std::ceil(r * std::sqrt(2.0))) + 1;
  }
  return best_v;
}

}  // namespace

sizing::Grid read_raster_native(const std::string& path, Point2 origin) {
  DatasetPtr src = open_raster(path);
  if (src->GetRasterCount() < 1) throw Error(ExitCode::kInputUnreadable, path + ": raster has no band");
  double gt[6];
  if (src->GetGeoTransform(gt) != CE_None)
    throw Error(ExitCode::kInputUnreadable, path + ": raster has no geotransform");
  GDALRasterBand& band = *src->GetRasterBand(1);
  if (gt[2] == 0 && gt[4] == 0 && gt[1] > 0) return read_north_up(*src, path, gt, origin, band);
  // Rotated or mirrored: resample north-up in the raster's own CRS at about its resolution.
  void* tr = GDALCreateGenImgProjTransformer2(GDALDataset::ToHandle(src.get()), nullptr, nullptr);
  if (!tr) throw Error(ExitCode::kInputUnreadable, path + ": cannot georeference the rotated raster");
  double ogt[6];
  int onx = 0, ony = 0;
  const CPLErr e = GDALSuggestedWarpOutput(GDALDataset::ToHandle(src.get()), GDALGenImgProjTransform, tr, ogt, &onx, &ony);
  GDALDestroyGenImgProjTransformer(tr);
  if (e != CE_None || onx <= 0 || ony <= 0)
    throw Error(ExitCode::kInputUnreadable, path + ": cannot resample the rotated raster north-up");
  if (double(onx) * double(ony) > 16e6)
    throw Error(ExitCode::kWorkLimit, path + ": resampled north-up it would have " + std::to_string(onx) + " x " +
                                          std::to_string(ony) + " cells (limit 16M)");
  GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
  DatasetPtr dst(mem->Create("", onx, ony, 1, GDT_Float64, nullptr));
  dst->SetGeoTransform(ogt);
  if (const OGRSpatialReference* s = src->GetSpatialRef()) dst->SetSpatialRef(s);
  warp_band1(*src, *dst, path, "a north-up grid");
  return read_north_up(*dst, path, ogt, origin, band);
}

std::vector<double> sample_depths(const sizing::Grid& g, const std::vector<Point2>& nodes, int* n_filled) {
  if (n_filled) *n_filled = 0;
  bool any = false;
  for (double v : g.v)
    if (std::isfinite(v)) { any = true; break; }
  if (!any || g.nx == 0 || g.ny == 0) throw Error(ExitCode::kInvalidSpacing, "depth grid has no valid cell");
  std::vector<double> out(nodes.size());
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    const Point2 p = nodes[k];
    const double u = std::clamp((p.x - g.x0) / g.dx - 0.5, 0.0, double(g.nx - 1));
    const double v = std::clamp((p.y - g.y0) / g.dy - 0.5, 0.0, double(g.ny - 1));
    const std::size_t i = std::min(static_cast<std::size_t>(u), g.nx > 1 ? g.nx - 2 : 0);
    const std::size_t j = std::min(static_cast<std::size_t>(v), g.ny > 1 ? g.ny - 2 : 0);
    const std::size_t i1 = std::min(i + 1, g.nx - 1), j1 = std::min(j + 1, g.ny - 1);
    const double s = u - double(i), t = v - double(j);
    const double z = (1 - t) * ((1 - s) * g.at(i, j) + s * g.at(i1, j)) + t * ((1 - s) * g.at(i, j1) + s * g.at(i1, j1));
    if (std::isfinite(z)) {
      out[k] = z;
    } else {
      out[k] = nearest_valid(g, p);
      if (n_filled) ++*n_filled;
    }
  }
  return out;
}

double grid_cell_size_hint(const std::string& path, const Frame& frame, Box2 box, double max_cells) {
  DatasetPtr src = open_raster(path);
  OGRSpatialReference rs = raster_srs(*src, path);
  double gt[6];
  if (src->GetGeoTransform(gt) != CE_None)
    throw Error(ExitCode::kInputUnreadable, path + ": raster has no geotransform");
  const double px = std::hypot(gt[1], gt[4]), py = std::hypot(gt[2], gt[5]);
  double mx, my;
  if (rs.IsGeographic()) {
    // Degrees (angular units) to metres at the box centre on the WGS 84 mean radius.
    const double rad = rs.GetAngularUnits(nullptr);
    const double lat = frame.to_lonlat(box.center()).lat_deg * std::numbers::pi / 180.0;
    const double R = 6371008.8;
    mx = px * rad * R * std::cos(lat);
    my = py * rad * R;
  } else {
    const double unit = rs.GetLinearUnits(nullptr);
    mx = px * unit;
    my = py * unit;
  }
  double cell = std::min(mx, my);
  if (!(cell > 0) || !std::isfinite(cell)) cell = std::max(box.width(), box.height()) / 100.0;
  const double area = std::max(box.width(), cell) * std::max(box.height(), cell);
  cell = std::max(cell, std::sqrt(area / max_cells));
  return cell;
}

}  // namespace fdr::gis
