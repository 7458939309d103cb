// Vector input: reads OGR layers, projects them to the working frame and assembles the PSLG.
#include "gis/vector_input.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <unordered_map>

#include <cpl_error.h>
#include <gdal_priv.h>
#include <ogr_geometry.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include "base/error.hpp"
#include "gis/gdal_util.hpp"
#include "gis/pg_open.hpp"
#include "base/edge_kind.hpp"
#include "predicates/predicates.hpp"

namespace fdr::gis {

namespace {

using fdr::EdgeKind;

std::string num(double v, int prec = 6) {
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

// One feature's geometry, flattened to 2D and with curves linearized.
struct Feature {
  std::int64_t fid = -1;
  std::unique_ptr<OGRGeometry> geom;
};

struct LayerData {
  std::string file, layer;
  OGRSpatialReference srs;  // traditional GIS order
  std::vector<Feature> features;
  std::string label() const { return file + ": layer '" + layer + "'"; }
};

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

LayerData read_layer(const LayerRef& ref, const std::string& s_srs, const char* option) {
  GdalQuiet quiet;
  const std::string name = source_label(ref.path);  // a "PG:" database without its password
  DatasetPtr ds = is_pg_connection(ref.path) ? open_pg_vector(ref.path) : open_vector(ref.path);
  OGRLayer* lyr = nullptr;
  if (ref.layer.empty()) {
    if (ds->GetLayerCount() == 0) throw Error(ExitCode::kInputUnreadable, name + ": no layers");
    lyr = ds->GetLayer(0);
  } else {
    lyr = ds->GetLayerByName(ref.layer.c_str());
    if (!lyr) {
      std::string names;
      for (int i = 0; i < ds->GetLayerCount(); ++i)
        names += (i ? ", " : "") + std::string(ds->GetLayer(i)->GetName());
      throw Error(ExitCode::kInputUnreadable, name + ": no layer '" + ref.layer + "' (layers: " + names + ")");
    }
  }
  if (is_pg_connection(ref.path)) check_pg_layer(*lyr, ref.path);
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

// Appends the polygons in g (Polygon, MultiPolygon, collections of them) to out; returns the
// first geometry of another type, or nullptr.
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

// Densification of geographic segments (DomainOptions::densify_deg, `--densify DEG`; off by
// default, as in GDAL and QGIS, where a reprojected segment is the chord between its projected
// ends). Why offer it: a lon/lat segment may mean the straight line in lon/lat (a parallel, a
// meridian), and on an ocean basin the 46-degree bottom side of a region box as one chord crosses
// the Antilles. A segment whose longitude or latitude span exceeds `step` degrees gets
// k - 1 points at j/k of the way, k = ceil(span / step). The points are computed from the
// segment's lexicographically smaller end, so the same source segment gives bitwise the same
// points in every layer and in either direction (a polygon ring and an open-boundary line drawn
// along it meet exactly).
constexpr double kGeoMaxPieces = 100000;  // cap: a segment never becomes more than this many

// Appends the interior points of segment a -> b (in order from a); returns how many.
std::size_t densify_segment(Point2 a, Point2 b, std::vector<Point2>& out, double step) {
  const double span = std::max(std::fabs(b.x - a.x), std::fabs(b.y - a.y));
  if (!(step > 0) || !(span > step)) return 0;
  const int k = static_cast<int>(std::min(std::ceil(span / step), kGeoMaxPieces));
  const bool fwd = a.x < b.x || (a.x == b.x && a.y <= b.y);
  const Point2 lo = fwd ? a : b, hi = fwd ? b : a;
  for (int i = 1; i < k; ++i) {
    const double t = static_cast<double>(fwd ? i : k - i) / k;
    out.push_back({lo.x + (hi.x - lo.x) * t, lo.y + (hi.y - lo.y) * t});
  }
  return static_cast<std::size_t>(k - 1);
}

// pts densified (closed: the ring's closing segment too). src (optional) receives, per output
// segment, the index of the source segment it lies on.
std::vector<Point2> densify(const std::vector<Point2>& pts, bool closed, double step, GisCounts& counts,
                            std::vector<std::uint32_t>* src = nullptr) {
  std::vector<Point2> out;
  out.reserve(pts.size());
  if (src) src->clear();
  const std::size_t n = pts.size(), nseg = closed ? n : (n == 0 ? 0 : n - 1);
  for (std::size_t i = 0; i < n; ++i) {
    out.push_back(pts[i]);
    if (src) src->push_back(static_cast<std::uint32_t>(i));
    if (i >= nseg) continue;
    const std::size_t added = densify_segment(pts[i], pts[(i + 1) % n], out, step);
    if (added) {
      ++counts.densified_segments;
      counts.densify_points += added;
      if (src) src->insert(src->end(), added, static_cast<std::uint32_t>(i));
    }
  }
  return out;
}

// A line of layer L (vertices in L's CRS) in the local frame, densified as the domain's rings
// are: in L's CRS when that is geographic; when L is projected but the domain layer is
// geographic, in the domain's CRS (the line's vertices taken there first), so that an open
// boundary in Web Mercator drawn along a lon/lat polygon's side gets the same points as the side.
void line_to_local(std::vector<Point2>& pts, const OGRSpatialReference& srs, const OGRSpatialReference& dom_srs,
                   const Frame& frame, const std::string& label, double step, GisCounts& counts) {
  if (!(step > 0)) {
    frame.to_local_batch(pts, srs, label);
    return;
  }
  if (srs.IsGeographic()) {
    pts = densify(pts, false, step, counts);
    frame.to_local_batch(pts, srs, label);
    return;
  }
  if (dom_srs.IsGeographic() && !srs.IsSame(&dom_srs)) {
    std::unique_ptr<OGRCoordinateTransformation> ct(OGRCreateCoordinateTransformation(&srs, &dom_srs));
    std::vector<double> x(pts.size()), y(pts.size());
    for (std::size_t i = 0; i < pts.size(); ++i) { x[i] = pts[i].x; y[i] = pts[i].y; }
    if (ct && ct->Transform(pts.size(), x.data(), y.data())) {
      std::vector<Point2> g(pts.size());
      for (std::size_t i = 0; i < pts.size(); ++i) g[i] = {x[i], y[i]};
      std::size_t before = counts.densify_points;
      g = densify(g, false, step, counts);
      if (counts.densify_points != before) {
        frame.to_local_batch(g, dom_srs, label);
        pts = std::move(g);
        return;
      }
    }
  }
  frame.to_local_batch(pts, srs, label);
}

// A ring as read: vertices (without the closing repeat) and where it came from.
struct Ring {
  std::vector<Point2> pts;
  std::vector<int> open;  // per segment i -> i+1 (mod n): 0 closed, else 1 + tag of the open line
  int part = -1;
  bool hole = false;
};

double ring_area(const std::vector<Point2>& r) {
  double a = 0;
  for (std::size_t i = 0, n = r.size(); i < n; ++i) {
    const Point2 p = r[i], q = r[(i + 1) % n];
    a += (p.x - r[0].x) * (q.y - r[0].y) - (q.x - r[0].x) * (p.y - r[0].y);
  }
  return 0.5 * a;
}


// Uniform bucket grid over line segments for "is this point within tol of a line" queries.
class SegmentBuckets {
 public:
  struct Seg { Point2 a, b; int tag; };
  SegmentBuckets(std::vector<Seg> segs, double tol) : segs_(std::move(segs)), tol_(tol) {
    for (const auto& s : segs_) { box_.add(s.a); box_.add(s.b); }
    if (segs_.empty()) return;
    const double side = std::max({box_.width(), box_.height(), 1.0});
    n_ = static_cast<int>(std::clamp(std::sqrt(double(segs_.size())) * 2.0, 1.0, 512.0));
    cell_ = side / n_ * 1.0000001;
    cells_.resize(static_cast<std::size_t>(n_) * n_);
    for (std::size_t k = 0; k < segs_.size(); ++k) {
      Box2 b;
      b.add(segs_[k].a); b.add(segs_[k].b);
      const auto [i0, j0] = cell(b.lo - Point2{tol_, tol_});
      const auto [i1, j1] = cell(b.hi + Point2{tol_, tol_});
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) cells_[static_cast<std::size_t>(j) * n_ + i].push_back(k);
    }
  }
  // Tag of a segment within tol of p, or -1.
  int near(Point2 p) const {
    if (segs_.empty()) return -1;
    if (p.x < box_.lo.x - tol_ || p.y < box_.lo.y - tol_ || p.x > box_.hi.x + tol_ || p.y > box_.hi.y + tol_) return -1;
    const auto [i, j] = cell(p);
    for (std::size_t k : cells_[static_cast<std::size_t>(j) * n_ + i])
      if (dist_to_segment(p, segs_[k].a, segs_[k].b) <= tol_) return segs_[k].tag;
    return -1;
  }

 private:
  std::pair<int, int> cell(Point2 p) const {
    const int i = std::clamp(static_cast<int>(std::floor((p.x - box_.lo.x) / cell_)), 0, n_ - 1);
    const int j = std::clamp(static_cast<int>(std::floor((p.y - box_.lo.y) / cell_)), 0, n_ - 1);
    return {i, j};
  }
  std::vector<Seg> segs_;
  double tol_;
  Box2 box_;
  int n_ = 1;
  double cell_ = 1;
  std::vector<std::vector<std::size_t>> cells_;
};

// Parity point-in-domain test over all rings (the mesher's own inside/outside rule).
// Why the half-open rule (a.y > p.y) != (b.y > p.y): a ray through a vertex is counted once.
bool inside_by_parity(Point2 p, const std::vector<Ring>& rings) {
  bool in = false;
  for (const auto& r : rings) {
    const std::size_t n = r.pts.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Point2 a = r.pts[i], b = r.pts[(i + 1) % n];
      if ((a.y > p.y) == (b.y > p.y)) continue;
      const int o = predicates::orient2d(a, b, p);
      if (o == 0) return true;  // on the boundary: keep the point (cleaning will merge it)
      if ((b.y > a.y) ? (o > 0) : (o < 0)) in = !in;
    }
  }
  return in;
}

// Converts polygons in LayerData (source CRS) to rings in the local frame.
void add_polygon_rings(const LayerData& L, const Frame& frame, const std::string& role_outer,
                       std::vector<Ring>& rings, std::vector<SourcePart>& parts, GisCounts& counts,
                       std::vector<std::vector<std::vector<Point2>>>& polys,
                       double step, std::vector<std::vector<std::uint32_t>>* seg_source = nullptr) {
  const bool geographic = L.srs.IsGeographic() && step > 0;
  // Gather every ring in one vector so that one batch transformation does the whole layer.
  std::vector<Point2> all;
  struct Pending { std::size_t begin, size; std::int64_t fid; int ring; std::size_t poly; };
  std::vector<Pending> pending;
  for (const auto& f : L.features) {
    std::vector<const OGRPolygon*> ps;
    if (const OGRGeometry* bad = collect_polygons(f.geom.get(), ps))
      throw Error(ExitCode::kInvalidGeometry, L.label() + ", feature FID " + std::to_string(f.fid) + " " +
                                                  where_str(bad) + ": geometry is " + bad->getGeometryName() +
                                                  ", expected Polygon or MultiPolygon");
    ++counts.polygon_features;
    for (const OGRPolygon* p : ps) {
      if (p->IsEmpty()) continue;
      ++counts.polygons;
      polys.emplace_back();
      int ring_index = 0;
      for (const OGRLinearRing* r : *p) {
        std::vector<Point2> pts = curve_points(r);
        if (pts.size() >= 2 && pts.front() == pts.back()) pts.pop_back();
        if (L.srs.IsGeographic() && !geographic)  // long lon/lat segments kept as chords: say so
          for (std::size_t i = 0, n = pts.size(); i < n; ++i) {
            const Point2 a = pts[i], b = pts[(i + 1) % n];
            if (std::max(std::fabs(b.x - a.x), std::fabs(b.y - a.y)) > 1.0) ++counts.long_chords;
          }
        if (geographic || seg_source) {
          std::vector<std::uint32_t> src;
          if (geographic) pts = densify(pts, true, step, counts, seg_source ? &src : nullptr);
          else for (std::uint32_t i = 0; i < pts.size(); ++i) src.push_back(i);
          if (seg_source) seg_source->push_back(std::move(src));
        }
        pending.push_back({all.size(), pts.size(), f.fid, ring_index++, polys.size() - 1});
        all.insert(all.end(), pts.begin(), pts.end());
      }
    }
  }
  frame.to_local_batch(all, L.srs, L.label());
  for (const auto& q : pending) {
    Ring r;
    r.pts.assign(all.begin() + static_cast<std::ptrdiff_t>(q.begin),
                 all.begin() + static_cast<std::ptrdiff_t>(q.begin + q.size));
    r.hole = q.ring > 0;
    r.open.assign(r.pts.size(), 0);
    r.part = static_cast<int>(parts.size());
    parts.push_back({L.file, L.layer, q.fid, r.hole ? "hole" : role_outer, q.ring});
    (r.hole ? counts.holes : counts.outer_rings) += 1;
    polys[q.poly].push_back(r.pts);
    rings.push_back(std::move(r));
  }
}

// Land + extent: the extent box minus the land polygons, computed with GEOS in the CRS in which
// the box is an axis-aligned rectangle. Returns a layer of polygons in that CRS; marks which ring
// segments lie on the box outline through `on_box` (per polygon, per ring, per segment).
LayerData land_minus_box(const DomainOptions& o, std::vector<std::vector<std::vector<char>>>& on_box) {
  LayerData land = read_layer(o.land, o.s_srs, "--land");
  const auto& e = *o.extent;
  if (!(e[0] < e[2] && e[1] < e[3]))
    throw Error(ExitCode::kUsage, "--extent " + num(e[0]) + "," + num(e[1]) + "," + num(e[2]) + "," + num(e[3]) +
                                      ": need xmin < xmax and ymin < ymax");
  OGRSpatialReference work = land.srs;
  if (o.extent_in_lonlat) {
    work.importFromEPSG(4326);
    work.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  }
  GdalQuiet quiet;
  OGRPolygon box;
  {
    OGRLinearRing r;
    r.addPoint(e[0], e[1]); r.addPoint(e[2], e[1]); r.addPoint(e[2], e[3]); r.addPoint(e[0], e[3]);
    r.addPoint(e[0], e[1]);
    box.addRing(&r);
  }
  // Clip each land polygon to the box first so that the union only sees what matters.
  OGRMultiPolygon clipped;
  for (auto& f : land.features) {
    if (o.extent_in_lonlat && !land.srs.IsSame(&work)) {
      f.geom->assignSpatialReference(&land.srs);
      if (f.geom->transformTo(&work) != OGRERR_NONE)
        throw Error(ExitCode::kCrsError, land.label() + ", feature FID " + std::to_string(f.fid) +
                                             ": cannot transform to WGS 84 lon/lat");
    }
    std::vector<const OGRPolygon*> ps;
    if (const OGRGeometry* bad = collect_polygons(f.geom.get(), ps))
      throw Error(ExitCode::kInvalidGeometry, land.label() + ", feature FID " + std::to_string(f.fid) + " " +
                                                  where_str(bad) + ": geometry is " + bad->getGeometryName() +
                                                  ", expected Polygon or MultiPolygon");
    for (const OGRPolygon* p : ps) {
      OGREnvelope env;
      p->getEnvelope(&env);
      if (env.MaxX < e[0] || env.MinX > e[2] || env.MaxY < e[1] || env.MinY > e[3]) continue;
      std::unique_ptr<OGRGeometry> c(p->Intersection(&box));
      if (!c) {  // invalid land polygon: GEOS refuses it; repair this copy only for the subtraction
        std::unique_ptr<OGRGeometry> v(p->MakeValid());
        if (v) c.reset(v->Intersection(&box));
      }
      if (!c)
        throw Error(ExitCode::kInvalidGeometry, land.label() + ", feature FID " + std::to_string(f.fid) + " " +
                                                    where_str(p) + ": cannot intersect with the extent: " +
                                                    CPLGetLastErrorMsg());
      std::vector<const OGRPolygon*> cps;
      collect_polygons(c.get(), cps);  // lines/points of a touching intersection are dropped
      for (const OGRPolygon* cp : cps) clipped.addGeometry(cp);
    }
  }
  std::unique_ptr<OGRGeometry> water;
  if (clipped.IsEmpty()) {
    water.reset(box.clone());
  } else {
    std::unique_ptr<OGRGeometry> uni(clipped.UnionCascaded());
    if (!uni) throw Error(ExitCode::kInvalidGeometry, land.label() + ": union of the land polygons failed: " +
                                                          CPLGetLastErrorMsg());
    water.reset(box.Difference(uni.get()));
    if (!water) throw Error(ExitCode::kInvalidGeometry, land.label() + ": extent minus land failed: " +
                                                            CPLGetLastErrorMsg());
  }
  LayerData out;
  out.file = land.file;
  out.layer = land.layer + " (extent minus land)";
  out.srs = work;
  std::vector<const OGRPolygon*> ps;
  collect_polygons(water.get(), ps);
  if (ps.empty())
    throw Error(ExitCode::kInvalidGeometry, land.label() + ": the land covers the whole --extent; no domain left");
  // A vertex lies on a box side if it equals that side's coordinate up to GEOS rounding.
  const double tol = 1e-9 * std::max(e[2] - e[0], e[3] - e[1]);
  auto side = [&](double x, double y) {
    int s = 0;
    if (std::abs(x - e[0]) <= tol) s |= 1;
    if (std::abs(x - e[2]) <= tol) s |= 2;
    if (std::abs(y - e[1]) <= tol) s |= 4;
    if (std::abs(y - e[3]) <= tol) s |= 8;
    return s;
  };
  auto mp = std::make_unique<OGRMultiPolygon>();
  for (const OGRPolygon* p : ps) {
    on_box.emplace_back();
    for (const OGRLinearRing* r : *p) {
      std::vector<Point2> pts = curve_points(r);
      if (pts.size() >= 2 && pts.front() == pts.back()) pts.pop_back();
      std::vector<char> flags(pts.size(), 0);
      for (std::size_t i = 0; i < pts.size(); ++i) {
        const Point2 a = pts[i], b = pts[(i + 1) % pts.size()];
        flags[i] = (side(a.x, a.y) & side(b.x, b.y)) != 0;
      }
      on_box.back().push_back(std::move(flags));
    }
    mp->addGeometry(p);
  }
  Feature f;
  f.fid = -1;
  f.geom = std::move(mp);
  out.features.push_back(std::move(f));
  return out;
}

// Sample of lon/lat points of a layer (at most ~20000) for choosing the frame.
void sample_lonlat(const LayerData& L, std::vector<LonLat>& out) {
  std::vector<double> x, y;
  for (const auto& f : L.features) {
    std::vector<const OGRPolygon*> ps;
    if (const OGRGeometry* bad = collect_polygons(f.geom.get(), ps))
      throw Error(ExitCode::kInvalidGeometry, L.label() + ", feature FID " + std::to_string(f.fid) + " " +
                                                  where_str(bad) + ": geometry is " + bad->getGeometryName() +
                                                  ", expected Polygon or MultiPolygon");
    for (const auto* p : ps)
      for (const OGRLinearRing* r : *p)
        for (int i = 0; i < r->getNumPoints(); ++i) { x.push_back(r->getX(i)); y.push_back(r->getY(i)); }
  }
  const std::size_t stride = std::max<std::size_t>(1, x.size() / 20000);
  std::vector<double> sx, sy;
  for (std::size_t i = 0; i < x.size(); i += stride) { sx.push_back(x[i]); sy.push_back(y[i]); }
  OGRSpatialReference ll;
  ll.importFromEPSG(4326);
  ll.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<OGRCoordinateTransformation, void (*)(OGRCoordinateTransformation*)> ct(
      OGRCreateCoordinateTransformation(&L.srs, &ll), OGRCoordinateTransformation::DestroyCT);
  if (!ct) throw Error(ExitCode::kCrsError, L.label() + ": no transformation from its CRS to WGS 84");
  std::vector<int> ok(sx.size(), 0);
  ct->Transform(static_cast<int>(sx.size()), sx.data(), sy.data(), nullptr, ok.data());
  for (std::size_t i = 0; i < sx.size(); ++i)
    if (ok[i] && std::isfinite(sx[i]) && std::isfinite(sy[i])) out.push_back({sx[i], sy[i]});
  if (out.empty()) throw Error(ExitCode::kCrsError, L.label() + ": no vertex can be transformed to WGS 84");
}

std::unique_ptr<OGRMultiPolygon> local_domain_geometry(const std::vector<std::vector<std::vector<Point2>>>& polys) {
  auto mp = std::make_unique<OGRMultiPolygon>();
  for (const auto& poly : polys) {
    OGRPolygon p;
    for (const auto& ring : poly) {
      if (ring.size() < 3) continue;
      OGRLinearRing r;
      for (const auto& q : ring) r.addPoint(q.x, q.y);
      r.addPoint(ring[0].x, ring[0].y);
      p.addRing(&r);
    }
    if (!p.IsEmpty()) mp->addGeometry(&p);
  }
  return mp;
}

}  // namespace

namespace {
// A repair in the local frame as a record: world coordinates and lon/lat.
RepairRecord repair_record(const Frame& frame, pslg::Repair rep) {
  RepairRecord rec;
  rec.lonlat = frame.to_lonlat(rep.where);
  rec.repair = std::move(rep);
  rec.repair.where = frame.to_world(rec.repair.where);
  return rec;
}
}  // namespace

void start_features(GisInput& in) { start_removed(in.features); }

void finish_features(GisInput& in) {
  std::vector<pslg::Repair> reps = finish_removed(in.features);
  if (reps.empty()) return;
  std::vector<RepairRecord> recs;
  for (auto& rep : reps) recs.push_back(repair_record(in.frame, std::move(rep)));
  // in.repairs starts with the filter's repairs (read_domain, clean_domain).
  const auto at = static_cast<std::ptrdiff_t>(std::min(in.feature_repairs.size(), in.repairs.size()));
  in.repairs.insert(in.repairs.begin() + at, recs.begin(), recs.end());
  in.feature_repairs.insert(in.feature_repairs.end(), recs.begin(), recs.end());
  in.counts.repairs = in.repairs.size();
}

void clean_domain(GisInput& in, const pslg::CleanOptions& options) {
  std::vector<pslg::Repair> reps;
  in.pslg = pslg::clean(in.raw, options, &reps);
  in.pslg.origin = in.frame.origin();
  in.repairs = in.feature_repairs;
  for (auto& r : reps) in.repairs.push_back(repair_record(in.frame, std::move(r)));
  in.counts.repairs = in.repairs.size();
}

GisInput read_domain(const DomainOptions& o) {
  ensure_gdal_registered();
  if (o.domain.given() == (o.land.given() || o.extent.has_value()))
    throw Error(ExitCode::kUsage, o.domain.given() ? "give either a domain layer or --land with --extent, not both"
                                                   : "no domain: give a polygon layer, or --land with --extent");
  if (o.land.given() != o.extent.has_value())
    throw Error(ExitCode::kUsage, o.land.given() ? "--land needs --extent xmin,ymin,xmax,ymax" : "--extent needs --land");

  GisInput in;
  std::vector<std::vector<std::vector<char>>> on_box;
  LayerData dom = o.domain.given() ? read_layer(o.domain, o.s_srs, "--where") : land_minus_box(o, on_box);

  std::vector<LonLat> sample;
  sample_lonlat(dom, sample);
  in.frame = choose_frame(sample, o.t_srs);
  const Frame& frame = in.frame;

  std::vector<Ring> rings;
  std::vector<std::vector<std::uint32_t>> seg_source;  // per ring: source segment of each segment
  add_polygon_rings(dom, frame, o.domain.given() ? "outer ring" : "extent box", rings, in.parts, in.counts,
                    in.domain_polygons, o.densify_deg, on_box.empty() ? nullptr : &seg_source);
  if (rings.empty())
    throw Error(ExitCode::kInvalidGeometry, dom.label() + ": no polygon rings");
  for (const auto& poly : in.domain_polygons)
    for (std::size_t k = 0; k < poly.size(); ++k) in.domain_area_m2 += (k == 0 ? 1 : -1) * std::abs(ring_area(poly[k]));

  Box2 bb;
  for (const auto& r : rings)
    for (const auto& p : r.pts) bb.add(p);
  const double diam = std::hypot(bb.width(), bb.height());
  in.frame.set_domain_box(bb);

  // Open boundary lines in the local frame (tag = index into open_fid_of_tag): the extent box
  // sides (land mode) and the open-boundary layer. Ring segments lying on them become kOpen
  // after the resolution filter has reshaped the rings.
  std::vector<std::int64_t> open_fid_of_tag;
  std::string open_file, open_layer;
  std::vector<SegmentBuckets::Seg> open_segs;
  if (!on_box.empty()) {
    std::size_t k = 0;
    for (const auto& poly : on_box)
      for (const auto& flags : poly) {
        const auto& pts = rings[k].pts;
        const auto& src = seg_source[k];  // densified segment -> source segment (its flag)
        for (std::size_t i = 0; i < src.size() && i < pts.size(); ++i)
          if (src[i] < flags.size() && flags[src[i]]) open_segs.push_back({pts[i], pts[(i + 1) % pts.size()], 0});
        ++k;
      }
    open_fid_of_tag.push_back(-1);
    open_file = o.land.path;
    open_layer = "--extent";
  }

  if (o.features) {
    const FeatureFilterOptions fo = o.features(bb);
    in.input_polygons = in.domain_polygons;
    FeatureFilterResult fr = filter_features(in.domain_polygons, fo);
    // Which input ring each new ring continues: vote of its vertices near the old rings.
    std::vector<SegmentBuckets::Seg> old_segs;
    for (const auto& r : rings)
      for (std::size_t i = 0; i < r.pts.size(); ++i) old_segs.push_back({r.pts[i], r.pts[(i + 1) % r.pts.size()], r.part});
    const SegmentBuckets old_near(std::move(old_segs), std::max({fo.close_width, 1e-7 * diam, 1e-6}));
    std::vector<Ring> out_rings;
    for (const auto& poly : fr.polygons)
      for (std::size_t k = 0; k < poly.size(); ++k) {
        Ring r;
        r.pts = poly[k];
        r.hole = k > 0;
        r.open.assign(r.pts.size(), 0);
        std::map<int, int> votes;
        const std::size_t step = std::max<std::size_t>(1, r.pts.size() / 16);
        for (std::size_t i = 0; i < r.pts.size(); i += step)
          if (const int t = old_near.near(r.pts[i]); t >= 0) ++votes[t];
        int best = -1, bestn = 0;
        for (const auto& [t, n] : votes)
          if (n > bestn) { best = t; bestn = n; }
        if (best >= 0 && (in.parts[static_cast<std::size_t>(best)].role == "hole") == r.hole) {
          r.part = best;
        } else {
          r.part = static_cast<int>(in.parts.size());
          SourcePart sp = best >= 0 ? in.parts[static_cast<std::size_t>(best)] : SourcePart{dom.file, dom.layer, -1, "", -1};
          sp.role = r.hole ? "hole" : (o.domain.given() ? "outer ring" : "extent box");
          sp.ring = r.hole ? -1 : 0;
          in.parts.push_back(sp);
        }
        out_rings.push_back(std::move(r));
      }
    rings = std::move(out_rings);
    in.domain_polygons = fr.polygons;
    in.domain_area_m2 = fr.output_area;
    for (auto& rep : fr.repairs) in.feature_repairs.push_back(repair_record(frame, std::move(rep)));
    fr.repairs.clear();
    fr.polygons.clear();
    in.features = std::move(fr);
    in.repairs = in.feature_repairs;
  }

  if (o.open_boundary.given()) {
    LayerData ob = read_layer(o.open_boundary, o.s_srs, "--open-boundary");
    open_file = ob.file;
    open_layer = ob.layer;
    for (const auto& f : ob.features) {
      std::vector<const OGRSimpleCurve*> ls;
      if (const OGRGeometry* bad = collect_lines(f.geom.get(), ls))
        throw Error(ExitCode::kInvalidGeometry, ob.label() + ", feature FID " + std::to_string(f.fid) + " " +
                                                    where_str(bad) + ": geometry is " + bad->getGeometryName() +
                                                    ", expected LineString or MultiLineString");
      ++in.counts.open_features;
      const int tag = static_cast<int>(open_fid_of_tag.size());
      open_fid_of_tag.push_back(f.fid);
      for (const auto* c : ls) {
        std::vector<Point2> pts = curve_points(c);
        line_to_local(pts, ob.srs, dom.srs, frame, ob.label(), o.densify_deg, in.counts);
        for (std::size_t i = 0; i + 1 < pts.size(); ++i) open_segs.push_back({pts[i], pts[i + 1], tag});
      }
    }
  }
  if (!open_segs.empty()) {
    // Open lines normally share the polygon's vertices exactly; the tolerance only absorbs
    // rounding from a different file format, a reprojection or the resolution filter.
    const double tol = std::max(1e-7 * diam, 1e-6);
    SegmentBuckets buckets(std::move(open_segs), tol);
    for (auto& r : rings) {
      const std::size_t n = r.pts.size();
      for (std::size_t i = 0; i < n; ++i) {
        const Point2 a = r.pts[i], b = r.pts[(i + 1) % n];
        const int ta = buckets.near(a);
        if (ta < 0 || buckets.near(b) < 0 || buckets.near(0.5 * (a + b)) < 0) continue;
        r.open[i] = 1 + ta;  // remember which open feature matched (1-based)
      }
    }
  }

  // Assemble the raw PSLG: ring segments, open runs get their own part ids.
  pslg::Pslg& P = in.raw;
  P.origin = frame.origin();
  for (auto& r : rings) {
    const std::size_t n = r.pts.size();
    if (n < 2) continue;
    const Index base = static_cast<Index>(P.points.size());
    P.points.insert(P.points.end(), r.pts.begin(), r.pts.end());
    // Start at a segment after a closed one so that a run never wraps around the ring start.
    std::size_t start = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (!r.open[i]) { start = (i + 1) % n; break; }
    int run_part = -1;
    for (std::size_t s = 0; s < n; ++s) {
      const std::size_t i = (start + s) % n;
      pslg::Segment seg;
      seg.a = base + static_cast<Index>(i);
      seg.b = base + static_cast<Index>((i + 1) % n);
      if (r.open[i]) {
        if (run_part < 0) {
          run_part = static_cast<int>(in.parts.size());
          const int tag = r.open[i] - 1;
          const std::int64_t fid = tag >= 0 && tag < static_cast<int>(open_fid_of_tag.size()) ? open_fid_of_tag[tag] : -1;
          in.parts.push_back({open_file, open_layer, fid, "open boundary", -1});
          ++in.counts.open_parts;
        }
        seg.marker = static_cast<std::int32_t>(EdgeKind::kOpen);
        seg.part = run_part;
        ++in.counts.open_segments;
      } else {
        run_part = -1;
        seg.marker = static_cast<std::int32_t>(r.hole ? EdgeKind::kIsland : EdgeKind::kLand);
        seg.part = r.part;
      }
      P.segments.push_back(seg);
      ++in.counts.boundary_segments;
    }
  }

  // Breaklines, clipped to the domain polygons with GEOS.
  if (o.breaklines.given()) {
    LayerData bl = read_layer(o.breaklines, o.s_srs, "--breaklines");
    GdalQuiet quiet;
    // After the resolution filter, clip to the domain shrunk by a hair (5 % of --close-width):
    // a breakline drawn along the coast (a border) would otherwise run a fraction of a metre from
    // the rounded corners the filter made, a sliver no mesher can split. Its ends are put back
    // on the coast by snap_loose_ends (pipeline).
    const double hair = 0.05 * in.features.close_width;
    std::unique_ptr<OGRGeometry> clip =
        local_domain_geometry(hair > 0 ? offset_polygons(in.domain_polygons, -hair) : in.domain_polygons);
    if (!clip->IsValid()) {  // raw (self-intersecting) rings: GEOS needs a valid copy to clip against
      std::unique_ptr<OGRGeometry> v(clip->MakeValid());
      if (!v) throw Error(ExitCode::kInvalidGeometry, dom.label() + ": cannot make a valid copy of the domain "
                                                                    "for clipping breaklines: " + CPLGetLastErrorMsg());
      clip = std::move(v);
    }
    for (const auto& f : bl.features) {
      std::vector<const OGRSimpleCurve*> ls;
      if (const OGRGeometry* bad = collect_lines(f.geom.get(), ls))
        throw Error(ExitCode::kInvalidGeometry, bl.label() + ", feature FID " + std::to_string(f.fid) + " " +
                                                    where_str(bad) + ": geometry is " + bad->getGeometryName() +
                                                    ", expected LineString or MultiLineString");
      ++in.counts.breakline_features;
      OGRMultiLineString local;
      for (const auto* c : ls) {
        std::vector<Point2> pts = curve_points(c);
        line_to_local(pts, bl.srs, dom.srs, frame, bl.label(), o.densify_deg, in.counts);
        OGRLineString l;
        for (const auto& p : pts) l.addPoint(p.x, p.y);
        local.addGeometry(&l);
      }
      std::unique_ptr<OGRGeometry> cut(clip->Intersection(&local));
      if (!cut)
        throw Error(ExitCode::kInvalidGeometry, bl.label() + ", feature FID " + std::to_string(f.fid) + " " +
                                                    where_str(f.geom.get()) + ": clipping to the domain failed: " +
                                                    CPLGetLastErrorMsg());
      std::vector<const OGRSimpleCurve*> pieces;
      collect_lines(cut.get(), pieces);
      if (pieces.empty()) continue;
      const int part = static_cast<int>(in.parts.size());
      in.parts.push_back({bl.file, bl.layer, f.fid, "breakline", -1});
      for (const auto* c : pieces) {
        const std::vector<Point2> pts = curve_points(c);
        if (pts.size() < 2) continue;
        const Index base = static_cast<Index>(P.points.size());
        P.points.insert(P.points.end(), pts.begin(), pts.end());
        for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
          P.segments.push_back({base + static_cast<Index>(i), base + static_cast<Index>(i + 1),
                                static_cast<std::int32_t>(EdgeKind::kBreakline), part});
          ++in.counts.breakline_segments;
        }
      }
    }
  }

  // Fixed points inside the domain (parity rule, as the mesher classifies triangles).
  if (o.points.given()) {
    LayerData pl = read_layer(o.points, o.s_srs, "--points");
    std::vector<Point2> pts;
    for (const auto& f : pl.features) {
      const auto t = wkbFlatten(f.geom->getGeometryType());
      if (t == wkbPoint) {
        pts.push_back({f.geom->toPoint()->getX(), f.geom->toPoint()->getY()});
      } else if (t == wkbMultiPoint) {
        for (const auto* p : *f.geom->toMultiPoint()) pts.push_back({p->getX(), p->getY()});
      } else {
        throw Error(ExitCode::kInvalidGeometry, pl.label() + ", feature FID " + std::to_string(f.fid) + " " +
                                                    where_str(f.geom.get()) + ": geometry is " +
                                                    f.geom->getGeometryName() + ", expected Point or MultiPoint");
      }
    }
    frame.to_local_batch(pts, pl.srs, pl.label());
    for (const auto& p : pts) {
      if (inside_by_parity(p, rings)) {
        P.points.push_back(p);
        ++in.counts.fixed_points;
      } else {
        ++in.counts.points_outside;
      }
    }
  }

  in.snap_distance_m = o.snap_distance_m >= 0 ? o.snap_distance_m : std::max(1e-6 * diam, 0.01);
  if (o.clean) {
    pslg::CleanOptions co;
    co.snap_distance = in.snap_distance_m;
    co.min_island_area_factor = o.min_island_area_factor;
    co.simplify_factor = o.simplify_factor;
    co.simplify_tolerance = o.simplify_tolerance_m;
    if (o.min_island_area_factor > 0 || o.simplify_factor > 0) {
      if (!o.spacing) throw Error(ExitCode::kUsage, "tiny-island removal and simplification need a spacing function");
      sizing::SizingPtr f = o.spacing(in.frame);
      co.spacing = [f](Point2 p) { return (*f)(p); };
    }
    clean_domain(in, co);
  } else {
    in.pslg = in.raw;
  }
  return in;
}

}  // namespace fdr::gis
