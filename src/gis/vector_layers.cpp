// Reading OGR layers for the vector input (vector_layers.hpp).
#include "gis/vector_layers.hpp"

#include <cmath>
#include <cstdio>

#include <cpl_error.h>
#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include "base/error.hpp"
#include "gis/gdal_util.hpp"
#include "gis/pg_open.hpp"

namespace fdr::gis {

std::string num(double v, int prec) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", prec, v);
  return buf;
}

std::string where_str(const OGRGeometry* g) {
  if (!g || g->IsEmpty()) return "(empty geometry)";
  OGREnvelope e;
  g->getEnvelope(&e);
  return "at (" + num(0.5 * (e.MinX + e.MaxX)) + ", " + num(0.5 * (e.MinY + e.MaxY)) + ")";
}

namespace {

// Refuses a vertex with a NaN, infinite or out-of-range coordinate, naming layer, feature id,
// part (member of a multi-geometry / collection), ring (polygons: 0 = outer), vertex index and
// value. Why here: a bad coordinate otherwise surfaces as a misleading CRS error later ("the
// domain spans 1e308 degrees of longitude"). Ranges: a geographic CRS needs |lon| <= 180,
// |lat| <= 90; a projected one |v| <= 1e9 (beyond the Earth in metres or feet) and, when the CRS
// knows its area of use, within that area's projected bounding box widened by its own size.
struct CoordLimits {
  bool geographic = false;
  double xmin = -1e9, xmax = 1e9, ymin = -1e9, ymax = 1e9;
  std::string what = "|x|, |y| <= 1e9";
};

CoordLimits coord_limits(const OGRSpatialReference& srs) {
  CoordLimits c;
  if (srs.IsGeographic()) {
    c.geographic = true;
    c.xmin = -180, c.xmax = 180, c.ymin = -90, c.ymax = 90;
    c.what = "longitude within [-180, 180] and latitude within [-90, 90]";
    return c;
  }
  double w = 0, s = 0, e = 0, n = 0;
  const char* name = nullptr;
  if (!srs.GetAreaOfUse(&w, &s, &e, &n, &name) || !(w >= -180 && e <= 180 && s >= -90 && n <= 90 && s < n)) return c;
  OGRSpatialReference ll;
  ll.SetWellKnownGeogCS("WGS84");
  ll.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  OGRSpatialReference dst(srs);
  dst.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<OGRCoordinateTransformation, void (*)(OGRCoordinateTransformation*)> ct(
      OGRCreateCoordinateTransformation(&ll, &dst), OGRCoordinateTransformation::DestroyCT);
  if (!ct) return c;
  const double east = e >= w ? e : e + 360;  // area crossing the antimeridian
  std::vector<double> xs, ys;
  for (int i = 0; i <= 16; ++i)
    for (int j = 0; j <= 16; ++j) {
      double lon = w + (east - w) * i / 16.0;
      if (lon > 180) lon -= 360;
      xs.push_back(lon);
      ys.push_back(s + (n - s) * j / 16.0);
    }
  std::vector<int> ok(xs.size(), 0);
  ct->Transform(static_cast<int>(xs.size()), xs.data(), ys.data(), nullptr, ok.data());
  Box2 b;
  for (std::size_t k = 0; k < xs.size(); ++k)
    if (ok[k] && std::isfinite(xs[k]) && std::isfinite(ys[k])) b.add({xs[k], ys[k]});
  if (!(b.width() > 0 && b.height() > 0)) return c;
  const double m = std::max(b.width(), b.height());
  c.xmin = std::max(c.xmin, b.lo.x - m), c.xmax = std::min(c.xmax, b.hi.x + m);
  c.ymin = std::max(c.ymin, b.lo.y - m), c.ymax = std::min(c.ymax, b.hi.y + m);
  std::string area = name ? name : "";
  if (area.size() > 48) area = area.substr(0, 45) + "...";
  c.what = "within the CRS's area of use" + (area.empty() ? std::string() : " (" + area + ")") +
           ", widened by its size: x in [" + num(c.xmin) + ", " + num(c.xmax) + "], y in [" + num(c.ymin) + ", " +
           num(c.ymax) + "]";
  return c;
}

void check_coordinates(const OGRGeometry* g, const CoordLimits& lim, const std::string& label, std::int64_t fid,
                       const std::string& where) {
  auto bad = [&](double v, double lo, double hi) { return !std::isfinite(v) || v < lo || v > hi; };
  auto check_curve = [&](const OGRSimpleCurve* c, const std::string& at) {
    for (int i = 0; i < c->getNumPoints(); ++i) {
      const double x = c->getX(i), y = c->getY(i);
      const bool bx = bad(x, lim.xmin, lim.xmax), by = bad(y, lim.ymin, lim.ymax);
      if (!bx && !by) continue;
      const char* axis = bx ? (lim.geographic ? "longitude" : "x") : (lim.geographic ? "latitude" : "y");
      char v[48];
      std::snprintf(v, sizeof v, "%.17g", bx ? x : y);
      throw Error(ExitCode::kInvalidGeometry,
                  label + ", feature FID " + std::to_string(fid) + at + ", vertex " + std::to_string(i) + ": " +
                      axis + " = " + v + " is " + (std::isfinite(bx ? x : y) ? "out of range (need " + lim.what + ")"
                                                                             : std::string("not a finite number")));
    }
  };
  const auto t = wkbFlatten(g->getGeometryType());
  if (t == wkbPoint) {
    const auto* p = g->toPoint();
    OGRLineString l;
    l.addPoint(p->getX(), p->getY());
    check_curve(&l, where);
  } else if (t == wkbLineString || t == wkbLinearRing) {
    check_curve(g->toSimpleCurve(), where);
  } else if (t == wkbPolygon || t == wkbTriangle) {
    int r = 0;
    for (const OGRLinearRing* ring : *g->toPolygon()) {
      check_curve(ring, where + ", ring " + std::to_string(r) + (r == 0 ? " (outer)" : " (hole)"));
      ++r;
    }
  } else if (OGR_GT_IsSubClassOf(t, wkbGeometryCollection) || t == wkbPolyhedralSurface || t == wkbTIN) {
    int k = 0;
    const OGRGeometryCollection* gc = t == wkbPolyhedralSurface || t == wkbTIN ? nullptr : g->toGeometryCollection();
    if (!gc) return;
    for (const auto* sub : *gc) check_coordinates(sub, lim, label, fid, where + ", part " + std::to_string(k++));
  }
}

}  // namespace

OpenedLayer open_layer(const std::string& path, const std::string& layer) {
  OpenedLayer o;
  o.source = source_label(path);  // a "PG:" database without its password
  o.ds = is_pg_connection(path) ? open_pg_vector(path) : open_vector(path);
  if (layer.empty()) {
    if (o.ds->GetLayerCount() == 0) throw Error(ExitCode::kInputUnreadable, o.source + ": no layers");
    o.layer = o.ds->GetLayer(0);
  } else {
    o.layer = o.ds->GetLayerByName(layer.c_str());
    if (!o.layer) {
      std::string names;
      for (int i = 0; i < o.ds->GetLayerCount(); ++i)
        names += (i ? ", " : "") + std::string(o.ds->GetLayer(i)->GetName());
      throw Error(ExitCode::kInputUnreadable, o.source + ": no layer '" + layer + "' (layers: " + names + ")");
    }
  }
  if (is_pg_connection(path)) check_pg_layer(*o.layer, path);
  return o;
}

LayerData read_layer(const LayerRef& ref, const std::string& s_srs, const char* option) {
  GdalQuiet quiet;
  const OpenedLayer opened = open_layer(ref.path, ref.layer);
  OGRLayer* lyr = opened.layer;
  const std::string& name = opened.source;
  LayerData out;
  out.file = name;
  out.layer = lyr->GetName();
  if (!ref.where.empty() && lyr->SetAttributeFilter(ref.where.c_str()) != OGRERR_NONE)
    throw Error(ExitCode::kUsage, out.label() + ": invalid " + option + " where clause '" + ref.where +
                                      "': " + CPLGetLastErrorMsg());
  const OGRSpatialReference* srs = lyr->GetSpatialRef();
  if (srs) {
    out.srs = *srs;
  } else if (!s_srs.empty()) {
    if (out.srs.SetFromUserInput(s_srs.c_str()) != OGRERR_NONE)
      throw Error(ExitCode::kCrsError, "--s_srs '" + s_srs + "': unknown CRS");
  } else {
    throw Error(ExitCode::kCrsError, out.label() + " has no CRS; give --s_srs");
  }
  out.srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  const CoordLimits limits = coord_limits(out.srs);
  lyr->ResetReading();
  CPLErrorReset();
  for (auto& f : *lyr) {
    const OGRGeometry* g = f->GetGeometryRef();
    if (!g || g->IsEmpty()) continue;
    Feature feat;
    feat.fid = f->GetFID();
    feat.geom.reset(g->hasCurveGeometry() ? g->getLinearGeometry() : g->clone());
    feat.geom->flattenTo2D();
    check_coordinates(feat.geom.get(), limits, out.label(), feat.fid, "");
    out.features.push_back(std::move(feat));
  }
  if (CPLGetLastErrorType() >= CE_Failure) {
    const std::string msg = CPLGetLastErrorMsg();
    if (!ref.where.empty())
      throw Error(ExitCode::kUsage, out.label() + ": invalid " + option + " where clause '" + ref.where + "': " + msg);
    throw Error(ExitCode::kInputMalformed, out.label() + ": reading features failed: " + msg);
  }
  if (out.features.empty()) {
    if (!ref.where.empty())
      throw Error(ExitCode::kInvalidGeometry, out.label() + ": " + option + " where clause '" + ref.where +
                                                  "' selects no features with a geometry");
    throw Error(ExitCode::kInvalidGeometry, out.label() + " has no features with a geometry");
  }
  return out;
}

const OGRGeometry* collect_polygons(const OGRGeometry* g, std::vector<const OGRPolygon*>& out) {
  const auto t = wkbFlatten(g->getGeometryType());
  if (t == wkbPolygon || t == wkbTriangle) {
    out.push_back(g->toPolygon());
    return nullptr;
  }
  if (t == wkbMultiPolygon || t == wkbGeometryCollection || t == wkbPolyhedralSurface || t == wkbTIN) {
    for (const auto* sub : *g->toGeometryCollection()) {
      if (const OGRGeometry* bad = collect_polygons(sub, out)) return bad;
    }
    return nullptr;
  }
  return g;
}

const OGRGeometry* collect_lines(const OGRGeometry* g, std::vector<const OGRSimpleCurve*>& out) {
  const auto t = wkbFlatten(g->getGeometryType());
  if (t == wkbLineString || t == wkbLinearRing) {
    out.push_back(g->toSimpleCurve());
    return nullptr;
  }
  if (t == wkbMultiLineString || t == wkbGeometryCollection) {
    for (const auto* sub : *g->toGeometryCollection()) {
      if (wkbFlatten(sub->getGeometryType()) == wkbPoint) continue;  // intersection by-products
      if (const OGRGeometry* bad = collect_lines(sub, out)) return bad;
    }
    return nullptr;
  }
  return g;
}

std::vector<Point2> curve_points(const OGRSimpleCurve* c) {
  std::vector<Point2> v(static_cast<std::size_t>(c->getNumPoints()));
  for (int i = 0; i < c->getNumPoints(); ++i) v[i] = {c->getX(i), c->getY(i)};
  return v;
}

}  // namespace fdr::gis
