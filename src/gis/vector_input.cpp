// Vector input: reads OGR layers, projects them to the working frame and assembles the PSLG.
#include "gis/vector_input.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <numbers>
#include <memory>
#include <mutex>
#include <unordered_map>

#include <cpl_error.h>
#include <gdal_priv.h>
#include <ogr_geometry.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include "coast/convex.hpp"
#include "base/error.hpp"
#include "gis/gdal_util.hpp"
#include "gis/global_domain.hpp"
#include "gis/vector_layers.hpp"
#include "base/edge_kind.hpp"
#include "predicates/predicates.hpp"

namespace fdr::gis {

namespace {

using fdr::EdgeKind;

// Densification of geographic segments (DomainOptions::densify_deg, `--densify DEG`; off by
// default, as in GDAL and QGIS, where a reprojected segment is the chord between its projected
// ends). Why offer it: a lon/lat segment may mean the straight line in lon/lat (a parallel, a
// meridian), and a long side of a region box as one chord can cross whole islands. A segment whose longitude or latitude span exceeds `step` degrees gets
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

void start_features(GisInput& in) { coast::start_removed(in.features); }

void finish_features(GisInput& in) {
  std::vector<pslg::Repair> reps = coast::finish_removed(in.features);
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


namespace {

// Usage errors in the choice of domain layers.
void check_domain_options(const DomainOptions& o) {
  if (o.domain.given() == (o.land.given() || o.extent.has_value()))
    throw Error(ExitCode::kUsage, o.domain.given() ? "give either a domain layer or --land with --extent, not both"
                                                   : "no domain: give a polygon layer, or --land with --extent");
  if (o.global_pole) {
    if (!o.land.given() || o.extent) throw Error(ExitCode::kUsage, "--global takes --land and no --extent");
    return;
  }
  if (o.land.given() != o.extent.has_value())
    throw Error(ExitCode::kUsage, o.land.given() ? "--land needs --extent xmin,ymin,xmax,ymax" : "--extent needs --land");
}

// Open boundary lines in the local frame (tag = index into fid_of_tag): the extent box sides
// (land mode) and the open-boundary layer. Ring segments lying on them become kOpen after the
// resolution filter has reshaped the rings.
struct OpenLines {
  std::vector<std::int64_t> fid_of_tag;
  std::string file, layer;
  std::vector<SegmentBuckets::Seg> segs;
};

// The sides of the extent box (land mode): the ring segments on_box flags, through seg_source
// (per ring, the source segment of each densified segment).
void add_box_sides(const std::vector<std::vector<std::vector<char>>>& on_box, const std::vector<Ring>& rings,
                   const std::vector<std::vector<std::uint32_t>>& seg_source, const DomainOptions& o, OpenLines& open) {
  auto& open_segs = open.segs;
  std::size_t k = 0;
  for (const auto& poly : on_box)
    for (const auto& flags : poly) {
      const auto& pts = rings[k].pts;
      const auto& src = seg_source[k];  // densified segment -> source segment (its flag)
      for (std::size_t i = 0; i < src.size() && i < pts.size(); ++i)
        if (src[i] < flags.size() && flags[src[i]]) open_segs.push_back({pts[i], pts[(i + 1) % pts.size()], 0});
      ++k;
    }
  open.fid_of_tag.push_back(-1);
  open.file = o.land.path;
  open.layer = "--extent";
}

// The coast generalisation (coast/generalise.hpp) of the domain polygons: the rings replaced by
// its result, each new ring given the source part of the input ring it continues (a vote of its
// vertices near the old rings); its repairs and figures in `in`.
void generalise_domain(const DomainOptions& o, const LayerData& dom, const Box2& bb, double diam, GisInput& in,
                       std::vector<Ring>& rings) {
  const Frame& frame = in.frame;
  const coast::Options fo = o.features(bb);
  in.input_polygons = in.domain_polygons;
  coast::Result fr = coast::generalise(in.domain_polygons, fo);
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

// The open-boundary layer's lines (tags after the box sides').
void read_open_boundary(const DomainOptions& o, const LayerData& dom, GisInput& in, OpenLines& open) {
  const Frame& frame = in.frame;
  auto& open_segs = open.segs;
  auto& open_fid_of_tag = open.fid_of_tag;
  LayerData ob = read_layer(o.open_boundary, o.s_srs, "--open-boundary");
  open.file = ob.file;
  open.layer = ob.layer;
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

// Ring segments lying on an open line become open (r.open: 1 + the line's tag).
void mark_open_segments(std::vector<Ring>& rings, OpenLines& open, double diam) {
  auto& open_segs = open.segs;
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

// The raw PSLG: ring segments, open runs get their own part ids.
void assemble_rings(GisInput& in, const std::vector<Ring>& rings, const OpenLines& open) {
  const Frame& frame = in.frame;
  const auto& open_fid_of_tag = open.fid_of_tag;
  const std::string& open_file = open.file;
  const std::string& open_layer = open.layer;
  pslg::Pslg& P = in.raw;
  P.origin = frame.origin();
  for (const auto& r : rings) {
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
}

// Breaklines, clipped to the domain polygons with GEOS.
void add_breaklines(const DomainOptions& o, const LayerData& dom, GisInput& in) {
  const Frame& frame = in.frame;
  pslg::Pslg& P = in.raw;
  LayerData bl = read_layer(o.breaklines, o.s_srs, "--breaklines");
  GdalQuiet quiet;
  // After the resolution filter, clip to the domain shrunk by a hair (5 % of --close-width):
  // a breakline drawn along the coast (a border) would otherwise run a fraction of a metre from
  // the rounded corners the filter made, a sliver no mesher can split. Its ends are put back
  // on the coast by snap_loose_ends (pipeline).
  const double hair = 0.05 * in.features.close_width;
  std::unique_ptr<OGRGeometry> clip =
      local_domain_geometry(hair > 0 ? coast::offset_polygons(in.domain_polygons, -hair) : in.domain_polygons);
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
void add_points(const DomainOptions& o, const std::vector<Ring>& rings, GisInput& in) {
  const Frame& frame = in.frame;
  pslg::Pslg& P = in.raw;
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

// --global: the sphere minus land (gis/global_domain.hpp) in its stereographic frame, as rings
// (the outer coast a land boundary, every other coast an island); areas on the sphere.
LayerData global_domain(const DomainOptions& o, GisInput& in, std::vector<Ring>& rings) {
  const SphereStereo proj(*o.global_pole);
  in.frame = Frame::from_crs(proj.proj_string(), {0, 0});
  // Land edges follow their lon/lat line before projection (0.1 degree unless --densify says).
  // The generalisation runs on the sphere's land in ground metres (gis/global_generalise.hpp),
  // not on the water in this plane, whose scale factor reaches 100 near the pole.
  std::optional<coast::Options> fo;
  if (o.features) {
    Box2 sphere;  // for a default hmin only; a global run requires --hmin
    sphere.add({-kEarthRadius * std::numbers::pi, -kEarthRadius * std::numbers::pi});
    sphere.add({kEarthRadius * std::numbers::pi, kEarthRadius * std::numbers::pi});
    fo = o.features(sphere);
  }
  GlobalWater gw = global_water(o.land, o.s_srs, proj, o.densify_deg > 0 ? o.densify_deg : 0.1, fo ? &*fo : nullptr);
  if (fo) {
    in.input_polygons = std::move(gw.input_polygons);
    for (auto& rep : gw.features.repairs) in.feature_repairs.push_back(repair_record(in.frame, std::move(rep)));
    gw.features.repairs.clear();
    in.features = std::move(gw.features);
    in.repairs = in.feature_repairs;
  }
  in.counts.densify_points += gw.densify_points;
  in.domain_area_m2 = gw.water_area_m2;
  LayerData dom;
  dom.file = gw.file;
  dom.layer = gw.layer + " (sphere minus land)";
  dom.srs.importFromEPSG(4326);
  dom.srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  for (auto& poly : gw.polygons) {
    ++in.counts.polygon_features;
    ++in.counts.polygons;
    for (std::size_t k = 0; k < poly.size(); ++k) {
      Ring r;
      r.pts = poly[k];
      r.hole = k > 0;
      r.open.assign(r.pts.size(), 0);
      r.part = static_cast<int>(in.parts.size());
      in.parts.push_back({gw.file, gw.layer, r.hole ? -1 : gw.pole_fid, r.hole ? "hole" : "outer ring", r.hole ? -1 : 0});
      (r.hole ? in.counts.holes : in.counts.outer_rings) += 1;
      rings.push_back(std::move(r));
    }
  }
  in.domain_polygons = std::move(gw.polygons);
  return dom;
}

}  // namespace

GisInput read_domain(const DomainOptions& o) {
  ensure_gdal_registered();
  check_domain_options(o);

  GisInput in;
  std::vector<std::vector<std::vector<char>>> on_box;
  LayerData dom;
  std::vector<Ring> rings;
  std::vector<std::vector<std::uint32_t>> seg_source;  // per ring: source segment of each segment
  if (o.global_pole) {
    dom = global_domain(o, in, rings);
  } else {
    dom = o.domain.given() ? read_layer(o.domain, o.s_srs, "--where") : land_minus_box(o, on_box);
    std::vector<LonLat> sample;
    sample_lonlat(dom, sample);
    in.frame = choose_frame(sample, o.t_srs);
    add_polygon_rings(dom, in.frame, o.domain.given() ? "outer ring" : "extent box", rings, in.parts, in.counts,
                      in.domain_polygons, o.densify_deg, on_box.empty() ? nullptr : &seg_source);
    for (const auto& poly : in.domain_polygons)
      for (std::size_t k = 0; k < poly.size(); ++k) in.domain_area_m2 += (k == 0 ? 1 : -1) * std::abs(coast::signed_area(poly[k]));
  }
  if (rings.empty())
    throw Error(ExitCode::kInvalidGeometry, dom.label() + ": no polygon rings");

  Box2 bb;
  for (const auto& r : rings)
    for (const auto& p : r.pts) bb.add(p);
  const double diam = std::hypot(bb.width(), bb.height());
  in.frame.set_domain_box(bb);
  OpenLines open;
  if (!on_box.empty()) add_box_sides(on_box, rings, seg_source, o, open);
  if (o.features && !o.global_pole) generalise_domain(o, dom, bb, diam, in, rings);
  if (o.open_boundary.given()) read_open_boundary(o, dom, in, open);
  if (!open.segs.empty()) mark_open_segments(rings, open, diam);
  assemble_rings(in, rings, open);
  if (o.breaklines.given()) add_breaklines(o, dom, in);
  if (o.points.given()) add_points(o, rings, in);
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
