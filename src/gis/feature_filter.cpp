// Resolution filter for water polygons: union, morphological opening with kept connections,
// island removal (GEOS through OGR). See feature_filter.hpp for the method.
#include "gis/feature_filter.hpp"
#include "base/step_laps.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <cstring>
#include <cstdint>
#include <limits>

#include <cpl_error.h>
#include <ogr_api.h>
#include <ogr_geometry.h>

#include "base/error.hpp"
#include "base/parallel.hpp"
#include "gis/gdal_util.hpp"
#include "predicates/predicates.hpp"
#include "pslg/contained_difference.hpp"
#include "pslg/segment_grid.hpp"

namespace fdr::gis {
namespace {

using GeomPtr = std::unique_ptr<OGRGeometry>;

// Quarter-circle segments of the buffers: the arcs are resampled to f afterwards, so a coarse
// polygon (15 degrees per chord, sagitta 0.9 % of r) is enough.
constexpr int kQuadSegs = 4;

std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// The filter's step timings (FDR_DEBUG_FILTER; base/step_laps.hpp).
class DebugLaps : public StepLaps {
 public:
  explicit DebugLaps(const char* prefix) : StepLaps(debug::Aid::kFilter, prefix) {}
};

GeomPtr checked(OGRGeometry* g, const char* what) {
  if (!g)
    throw Error(ExitCode::kInvalidGeometry, std::string("resolving narrow features: ") + what + " failed: " +
                                                CPLGetLastErrorMsg());
  return GeomPtr(g);
}

// The polygons of g (Polygon, MultiPolygon, collections), as owned copies.
void polygons_of(const OGRGeometry* g, std::vector<std::unique_ptr<OGRPolygon>>& out) {
  if (!g || g->IsEmpty()) return;
  const auto t = wkbFlatten(g->getGeometryType());
  if (t == wkbPolygon) {
    out.emplace_back(g->toPolygon()->clone());
  } else if (t == wkbMultiPolygon || t == wkbGeometryCollection) {
    for (const auto* sub : *g->toGeometryCollection()) polygons_of(sub, out);
  }
}

std::unique_ptr<OGRMultiPolygon> multi(std::vector<std::unique_ptr<OGRPolygon>>& ps) {
  auto m = std::make_unique<OGRMultiPolygon>();
  for (auto& p : ps) m->addGeometryDirectly(p.release());
  ps.clear();
  return m;
}

// Exact key of a coordinate pair (bit patterns), for "is this one of W's vertices".
std::uint64_t point_key(double x, double y) {
  std::uint64_t a, b;
  std::memcpy(&a, &x, 8);
  std::memcpy(&b, &y, 8);
  return a * 0x9E3779B97F4A7C15ull ^ (b + 0x632BE59BD9B4E019ull + (a << 6) + (a >> 2));
}

// A prepared geometry: fast repeated intersection tests against one polygon.
class Prepared {
 public:
  explicit Prepared(const OGRGeometry* g)
      : h_(OGRCreatePreparedGeometry(OGRGeometry::ToHandle(const_cast<OGRGeometry*>(g)))), g_(g) {}
  ~Prepared() {
    if (h_) OGRDestroyPreparedGeometry(h_);
  }
  Prepared(const Prepared&) = delete;
  Prepared& operator=(const Prepared&) = delete;
  bool intersects(const OGRGeometry* o) const {
    if (h_) return OGRPreparedGeometryIntersects(h_, OGRGeometry::ToHandle(const_cast<OGRGeometry*>(o)));
    return g_->Intersects(o);
  }
  bool contains(const OGRGeometry* o) const {
    if (h_) return OGRPreparedGeometryContains(h_, OGRGeometry::ToHandle(const_cast<OGRGeometry*>(o)));
    return g_->Contains(o);
  }

 private:
  OGRPreparedGeometryH h_;
  const OGRGeometry* g_;
};

// Holes far from an overlay. GEOS 3.11's overlay places every hole of its result by scanning the
// points of the candidate shells (PolygonBuilder::placeFreeHoles: holes x shell points): a basin
// polygon with thousands of islands overlaid with a few small pieces spent most of its time
// there. Holes that the other operand cannot touch are taken out before the overlay and put back
// after it, into the result polygon that contains them.

// The holes of p whose envelope, grown by `hair`, meets none of `touch` (sorted by MinX): removed
// from p and returned.
std::vector<std::unique_ptr<OGRLinearRing>> detach_far_holes(OGRPolygon& p, const std::vector<OGREnvelope>& touch,
                                                             double hair) {
  std::vector<std::unique_ptr<OGRLinearRing>> far;
  if (p.getNumInteriorRings() < 32) return far;  // not worth it
  OGRPolygon core;
  core.addRing(const_cast<OGRLinearRing*>(p.getExteriorRing()));
  for (int k = 0; k < p.getNumInteriorRings(); ++k) {
    const OGRLinearRing* h = p.getInteriorRing(k);
    OGREnvelope e;
    h->getEnvelope(&e);
    e.MinX -= hair; e.MinY -= hair; e.MaxX += hair; e.MaxY += hair;
    bool meets = false;
    for (const OGREnvelope& t : touch) {
      if (t.MinX > e.MaxX) break;
      if (t.Intersects(e)) { meets = true; break; }
    }
    if (meets) core.addRing(const_cast<OGRLinearRing*>(h));
    else far.emplace_back(h->clone());
  }
  if (!far.empty()) p = core;
  return far;
}

// Puts each hole back into the polygon of ps whose outer ring contains it (by its first vertex;
// the holes touch nothing). Holes no polygon takes are returned.
std::vector<std::unique_ptr<OGRLinearRing>> attach_holes(std::vector<std::unique_ptr<OGRPolygon>>& ps,
                                                         std::vector<std::unique_ptr<OGRLinearRing>>& holes) {
  std::vector<std::unique_ptr<OGRLinearRing>> left;
  if (holes.empty()) return left;
  if (ps.size() == 1) {
    for (auto& h : holes) ps[0]->addRingDirectly(h.release());
    holes.clear();
    return left;
  }
  std::vector<OGREnvelope> env(ps.size());
  std::vector<std::unique_ptr<OGRPolygon>> shells(ps.size());
  std::vector<std::unique_ptr<Prepared>> prep(ps.size());
  for (std::size_t i = 0; i < ps.size(); ++i) ps[i]->getEnvelope(&env[i]);
  for (auto& h : holes) {
    OGRPoint pt(h->getX(0), h->getY(0));
    bool placed = false;
    for (std::size_t i = 0; i < ps.size() && !placed; ++i) {
      if (!(env[i].MinX <= pt.getX() && pt.getX() <= env[i].MaxX && env[i].MinY <= pt.getY() && pt.getY() <= env[i].MaxY))
        continue;
      if (!prep[i]) {
        shells[i] = std::make_unique<OGRPolygon>();
        shells[i]->addRing(const_cast<OGRLinearRing*>(ps[i]->getExteriorRing()));
        prep[i] = std::make_unique<Prepared>(shells[i].get());
      }
      if (prep[i]->contains(&pt)) {
        ps[i]->addRingDirectly(h.release());
        placed = true;
      }
    }
    if (!placed) left.push_back(std::move(h));
  }
  holes.clear();
  return left;
}

// ps with the holes put back (attach_holes); a hole no polygon takes (cannot happen: the holes
// touch nothing) is left to the overlay. ps is emptied.
GeomPtr with_holes(std::vector<std::unique_ptr<OGRPolygon>>& ps, std::vector<std::unique_ptr<OGRLinearRing>>& holes,
                   const char* what) {
  auto left = attach_holes(ps, holes);
  GeomPtr m = multi(ps);
  if (left.empty()) return m;
  auto hm = std::make_unique<OGRMultiPolygon>();
  for (auto& h : left) {
    auto hp = std::make_unique<OGRPolygon>();
    hp->addRingDirectly(h.release());
    hm->addGeometryDirectly(hp.release());
  }
  return checked(m->Difference(hm.get()), what);
}

// The union of polygon pieces, overlaid only where they meet. Why: GEOS's cascaded union of a
// polygon with a thousand holes and fifty small pieces overlays the big one at every level of
// its tree (Gulf of Maine: 0.5 s); most pieces meet nothing, and the few that meet the big one
// are united first and overlaid with it once. Pieces are grouped when their envelopes, grown by
// `hair`, meet and the pieces (the smaller one grown by `hair`) intersect; the result equals the
// union of all pieces.
// `family` (optional, one label per piece): pieces with the same label have disjoint interiors
// (the polygons of one valid multipolygon); the others of a group that all share one label are
// overlaid with the big one as they are, without a cascaded union among themselves (the widened
// water: ten thousand grown pieces that never overlap each other, 2.6 s of union for nothing on
// a GSHHG-h basin).
GeomPtr union_pieces(std::vector<std::unique_ptr<OGRPolygon>>& ps, double hair, const char* what,
                     const std::vector<int>* family = nullptr) {
  const std::size_t n = ps.size();
  if (n <= 1) return GeomPtr(multi(ps).release());
  std::vector<OGREnvelope> env(n);
  std::vector<int> npts(n);
  for (std::size_t i = 0; i < n; ++i) {
    ps[i]->getEnvelope(&env[i]);
    int c = ps[i]->getExteriorRing()->getNumPoints();
    for (int k = 0; k < ps[i]->getNumInteriorRings(); ++k) c += ps[i]->getInteriorRing(k)->getNumPoints();
    npts[i] = c;
  }
  std::vector<std::size_t> parent(n);
  for (std::size_t i = 0; i < n; ++i) parent[i] = i;
  auto find = [&](std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return env[a].MinX != env[b].MinX ? env[a].MinX < env[b].MinX : a < b;
  });
  std::vector<std::unique_ptr<Prepared>> prep(n);
  std::vector<GeomPtr> grown(n);
  for (std::size_t a = 0; a < n; ++a) {
    const std::size_t i = order[a];
    for (std::size_t b = a + 1; b < n; ++b) {
      const std::size_t j = order[b];
      if (env[j].MinX > env[i].MaxX + hair) break;
      if (env[j].MinY > env[i].MaxY + hair || env[i].MinY > env[j].MaxY + hair) continue;
      if (find(i) == find(j)) continue;
      const std::size_t big = npts[i] >= npts[j] ? i : j, small = big == i ? j : i;
      if (!prep[big]) prep[big] = std::make_unique<Prepared>(ps[big].get());
      if (hair > 0 && !grown[small]) grown[small] = checked(ps[small]->Buffer(hair, 1), "buffer");
      if (prep[big]->intersects(hair > 0 ? grown[small].get() : ps[small].get())) parent[find(i)] = find(j);
    }
  }
  std::vector<std::vector<std::size_t>> groups(n);
  for (std::size_t i = 0; i < n; ++i) groups[find(i)].push_back(i);
  std::vector<std::unique_ptr<OGRPolygon>> out;
  for (std::size_t i = 0; i < n; ++i) {  // in the order of each group's first piece
    if (find(i) != i && groups[find(i)].front() != i) continue;
    auto& g = groups[find(i)];
    if (g.front() != i) continue;
    if (g.size() == 1) {
      out.push_back(std::move(ps[i]));
      continue;
    }
    std::size_t big = g.front();
    for (std::size_t k : g)
      if (npts[k] > npts[big]) big = k;
    std::vector<std::unique_ptr<OGRPolygon>> rest;
    bool one_family = family != nullptr;
    int label = -1;
    for (std::size_t k : g)
      if (k != big) {
        if (one_family) {
          if (label < 0) label = (*family)[k];
          one_family = (*family)[k] == label;
        }
        rest.push_back(std::move(ps[k]));
      }
    std::vector<OGREnvelope> touch;
    for (const auto& r : rest) {
      touch.emplace_back();
      r->getEnvelope(&touch.back());
    }
    std::sort(touch.begin(), touch.end(), [](const OGREnvelope& a, const OGREnvelope& b) { return a.MinX < b.MinX; });
    auto far = detach_far_holes(*ps[big], touch, hair + 1e-9 * (1 + std::fabs(env[big].MaxX) + std::fabs(env[big].MaxY)));
    auto rm = multi(rest);
    GeomPtr ru = rm->getNumGeometries() > 1 && !one_family ? checked(rm->UnionCascaded(), what) : GeomPtr(rm.release());
    GeomPtr u = checked(ps[big]->Union(ru.get()), what);
    std::vector<std::unique_ptr<OGRPolygon>> ups;
    polygons_of(u.get(), ups);
    GeomPtr uh = with_holes(ups, far, what);
    polygons_of(uh.get(), out);
  }
  ps.clear();
  return GeomPtr(multi(out).release());
}

double area_of(const OGRGeometry* g) {
  std::vector<std::unique_ptr<OGRPolygon>> ps;
  polygons_of(g, ps);
  double a = 0;
  for (const auto& p : ps) a += p->get_Area();
  return a;
}

Point2 inside_point(const OGRGeometry* g) {
  OGRGeometryH h = OGR_G_PointOnSurface(OGRGeometry::ToHandle(const_cast<OGRGeometry*>(g)));
  Point2 p{0, 0};
  if (h) {
    p = {OGR_G_GetX(h, 0), OGR_G_GetY(h, 0)};
    OGR_G_DestroyGeometry(h);
  } else {
    OGRPoint c;
    if (g->Centroid(&c) == OGRERR_NONE) p = {c.getX(), c.getY()};
  }
  return p;
}

// Offset of valid polygons by r (> 0 grows, < 0 shrinks), ring by ring: for a polygon with
// outer ring O and holes H_i, (O - U H_i) (+) r = (O (+) r) - U (H_i (-) r), and the same with
// the signs swapped for shrinking. Why: GEOS buffers a simple ring far faster than a polygon with
// a thousand holes (Gulf of Maine: 0.1 s against 1.5 s), and the holes are independent.
// b minus u, where u's polygons are disjoint (a union's pieces). Those strictly inside b (touching
// neither its boundary nor each other) become holes directly; the overlay gets only the others
// (see detach_far_holes: GEOS places every hole of an overlay's result by a linear scan).
GeomPtr minus_disjoint(GeomPtr b, const OGRGeometry& u, const char* what) {
  std::vector<std::unique_ptr<OGRPolygon>> hps, over;
  polygons_of(&u, hps);
  std::vector<std::unique_ptr<OGRLinearRing>> free_holes;
  if (hps.size() >= 32) {
    GeomPtr bnd(b->Boundary());
    Prepared pb(b.get()), pbnd(bnd.get());
    for (auto& hp : hps) {
      if (hp->getNumInteriorRings() == 0 && !pbnd.intersects(hp.get()) && pb.contains(hp.get()))
        free_holes.emplace_back(hp->getExteriorRing()->clone());
      else
        over.push_back(std::move(hp));
    }
  } else {
    over = std::move(hps);
  }
  if (!over.empty()) {
    GeomPtr ho = multi(over);
    b = checked(b->Difference(ho.get()), what);
  }
  if (!free_holes.empty()) {
    std::vector<std::unique_ptr<OGRPolygon>> bps;
    polygons_of(b.get(), bps);
    b = with_holes(bps, free_holes, what);
  }
  return b;
}

// b minus the disjoint polygons of u that touch b's boundary (islets joined to land), overlaid
// with only the holes of b near them: the other holes are detached first and put back after
// (detach_far_holes; GEOS places every hole of an overlay's result by a linear scan).
GeomPtr minus_touching(GeomPtr b, const OGRGeometry& u, const char* what) {
  std::vector<std::unique_ptr<OGRPolygon>> bps, ups;
  polygons_of(b.get(), bps);
  polygons_of(&u, ups);
  std::vector<OGREnvelope> touch(ups.size());
  for (std::size_t i = 0; i < ups.size(); ++i) ups[i]->getEnvelope(&touch[i]);
  std::sort(touch.begin(), touch.end(), [](const OGREnvelope& x, const OGREnvelope& y) { return x.MinX < y.MinX; });
  std::vector<std::unique_ptr<OGRLinearRing>> far;
  for (auto& p : bps) {
    OGREnvelope e;
    p->getEnvelope(&e);
    auto f = detach_far_holes(*p, touch, 1e-9 * (1 + std::fabs(e.MaxX) + std::fabs(e.MaxY)));
    for (auto& h : f) far.push_back(std::move(h));
  }
  GeomPtr core = multi(bps);
  GeomPtr d = checked(core->Difference(&u), what);
  std::vector<std::unique_ptr<OGRPolygon>> dps;
  polygons_of(d.get(), dps);
  return with_holes(dps, far, what);
}

// Ring r without the vertices that lie within eps of the vertex kept before them (and the
// closure's). Why: an earlier buffer's output can hold a cluster of vertices 1e-10 m apart (on a
// GSHHG-h ocean basin, three of them where an islet joined to land rounded a corner); buffering
// such a ring again, GEOS's noding fails and it retries the whole ring at reduced precision:
// 0.2 s -> 2.2 s for one 280 000-vertex ring. Nothing else moves; a ring that would lose its
// area is left as it is.
void drop_near_repeats(OGRLinearRing* r, double eps) {
  const int n = r->getNumPoints();
  if (n < 5) return;
  const double e2 = eps * eps;
  std::vector<int> keep{0};
  for (int i = 1; i + 1 < n; ++i) {
    const double dx = r->getX(i) - r->getX(keep.back()), dy = r->getY(i) - r->getY(keep.back());
    if (dx * dx + dy * dy > e2) keep.push_back(i);
  }
  while (keep.size() > 1) {  // the last kept against the first (the closure)
    const double dx = r->getX(keep.back()) - r->getX(0), dy = r->getY(keep.back()) - r->getY(0);
    if (dx * dx + dy * dy > e2) break;
    keep.pop_back();
  }
  if (keep.size() + 1 == static_cast<std::size_t>(n) || keep.size() < 3) return;
  OGRLinearRing c;
  c.setNumPoints(static_cast<int>(keep.size()) + 1, FALSE);
  for (std::size_t k = 0; k < keep.size(); ++k) c.setPoint(static_cast<int>(k), r->getX(keep[k]), r->getY(keep[k]));
  c.setPoint(static_cast<int>(keep.size()), r->getX(0), r->getY(0));
  *r = c;
}

// g grown by r (shrunk for r < 0); near_repeats: g is an earlier buffer's output, its clusters
// of vertices within 1e-6 r are merged first (drop_near_repeats).
GeomPtr offset(const OGRGeometry& g, double r, int quad_segs = kQuadSegs, bool near_repeats = false) {
  std::vector<std::unique_ptr<OGRPolygon>> polys;
  polygons_of(&g, polys);
  std::vector<std::unique_ptr<OGRPolygon>> out;
  for (const auto& p : polys) {
    if (near_repeats) {
      const double eps = 1e-6 * std::fabs(r);
      drop_near_repeats(p->getExteriorRing(), eps);
      for (int k = 0; k < p->getNumInteriorRings(); ++k) drop_near_repeats(p->getInteriorRing(k), eps);
    }
    OGRPolygon outer;
    outer.addRing(const_cast<OGRLinearRing*>(p->getExteriorRing()));
    GeomPtr b;
    auto holes = std::make_unique<OGRMultiPolygon>();
    auto buffer_outer = [&] { b = checked(outer.Buffer(r, quad_segs), "buffer of an outer ring"); };
    auto buffer_holes = [&] {
      for (int k = 0; k < p->getNumInteriorRings(); ++k) {
        OGRPolygon hp;
        hp.addRing(const_cast<OGRLinearRing*>(p->getInteriorRing(k)));
        GeomPtr hb = checked(hp.Buffer(-r, quad_segs), "buffer of a hole");
        std::vector<std::unique_ptr<OGRPolygon>> hps;
        polygons_of(hb.get(), hps);
        for (auto& h : hps) holes->addGeometryDirectly(h.release());
      }
    };
    // The outer ring's buffer and the holes' on two cores when both are big (an ocean basin:
    // seconds each); the same geometries in the same order either way.
    std::size_t hole_points = 0;
    for (int k = 0; k < p->getNumInteriorRings(); ++k) hole_points += static_cast<std::size_t>(p->getInteriorRing(k)->getNumPoints());
    if (max_threads() >= 2 && hole_points > 2000 && p->getExteriorRing()->getNumPoints() > 2000) {
      run_beside([&] {
        GdalQuiet quiet;
        buffer_holes();
      }, buffer_outer);
    } else {
      buffer_outer();
      if (!b->IsEmpty()) buffer_holes();
    }
    if (b->IsEmpty()) continue;
    if (p->getNumInteriorRings() > 0) {
      if (!holes->IsEmpty()) {
        std::vector<std::unique_ptr<OGRPolygon>> hv;
        polygons_of(holes.get(), hv);
        GeomPtr hu = union_pieces(hv, 1e-6 * std::fabs(r), "union of holes");
        b = minus_disjoint(std::move(b), *hu, "outer ring minus holes");
      }
    }
    polygons_of(b.get(), out);
  }
  if (r > 0 && out.size() > 1) return union_pieces(out, 1e-6 * r, "union of grown pieces");
  return GeomPtr(multi(out).release());
}

// The vertices two rings of g (or one ring twice) share: pinch points, where the water is zero
// wide. Ring closures do not count.
std::vector<Point2> pinch_points(const OGRGeometry* g) {
  std::vector<std::unique_ptr<OGRPolygon>> ps;
  polygons_of(g, ps);
  std::vector<std::pair<double, double>> v;
  for (const auto& p : ps)
    for (int k = -1; k < p->getNumInteriorRings(); ++k) {
      const OGRLinearRing* r = k < 0 ? p->getExteriorRing() : p->getInteriorRing(k);
      for (int i = 0; i + 1 < r->getNumPoints(); ++i) v.emplace_back(r->getX(i), r->getY(i));
    }
  std::sort(v.begin(), v.end());
  std::vector<Point2> out;
  for (std::size_t i = 0; i + 1 < v.size(); ++i)
    if (v[i] == v[i + 1] && (out.empty() || !(out.back().x == v[i].first && out.back().y == v[i].second)))
      out.push_back({v[i].first, v[i].second});
  return out;
}


// a - b for two polygonal geometries whose boundaries share most of their segments bit for bit
// (the two openings, both given the closed water's exact coast back). Why: GEOS overlays the
// whole of both (an ocean basin: 10 s, most of it in its snapping fallback where two rings differ
// by a vertex). The boundary of a - b lies on the segments that are not shared with the same
// interior side (such a segment has a and b on the same side, so a - b on neither), so every
// face of the arrangement of the non-shared segments lies wholly inside a - b or wholly outside
// it: the segments are noded, polygonized, and each face is kept when an inner point lies in a
// and not in b. (A shared ring inside a face, an island both keep, cannot border a - b, so such a
// face is outside it, and any inner point says so.) FDR_DIFF_OVERLAY: GEOS's overlay (for the
// test that the results are the same).
GeomPtr difference_by_faces(const OGRGeometry* a, const OGRGeometry* b, const char* what) {
  using Key = std::array<std::uint64_t, 4>;
  struct KeyHash {
    std::size_t operator()(const Key& k) const {
      std::uint64_t h = 0x9E3779B97F4A7C15ull;
      for (std::uint64_t v : k) h = (h ^ v) * 0x100000001B3ull + (h >> 29);
      return static_cast<std::size_t>(h);
    }
  };
  // Directed, with the polygon's interior on the left: a segment both have with their interiors
  // on opposite sides (where b is not inside a) is not shared.
  auto key = [](double x0, double y0, double x1, double y1, bool left) {
    if (!left) {
      std::swap(x0, x1);
      std::swap(y0, y1);
    }
    Key k;
    std::memcpy(&k[0], &x0, 8);
    std::memcpy(&k[1], &y0, 8);
    std::memcpy(&k[2], &x1, 8);
    std::memcpy(&k[3], &y1, 8);
    return k;
  };
  std::vector<std::unique_ptr<OGRPolygon>> pa, pb;
  polygons_of(a, pa);
  polygons_of(b, pb);
  struct Ring {
    const OGRLinearRing* r;
    bool left;  // the interior lies left of its segments
  };
  auto rings = [](const std::vector<std::unique_ptr<OGRPolygon>>& ps) {
    std::vector<Ring> rs;
    for (const auto& p : ps)
      for (int k = -1; k < p->getNumInteriorRings(); ++k) {
        const OGRLinearRing* r = k < 0 ? p->getExteriorRing() : p->getInteriorRing(k);
        rs.push_back({r, (k < 0) != static_cast<bool>(r->isClockwise())});
      }
    return rs;
  };
  const auto ra = rings(pa), rb = rings(pb);
  auto keys_of = [&](const std::vector<Ring>& rs) {
    std::size_t n = 0;
    for (const Ring& q : rs) n += static_cast<std::size_t>(std::max(0, q.r->getNumPoints() - 1));
    std::unordered_set<Key, KeyHash> s;
    s.reserve(n);
    for (const Ring& q : rs)
      for (int i = 0; i + 1 < q.r->getNumPoints(); ++i)
        s.insert(key(q.r->getX(i), q.r->getY(i), q.r->getX(i + 1), q.r->getY(i + 1), q.left));
    return s;
  };
  DebugLaps dl("  by faces");
  std::unordered_set<Key, KeyHash> ka, kb;
  run_beside([&] { ka = keys_of(ra); }, [&] { kb = keys_of(rb); });
  dl("keys");
  // The non-shared segments, as maximal runs.
  OGRMultiLineString lines;
  auto add_runs = [&](const std::vector<Ring>& rs, const std::unordered_set<Key, KeyHash>& other) {
    for (const Ring& q : rs) {
      const OGRLinearRing* r = q.r;
      const int n = r->getNumPoints();
      if (n < 2) continue;
      std::vector<char> own(static_cast<std::size_t>(n - 1));
      bool any = false, all = true;
      for (int i = 0; i + 1 < n; ++i) {
        own[static_cast<std::size_t>(i)] = other.count(key(r->getX(i), r->getY(i), r->getX(i + 1), r->getY(i + 1), q.left)) ? 0 : 1;
        any = any || own[static_cast<std::size_t>(i)];
        all = all && own[static_cast<std::size_t>(i)];
      }
      if (!any) continue;
      // Start at a shared segment so that a run does not wrap around the closure.
      int s = 0;
      if (!all)
        while (own[static_cast<std::size_t>(s)]) ++s;
      auto line = std::make_unique<OGRLineString>();
      for (int t = 0; t < n - 1; ++t) {
        const int i = (s + t) % (n - 1);
        if (own[static_cast<std::size_t>(i)]) {
          if (line->getNumPoints() == 0) line->addPoint(r->getX(i), r->getY(i));
          line->addPoint(r->getX(i + 1), r->getY(i + 1));
        } else if (line->getNumPoints() > 0) {
          lines.addGeometryDirectly(line.release());
          line = std::make_unique<OGRLineString>();
        }
      }
      if (line->getNumPoints() > 0) lines.addGeometryDirectly(line.release());
    }
  };
  add_runs(ra, kb);
  add_runs(rb, ka);
  if (lines.IsEmpty()) return GeomPtr(new OGRMultiPolygon());
  auto fallback = [&] {
    if (debug::value(debug::Aid::kFilter)) std::fprintf(stderr, "difference by faces: overlay fallback\n");
    return checked(a->Difference(b), what);
  };
  // Noded: the union of the lines with one of them nodes them all (OGR 3.6 has no unary union).
  std::unique_ptr<OGRGeometry> first(lines.getGeometryRef(0)->clone());
  GeomPtr noded(lines.Union(first.get()));
  dl("noded");
  if (!noded) return fallback();
  GeomPtr faces(noded->Polygonize());
  dl("polygonized");
  if (!faces) return fallback();
  std::vector<std::unique_ptr<OGRPolygon>> fs, out;
  polygons_of(faces.get(), fs);
  const Prepared in_a(a), in_b(b);
  for (auto& f : fs) {
    const Point2 p = inside_point(f.get());
    const OGRPoint pt(p.x, p.y);
    if (in_a.contains(&pt) && !in_b.contains(&pt)) out.push_back(std::move(f));
  }
  dl("faces");
  if (debug::value(debug::Aid::kFilter))
    std::fprintf(stderr, "difference by faces: %d lines, %zu faces, %zu pieces\n", lines.getNumGeometries(), fs.size(), out.size());
  return GeomPtr(multi(out).release());
}

// Rebuilds every polygon of ps with the holes for which keep(hole, |area|) is true (called once
// per hole, in order); true when some hole was dropped.
template <class Keep>
bool filter_holes(std::vector<std::unique_ptr<OGRPolygon>>& ps, Keep keep) {
  bool dropped = false;
  for (auto& p : ps) {
    if (p->getNumInteriorRings() == 0) continue;
    OGRPolygon q;
    q.addRing(const_cast<OGRLinearRing*>(p->getExteriorRing()));
    for (int k = 0; k < p->getNumInteriorRings(); ++k) {
      const OGRLinearRing* h = p->getInteriorRing(k);
      if (keep(h, std::fabs(h->get_Area()))) q.addRing(const_cast<OGRLinearRing*>(h));
      else dropped = true;
    }
    *p = q;
  }
  return dropped;
}

// open(g, r) = (g - r) + r. Empty when nothing of g is wider than 2r.
GeomPtr opening(const OGRGeometry& g, double r) {
  GeomPtr eroded = offset(g, -r);
  if (eroded->IsEmpty()) return eroded;
  return offset(*eroded, r, kQuadSegs, true);
}


// An OGR ring from vertices without the closing repeat.
OGRLinearRing closed_ring(const std::vector<Point2>& ring) {
  OGRLinearRing r;
  r.setNumPoints(static_cast<int>(ring.size()) + 1, FALSE);
  for (std::size_t i = 0; i < ring.size(); ++i) r.setPoint(static_cast<int>(i), ring[i].x, ring[i].y);
  r.setPoint(static_cast<int>(ring.size()), ring[0].x, ring[0].y);
  return r;
}

OGRPolygon to_ogr(const Rings& rings) {
  OGRPolygon p;
  for (const auto& ring : rings) {
    if (ring.size() < 3) continue;
    OGRLinearRing r = closed_ring(ring);
    p.addRing(&r);
  }
  return p;
}

double signed_area(const std::vector<Point2>& r) {
  double a = 0;
  for (std::size_t i = 0, n = r.size(); i < n; ++i) {
    const Point2 p = r[i], q = r[(i + 1) % n];
    a += (p.x - r[0].x) * (q.y - r[0].y) - (q.x - r[0].x) * (p.y - r[0].y);
  }
  return 0.5 * a;
}

// Small convex-geometry helpers for joining islets to nearby land (doubles: these decide
// where new coast goes, not the mesh; the mesher's exact predicates check the result).
// Convex hull, counter-clockwise, without collinear points (Andrew's monotone chain).
std::vector<Point2> convex_hull(std::vector<Point2> p) {
  std::sort(p.begin(), p.end(), [](Point2 a, Point2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  p.erase(std::unique(p.begin(), p.end(), [](Point2 a, Point2 b) { return a.x == b.x && a.y == b.y; }), p.end());
  if (p.size() < 3) return p;
  std::vector<Point2> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && predicates::orient2d(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && predicates::orient2d(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  return h;
}
bool segments_meet(Point2 a, Point2 b, Point2 c, Point2 d) {
  const int o1 = predicates::orient2d(a, b, c), o2 = predicates::orient2d(a, b, d);
  const int o3 = predicates::orient2d(c, d, a), o4 = predicates::orient2d(c, d, b);
  auto on = [](Point2 p, Point2 q, Point2 r) {  // r on segment pq, collinear
    return std::min(p.x, q.x) <= r.x && r.x <= std::max(p.x, q.x) && std::min(p.y, q.y) <= r.y && r.y <= std::max(p.y, q.y);
  };
  if (o1 != o2 && o3 != o4 && o1 * o2 <= 0 && o3 * o4 <= 0) return true;
  return (o1 == 0 && on(a, b, c)) || (o2 == 0 && on(a, b, d)) || (o3 == 0 && on(c, d, a)) || (o4 == 0 && on(c, d, b));
}
double segment_distance(Point2 a, Point2 b, Point2 c, Point2 d) {
  if (segments_meet(a, b, c, d)) return 0;
  return std::min({dist_to_segment(a, c, d), dist_to_segment(b, c, d), dist_to_segment(c, a, b), dist_to_segment(d, a, b)});
}
// Disks (centre, radius) by the cells of a uniform grid their boxes cover: which of them may
// meet a box. For the islets' triangles (thousands on an ocean basin, each placement testing
// every one before).
class DiskGrid {
 public:
  explicit DiskGrid(double cell) : cell_(cell > 0 ? cell : 1) {}
  void add(std::uint32_t id, Point2 c, double r) {
    cells({{c.x - r, c.y - r}, {c.x + r, c.y + r}}, [&](std::uint64_t k) {
      m_[k].push_back(id);
      return false;
    });
  }
  // The ids of the disks whose boxes may meet b, ascending, without repeats.
  void near(const Box2& b, std::vector<std::uint32_t>* out) const {
    out->clear();
    cells(b, [&](std::uint64_t k) {
      if (auto it = m_.find(k); it != m_.end()) out->insert(out->end(), it->second.begin(), it->second.end());
      return false;
    });
    std::sort(out->begin(), out->end());
    out->erase(std::unique(out->begin(), out->end()), out->end());
  }

 private:
  template <class F>
  void cells(const Box2& b, F f) const {
    const auto i0 = static_cast<std::int64_t>(std::floor(b.lo.x / cell_)), i1 = static_cast<std::int64_t>(std::floor(b.hi.x / cell_));
    const auto j0 = static_cast<std::int64_t>(std::floor(b.lo.y / cell_)), j1 = static_cast<std::int64_t>(std::floor(b.hi.y / cell_));
    for (std::int64_t i = i0; i <= i1; ++i)
      for (std::int64_t j = j0; j <= j1; ++j)
        if (f((static_cast<std::uint64_t>(i) << 32) ^ static_cast<std::uint64_t>(static_cast<std::uint32_t>(j)))) return;
  }
  double cell_;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> m_;
};

Box2 box_of(const std::vector<Point2>& pts) {
  Box2 b;
  for (Point2 q : pts) b.add(q);
  return b;
}
// p farther than r from box b (a cheap test before the exact ones).
bool beyond(Point2 p, double r, const Box2& b) {
  return p.x < b.lo.x - r || p.x > b.hi.x + r || p.y < b.lo.y - r || p.y > b.hi.y + r;
}
// Boxes a and b farther apart than r along x or y.
bool apart(const Box2& a, const Box2& b, double r) {
  return a.lo.x > b.hi.x + r || b.lo.x > a.hi.x + r || a.lo.y > b.hi.y + r || b.lo.y > a.hi.y + r;
}
bool inside_convex(Point2 p, const std::vector<Point2>& h) {  // closed
  for (std::size_t i = 0; i < h.size(); ++i)
    if (predicates::orient2d(h[i], h[(i + 1) % h.size()], p) < 0) return false;
  return true;
}
// Distance from segment ab to the convex polygon h (0 when they meet).
double convex_distance(Point2 a, Point2 b, const std::vector<Point2>& h) {
  if (inside_convex(a, h) || inside_convex(b, h)) return 0;
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < h.size(); ++i) d = std::min(d, segment_distance(a, b, h[i], h[(i + 1) % h.size()]));
  return d;
}

std::vector<Point2> ring_points(const OGRLinearRing* r, bool ccw) {
  std::vector<Point2> pts(static_cast<std::size_t>(r->getNumPoints()));
  for (int i = 0; i < r->getNumPoints(); ++i) pts[static_cast<std::size_t>(i)] = {r->getX(i), r->getY(i)};
  if (pts.size() >= 2 && pts.front() == pts.back()) pts.pop_back();
  // Consecutive duplicates (GEOS does not produce them, but be safe).
  pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
  if ((signed_area(pts) > 0) != ccw) std::reverse(pts.begin(), pts.end());
  return pts;
}

// a - b when b lies inside a and their boundaries run together (a closing and the ring it
// closed, an island and its opening, closed water and the tips cut from it): by
// pslg::contained_difference, which makes the near contacts exact and traces the faces without
// noding; GEOS's overlay when that refuses (it says why under FDR_DEBUG_FILTER).
// FDR_DIFF_OVERLAY: always GEOS's overlay (to compare).
GeomPtr traced_difference(const OGRGeometry& a, const OGRGeometry& b, const char* what) {
  static const bool overlay_only = std::getenv("FDR_DIFF_OVERLAY") != nullptr;
  if (!overlay_only) {
    auto sets = [](const OGRGeometry& g, double& mag) {
      std::vector<std::unique_ptr<OGRPolygon>> ps;
      polygons_of(&g, ps);
      pslg::PolygonSet out;
      for (const auto& p : ps) {
        pslg::PolygonRings pr;
        for (int k = -1; k < p->getNumInteriorRings(); ++k) {
          const OGRLinearRing* r = k < 0 ? p->getExteriorRing() : p->getInteriorRing(k);
          std::vector<Point2> pts(static_cast<std::size_t>(std::max(0, r->getNumPoints() - 1)));
          for (std::size_t i = 0; i < pts.size(); ++i) {
            pts[i] = {r->getX(static_cast<int>(i)), r->getY(static_cast<int>(i))};
            mag = std::max({mag, std::fabs(pts[i].x), std::fabs(pts[i].y)});
          }
          pr.push_back(std::move(pts));
        }
        out.push_back(std::move(pr));
      }
      return out;
    };
    double mag = 0;
    pslg::PolygonSet pa = sets(a, mag), pb = sets(b, mag);
    // Rounding in GEOS's offsets is up to a few ulps of the coordinates (1e-9 m at 2000 km).
    const double eps = 1e-11 * (1 + mag);
    pslg::ContainedDifferenceStats st;
    const auto t0 = std::chrono::steady_clock::now();
    auto r = pslg::contained_difference(std::move(pa), std::move(pb), eps, &st);
    const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (dt > 0.05 && debug::value(debug::Aid::kFilter))
      std::fprintf(stderr, "%s: contained difference %.3f s (%zu shells out, %zu snapped, %zu inserted, %zu cut, %zu dropped)\n", what, dt,
                   r ? r->size() : 0, st.snapped, st.inserted, st.cut, st.dropped);
    if (r) {
      auto m = std::make_unique<OGRMultiPolygon>();
      for (const auto& pr : *r) {
        auto p = std::make_unique<OGRPolygon>();
        for (const auto& ring : pr) {
          OGRLinearRing lr = closed_ring(ring);
          p->addRing(&lr);
        }
        m->addGeometryDirectly(p.release());
      }
      if (std::getenv("FDR_CHECK_TRACED")) {  // developer check: against GEOS's overlay
        GeomPtr g = checked(a.Difference(&b), what);
        GeomPtr x(m->SymDifference(g.get()));
        const double ag = area_of(g.get()), ax = x ? area_of(x.get()) : -1;
        if (!m->IsValid() || !(ax >= 0) || ax > 1e-6 * std::max(1.0, ag))
          std::fprintf(stderr, "%s: traced area %.6f, GEOS %.6f, symmetric difference %.6g, valid %d\n", what,
                       area_of(m.get()), ag, ax, static_cast<int>(m->IsValid()));
      }
      return GeomPtr(m.release());
    }
    if (debug::value(debug::Aid::kFilter))
      std::fprintf(stderr, "%s: not traced (%s)\n", what, st.refused ? st.refused : "?");
  }
  return nullptr;
}

GeomPtr difference_contained(const OGRGeometry& a, const OGRGeometry& b, const char* what) {
  if (GeomPtr r = traced_difference(a, b, what)) return r;
  return checked(a.Difference(&b), what);
}

// Moves every vertex within `hair` of an input vertex onto the nearest one (ties: the smaller
// x, then y), so boundaries the buffers left unchanged up to rounding are bitwise the input's.
class Snapper {
 public:
  Snapper(const OGRGeometry* input, double hair) : hair_(hair) {
    std::vector<std::unique_ptr<OGRPolygon>> ps;
    polygons_of(input, ps);
    for (const auto& w : ps)
      for (int k = -1; k < w->getNumInteriorRings(); ++k) {
        const OGRLinearRing* r = k < 0 ? w->getExteriorRing() : w->getInteriorRing(k);
        for (int i = 0; i < r->getNumPoints(); ++i)
          cells_[key(cell(r->getX(i)), cell(r->getY(i)))].push_back({r->getX(i), r->getY(i)});
      }
  }
  void snap(OGRPolygon* p) const {
    snap_ring(p->getExteriorRing());
    for (int k = 0; k < p->getNumInteriorRings(); ++k) snap_ring(p->getInteriorRing(k));
  }

 private:
  std::int64_t cell(double v) const { return static_cast<std::int64_t>(std::floor(v / hair_)); }
  static std::uint64_t key(std::int64_t i, std::int64_t j) {
    return (static_cast<std::uint64_t>(i) << 32) ^ static_cast<std::uint64_t>(j & 0xffffffff);
  }
  void snap_ring(OGRLinearRing* r) const {
    for (int i = 0; i < r->getNumPoints(); ++i) {
      const double x = r->getX(i), y = r->getY(i);
      double best = hair_;
      Point2 to{x, y};
      bool found = false;
      const std::int64_t ci = cell(x), cj = cell(y);
      for (std::int64_t di = -1; di <= 1; ++di)
        for (std::int64_t dj = -1; dj <= 1; ++dj) {
          const auto it = cells_.find(key(ci + di, cj + dj));
          if (it == cells_.end()) continue;
          for (const Point2 q : it->second) {
            const double d = std::hypot(q.x - x, q.y - y);
            if (d < best || (d == best && found && (q.x < to.x || (q.x == to.x && q.y < to.y)))) {
              best = d;
              to = q;
              found = true;
            }
          }
        }
      if (found) r->setPoint(i, to.x, to.y);
    }
  }
  double hair_;
  std::unordered_map<std::uint64_t, std::vector<Point2>> cells_;
};

// pslg::find_contacts on two cores: the segments are split at the median of their left ends into
// those reaching left of it and those reaching right of it (a segment across it goes to both),
// each half is searched on its own, and the results are concatenated (segment indices into
// `segs`; a contact may be listed twice). The same contacts as one search: two segments that
// meet share a point, and both reach that point's side; a point inside a segment lies in its
// x-range, so it and the segments ending at it are in a half with that segment. For callers that
// use the contacts as a set (or only whether there are any). Small inputs: one search.
pslg::Contacts find_contacts_2(const std::vector<Point2>& pts, const std::vector<pslg::Segment>& segs,
                               const std::vector<char>* alive) {
  if (segs.size() < 20000 || max_threads() < 2) return pslg::find_contacts(pts, segs, alive);
  std::vector<double> lo(segs.size());
  for (std::size_t i = 0; i < segs.size(); ++i)
    lo[i] = std::min(pts[static_cast<std::size_t>(segs[i].a)].x, pts[static_cast<std::size_t>(segs[i].b)].x);
  std::vector<double> sorted = lo;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
  const double split = sorted[sorted.size() / 2];
  auto half = [&](bool left) {
    std::vector<pslg::Segment> sub;
    std::vector<std::size_t> id;
    std::vector<char> live(pts.size(), 0);
    for (std::size_t i = 0; i < segs.size(); ++i) {
      const double hi = std::max(pts[static_cast<std::size_t>(segs[i].a)].x, pts[static_cast<std::size_t>(segs[i].b)].x);
      if (left ? !(lo[i] <= split) : !(hi >= split)) continue;
      sub.push_back(segs[i]);
      id.push_back(i);
      for (const Index e : {segs[i].a, segs[i].b})
        if (!alive || (*alive)[static_cast<std::size_t>(e)]) live[static_cast<std::size_t>(e)] = 1;
    }
    pslg::Contacts c = pslg::find_contacts(pts, sub, &live);
    for (auto& [x, y] : c.segment_pairs) {
      x = static_cast<Index>(id[static_cast<std::size_t>(x)]);
      y = static_cast<Index>(id[static_cast<std::size_t>(y)]);
    }
    for (auto& vs : c.vertex_on_segment) vs.second = static_cast<Index>(id[static_cast<std::size_t>(vs.second)]);
    return c;
  };
  auto right_job = std::async(std::launch::async, half, false);
  pslg::Contacts out = half(true);
  pslg::Contacts r = right_job.get();
  out.segment_pairs.insert(out.segment_pairs.end(), r.segment_pairs.begin(), r.segment_pairs.end());
  out.kinds.insert(out.kinds.end(), r.kinds.begin(), r.kinds.end());
  out.vertex_on_segment.insert(out.vertex_on_segment.end(), r.vertex_on_segment.begin(), r.vertex_on_segment.end());
  return out;
}

// A sufficient test of validity with the mesher's exact contact finder: every ring simple, no
// two rings meeting at all, every hole inside the outer ring and none inside another hole.
// Why: GEOS's IsValid on a basin polygon with 10 000 holes costs seconds, this a tenth of a
// second. False does not mean invalid, only that GEOS must decide.
bool surely_valid(const Rings& rings) {
  if (rings.empty()) return false;
  std::vector<Point2> pts;
  std::vector<pslg::Segment> segs;
  for (const auto& r : rings) {
    std::size_t n = r.size();
    if (n >= 2 && r.front() == r.back()) --n;  // closed copy
    if (n < 3) return false;
    const auto base = static_cast<Index>(pts.size());
    for (std::size_t i = 0; i < n; ++i) {
      if (r[i] == r[(i + 1) % n] || !std::isfinite(r[i].x) || !std::isfinite(r[i].y)) return false;
      pts.push_back(r[i]);
    }
    for (std::size_t i = 0; i < n; ++i)
      segs.push_back({base + static_cast<Index>(i), base + static_cast<Index>((i + 1) % n)});
  }
  {  // rings touching at a shared vertex: GEOS decides (they may cut the interior in two)
    std::vector<Point2> sorted = pts;
    std::sort(sorted.begin(), sorted.end(), [](Point2 a, Point2 b) { return a.x != b.x ? a.x < b.x : a.y < b.y; });
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) return false;
  }
  const pslg::Contacts ct = find_contacts_2(pts, segs, nullptr);
  if (!ct.segment_pairs.empty() || !ct.vertex_on_segment.empty()) return false;
  if (rings.size() == 1) return true;
  // Rings are disjoint: one vertex decides on which side of another ring a ring lies.
  OGRPolygon shell;
  {
    Rings outer{rings[0]};
    shell = to_ogr(outer);
  }
  Prepared ps(&shell);
  std::vector<OGREnvelope> env(rings.size());
  for (std::size_t k = 1; k < rings.size(); ++k) {
    OGRPoint q(rings[k][0].x, rings[k][0].y);
    if (!ps.intersects(&q)) return false;  // a hole outside the shell
    for (const Point2 v : rings[k]) env[k].Merge(v.x, v.y);
  }
  // Nested holes: a hole's vertex inside another hole (candidates by envelope, sorted by x).
  std::vector<std::size_t> order;
  for (std::size_t k = 1; k < rings.size(); ++k) order.push_back(k);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return env[a].MinX != env[b].MinX ? env[a].MinX < env[b].MinX : a < b;
  });
  for (std::size_t a = 0; a < order.size(); ++a)
    for (std::size_t b = a + 1; b < order.size(); ++b) {
      const std::size_t i = order[a], j = order[b];
      if (env[j].MinX > env[i].MaxX) break;
      if (!env[i].Intersects(env[j])) continue;
      // The one whose envelope contains the other's may contain it.
      for (const auto& [outer, inner] : {std::pair{i, j}, std::pair{j, i}}) {
        if (!env[outer].Contains(env[inner])) continue;
        const Point2 p = rings[inner][0];
        bool in = false;
        const auto& r = rings[outer];
        for (std::size_t e = 0, m = r.size(); e < m; ++e) {
          const Point2 u = r[e], w = r[(e + 1) % m];
          if ((u.y > p.y) == (w.y > p.y)) continue;
          const int o = predicates::orient2d(u, w, p);  // exact: p is on no ring
          if ((w.y > u.y) ? (o > 0) : (o < 0)) in = !in;
        }
        if (in) return false;
      }
    }
  return true;
}

// Gives the input's exact coast back wherever a buffer result runs within `hair` of it. Why:
// GEOS rounds every corner of an offset with arc points, so after a closing or an opening the
// unchanged coast comes back as 2-5 points per input vertex (113k input vertices of an ocean
// basin became 600k), which every later overlay, the cleaning (thousands of snap/zero-length
// repairs) and the resampling pay for. A run of consecutive result vertices each within hair of
// the same input ring, advancing along it (each step no longer along the input than the step
// itself plus 2 hair), is replaced by its two end vertices and the input vertices between them;
// only places that moved more than hair (the closed inlets, the rounded corners that matter)
// keep the buffers' vertices. A polygon that the replacement would make invalid (checked with
// the exact contact finder, GEOS deciding when that is unsure) is left as it was.
class CoastRestorer {
 public:
  CoastRestorer(const OGRGeometry* input, double hair) : hair_(hair), on_tol_(1e-3 * hair) {
    std::vector<std::unique_ptr<OGRPolygon>> ps;
    polygons_of(input, ps);
    Box2 box;
    std::size_t nseg = 0;
    double total = 0;
    for (const auto& w : ps)
      for (int k = -1; k < w->getNumInteriorRings(); ++k) {
        const OGRLinearRing* r = k < 0 ? w->getExteriorRing() : w->getInteriorRing(k);
        InRing ir;
        for (int i = 0; i + 1 < r->getNumPoints(); ++i) ir.p.push_back({r->getX(i), r->getY(i)});
        if (ir.p.size() < 3) continue;
        ir.cum.resize(ir.p.size() + 1, 0.0);
        for (std::size_t i = 0; i < ir.p.size(); ++i) {
          box.add(ir.p[i]);
          ir.cum[i + 1] = ir.cum[i] + dist(ir.p[i], ir.p[(i + 1) % ir.p.size()]);
        }
        ir.first_seg = nseg;
        nseg += ir.p.size();
        total += ir.cum.back();
        rings_.push_back(std::move(ir));
      }
    if (rings_.empty() || !(hair > 0)) return;
    box.lo = box.lo - Point2{2 * hair, 2 * hair};
    box.hi = box.hi + Point2{2 * hair, 2 * hair};
    box_ = box;
    grid_ = std::make_unique<pslg::SegmentGrid>(box, nseg, std::max(total / static_cast<double>(nseg), hair));
    seg_ring_.reserve(nseg);
    for (std::size_t k = 0; k < rings_.size(); ++k) {
      const auto& ir = rings_[k];
      for (std::size_t i = 0; i < ir.p.size(); ++i) {
        grid_->add_segment(static_cast<Index>(seg_ring_.size()), ir.p[i], ir.p[(i + 1) % ir.p.size()]);
        seg_ring_.push_back({static_cast<std::uint32_t>(k), static_cast<std::uint32_t>(i)});
      }
    }
  }

  // g with the input's coast given back (a new geometry; g itself when nothing changes).
  GeomPtr restore(GeomPtr g) const {
    if (!grid_ || !g || g->IsEmpty()) return g;
    std::vector<std::unique_ptr<OGRPolygon>> ps;
    polygons_of(g.get(), ps);
    bool any = false;
    for (auto& p : ps) {
      std::vector<Plan> plans(static_cast<std::size_t>(p->getNumInteriorRings() + 1));
      std::size_t points = 0;
      for (int k = -1; k < p->getNumInteriorRings(); ++k) {
        const OGRLinearRing* r = k < 0 ? p->getExteriorRing() : p->getInteriorRing(k);
        Plan& pl = plans[static_cast<std::size_t>(k + 1)];
        pl.v.reserve(static_cast<std::size_t>(std::max(0, r->getNumPoints() - 1)));
        for (int i = 0; i + 1 < r->getNumPoints(); ++i) pl.v.push_back({r->getX(i), r->getY(i)});
        points += pl.v.size();
      }
      // Each ring is planned on its own (plan_ring reads only the input's rings and grid): on
      // two threads when there is enough work, rings claimed in order; the plans are the same.
      {
        std::atomic<std::size_t> next{0};
        auto work = [&] {
          for (std::size_t k; (k = next.fetch_add(1)) < plans.size();) plan_ring(plans[k]);
        };
        if (max_threads() >= 2 && points > 20000) run_beside(work, work);
        else work();
      }
      std::size_t nruns = 0;
      for (Plan& pl : plans) {
        pl.first_run = nruns;
        nruns += pl.runs.size();
      }
      if (nruns == 0) continue;
      // Runs whose new segments meet anything (other than at a shared end) are given up, round
      // after round, until the only contacts left are the buffer's own (valid in GEOS).
      std::vector<char> off(nruns, 0);
      Rings rings;
      // Rounds after the first examine only what the previous round changed: a contact between
      // segments (same coordinates, same run) that were there before was found then and its runs
      // given up, so only contacts near a new segment can give up more (same result, a
      // fraction of the work: an ocean basin's second round checked 400k segments for 20 new).
      // (FDR_RESTORE_FULL_ROUNDS: every round examines everything, as before; for the test that
      // the results are the same)
      const bool full_rounds = std::getenv("FDR_RESTORE_FULL_ROUNDS") != nullptr;
      std::vector<SegKey> prev_keys;  // the previous round's segments
      bool settled = false;
      int rounds = 0;
      for (int round = 0; round < 8 && !settled; ++round, ++rounds) {
        rings.clear();
        std::vector<Point2> pts;
        std::vector<pslg::Segment> segs;
        std::vector<long> tag;  // per segment: global run id, or -1 (the buffer's own)
        for (const auto& pl : plans) {
          std::vector<long> st;
          std::vector<Point2> w = build_ring(pl, off, st);
          const auto base = static_cast<Index>(pts.size());
          for (std::size_t i = 0; i < w.size(); ++i) {
            pts.push_back(w[i]);
            segs.push_back({base + static_cast<Index>(i), base + static_cast<Index>((i + 1) % w.size())});
            tag.push_back(st[i]);
          }
          rings.push_back(std::move(w));
        }
        std::vector<std::size_t> seg_of_pt_prev(pts.size()), seg_of_pt_next(pts.size());
        for (std::size_t si = 0; si < segs.size(); ++si) {
          seg_of_pt_next[static_cast<std::size_t>(segs[si].a)] = si;
          seg_of_pt_prev[static_cast<std::size_t>(segs[si].b)] = si;
        }
        std::vector<std::size_t> bad;  // segments in a contact
        std::vector<SegKey> keys(segs.size());
        for (std::size_t si = 0; si < segs.size(); ++si)
          keys[si] = seg_key(pts[static_cast<std::size_t>(segs[si].a)], pts[static_cast<std::size_t>(segs[si].b)], tag[si]);
        // The segments to examine (all in the first round) and the points among their ends.
        const bool all = round == 0 || full_rounds;
        std::vector<std::size_t> sub;
        std::vector<char> alive;
        if (all) {
          sub.resize(segs.size());
          for (std::size_t si = 0; si < segs.size(); ++si) sub[si] = si;
        } else {
          const std::unordered_set<SegKey, SegKeyHash> prev(prev_keys.begin(), prev_keys.end());
          // A key found twice in this round counts as new in every copy (the previous round
          // may have had one copy only).
          std::unordered_set<SegKey, SegKeyHash> cur, dup;
          cur.reserve(keys.size());
          for (const SegKey& k : keys)
            if (!cur.insert(k).second) dup.insert(k);
          std::vector<char> repeated(segs.size(), 0);
          if (!dup.empty())
            for (std::size_t si = 0; si < segs.size(); ++si) repeated[si] = dup.count(keys[si]) ? 1 : 0;
          local_subset(pts, segs, keys, repeated, prev, sub);
          alive.assign(pts.size(), 0);
          for (std::size_t si : sub) {
            alive[static_cast<std::size_t>(segs[si].a)] = 1;
            alive[static_cast<std::size_t>(segs[si].b)] = 1;
          }
        }
        prev_keys = std::move(keys);
        std::vector<pslg::Segment> sub_segs;
        sub_segs.reserve(sub.size());
        for (std::size_t si : sub) sub_segs.push_back(segs[si]);
        const pslg::Contacts ct = find_contacts_2(pts, sub_segs, all ? nullptr : &alive);
        for (const auto& [x, y] : ct.segment_pairs) { bad.push_back(sub[static_cast<std::size_t>(x)]); bad.push_back(sub[static_cast<std::size_t>(y)]); }
        for (const auto& [v, sg] : ct.vertex_on_segment) {
          bad.push_back(sub[static_cast<std::size_t>(sg)]);
          bad.push_back(seg_of_pt_prev[static_cast<std::size_t>(v)]);
          bad.push_back(seg_of_pt_next[static_cast<std::size_t>(v)]);
        }
        {  // a vertex repeated (rings touching there): the runs that brought it
          std::vector<std::size_t> order;
          order.reserve(pts.size());
          for (std::size_t i = 0; i < pts.size(); ++i)
            if (all || alive[i]) order.push_back(i);
          std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
            return pts[x].x != pts[y].x ? pts[x].x < pts[y].x : (pts[x].y != pts[y].y ? pts[x].y < pts[y].y : x < y);
          });
          for (std::size_t i = 0; i + 1 < order.size(); ++i)
            if (pts[order[i]] == pts[order[i + 1]])
              for (std::size_t q : {order[i], order[i + 1]}) {
                bad.push_back(seg_of_pt_prev[q]);
                bad.push_back(seg_of_pt_next[q]);
              }
        }
        settled = true;
        for (std::size_t si : bad)
          if (tag[si] >= 0 && !off[static_cast<std::size_t>(tag[si])]) {
            off[static_cast<std::size_t>(tag[si])] = 1;
            settled = false;
          }
      }
      if (debug::value(debug::Aid::kFilter) && plans[0].v.size() > 5000) {
        std::size_t nin = 0, nout = 0, noff = 0;
        for (const auto& pl : plans) nin += pl.v.size();
        for (const auto& r : rings) nout += r.size();
        for (char c : off) noff += c != 0;
        std::fprintf(stderr, "restore: %zu -> %zu vertices, %zu runs, %zu given up, settled %d after %d rounds\n", nin,
                     nout, nruns, noff, settled, rounds);
      }
      if (!settled) continue;  // (cap reached: the buffer's coordinates stay)
      bool changed = false;
      for (std::size_t k = 0; k < rings.size() && !changed; ++k) changed = rings[k] != plans[k].v;
      if (!changed) continue;
      for (const auto& r : rings)
        if (r.size() < 3) changed = false;
      if (!changed) continue;
      *p = to_ogr_closed(rings);
      any = true;
    }
    if (!any) return g;
    return GeomPtr(multi(ps).release());
  }

 private:
  struct InRing {
    std::vector<Point2> p;    // without the closing repeat
    std::vector<double> cum;  // arc length at each vertex (cum[n] = perimeter)
    std::size_t first_seg = 0;
  };
  struct Where {
    int ring = -1;
    double s = 0;  // position: segment index + fraction
    double d = 0;  // distance to the input
  };

  // A segment by its exact coordinates (bit patterns) and the run it belongs to.
  using SegKey = std::array<std::uint64_t, 5>;
  struct SegKeyHash {
    std::size_t operator()(const SegKey& k) const {
      std::uint64_t h = 0x9E3779B97F4A7C15ull;
      for (std::uint64_t v : k) h = (h ^ v) * 0x100000001B3ull + (h >> 29);
      return static_cast<std::size_t>(h);
    }
  };
  static SegKey seg_key(Point2 a, Point2 b, long tag) {
    SegKey k;
    std::memcpy(&k[0], &a.x, 8);
    std::memcpy(&k[1], &a.y, 8);
    std::memcpy(&k[2], &b.x, 8);
    std::memcpy(&k[3], &b.y, 8);
    k[4] = static_cast<std::uint64_t>(tag);
    return k;
  }
  static Box2 seg_box(Point2 a, Point2 b) {
    Box2 bx;
    bx.add(a);
    bx.add(b);
    return bx;
  }
  static bool boxes_meet(const Box2& p, const Box2& q) {
    return p.lo.x <= q.hi.x && q.lo.x <= p.hi.x && p.lo.y <= q.hi.y && q.lo.y <= p.hi.y;
  }
  // sub = the segments not in `prev` or repeated (new) and every segment whose bounding box meets a new
  // one's: any contact with a new segment or with an end of one is among them.
  static void local_subset(const std::vector<Point2>& pts, const std::vector<pslg::Segment>& segs,
                           const std::vector<SegKey>& keys, const std::vector<char>& repeated,
                           const std::unordered_set<SegKey, SegKeyHash>& prev, std::vector<std::size_t>& sub) {
    sub.clear();
    std::vector<std::size_t> fresh;
    Box2 fb;
    double len = 0;
    auto P = [&](Index i) { return pts[static_cast<std::size_t>(i)]; };
    for (std::size_t si = 0; si < segs.size(); ++si)
      if (repeated[si] || !prev.count(keys[si])) {
        fresh.push_back(si);
        fb.add(P(segs[si].a));
        fb.add(P(segs[si].b));
        len += dist(P(segs[si].a), P(segs[si].b));
      }
    if (fresh.empty()) return;
    pslg::SegmentGrid grid(fb, fresh.size(), len / static_cast<double>(fresh.size()));
    for (std::size_t k = 0; k < fresh.size(); ++k)
      grid.add_segment(static_cast<Index>(k), P(segs[fresh[k]].a), P(segs[fresh[k]].b));
    std::vector<Index> near;
    for (std::size_t si = 0; si < segs.size(); ++si) {
      const Box2 b = seg_box(P(segs[si].a), P(segs[si].b));
      if (!boxes_meet(b, fb)) continue;
      grid.segments_near(b, &near);
      for (Index k : near)
        if (boxes_meet(b, seg_box(P(segs[fresh[k]].a), P(segs[fresh[k]].b)))) {
          sub.push_back(si);
          break;
        }
    }
  }

  static OGRPolygon to_ogr_closed(const Rings& rings) {
    OGRPolygon p;
    for (const auto& ring : rings) {
      OGRLinearRing r = closed_ring(ring);
      p.addRing(&r);
    }
    return p;
  }

  Where locate(Point2 q, std::vector<Index>& cand) const {
    Where w;
    if (!box_.contains(q)) return w;
    Box2 b;
    b.add(q - Point2{hair_, hair_});
    b.add(q + Point2{hair_, hair_});
    // Every segment of the cells near q, some more than once: the nearest (ties to the smaller
    // id) does not depend on repeats, and reading the cells directly keeps locate() free of the
    // grid's shared stamps, so rings are planned on several threads.
    cand.clear();
    grid_->for_box_cells(b, [&](std::size_t c) {
      const auto& in = grid_->segments_in(c);
      cand.insert(cand.end(), in.begin(), in.end());
    });
    double best = hair_;
    Index best_id = 0;
    for (Index id : cand) {
      const auto [k, i] = seg_ring_[static_cast<std::size_t>(id)];
      const auto& ir = rings_[k];
      const Point2 a = ir.p[i], c = ir.p[(i + 1) % ir.p.size()];
      const double d = dist_to_segment(q, a, c);
      if (d < best || (d == best && w.ring >= 0 && id < best_id)) {
        best = d;
        best_id = id;
        w.d = d;
        const Point2 ac = c - a;
        const double l2 = ac.x * ac.x + ac.y * ac.y;
        double t = l2 > 0 ? ((q.x - a.x) * ac.x + (q.y - a.y) * ac.y) / l2 : 0.0;
        t = std::clamp(t, 0.0, 1.0);
        w.ring = static_cast<int>(k);
        // (the end of the last segment is position 0, not n: positions stay in [0, n))
        w.s = t < 1 ? static_cast<double>(i) + t : static_cast<double>((i + 1) % ir.p.size());
      }
    }
    return w;
  }
  double arc_at(const InRing& ir, double s) const {
    const std::size_t i = static_cast<std::size_t>(s);
    const double t = s - static_cast<double>(i);
    return ir.cum[i] + t * (ir.cum[i + 1] - ir.cum[i]);
  }

  struct Run {
    std::size_t a = 0, len = 0;  // from vertex a, len links
    int dir = 0;                 // along the input ring: +1, -1, 0 (no input vertex between)
  };
  struct Plan {
    std::vector<Point2> v;       // the buffer's ring
    std::vector<Where> at;
    std::size_t start = 0;       // walk from here
    std::vector<Run> runs;       // in walking order; vertices not in a run stay
    std::size_t first_run = 0;   // global id of runs[0]
  };

  void plan_ring(Plan& pl) const {
    const auto& v = pl.v;
    const std::size_t n = v.size();
    if (n < 3) return;
    std::vector<Index> cand;
    pl.at.resize(n);
    for (std::size_t i = 0; i < n; ++i) pl.at[i] = locate(v[i], cand);
    // link[i]: v[i] -> v[i+1] follows the input: +1 forwards, -1 backwards, 2 either (same
    // place), 0 no.
    std::vector<int> link(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
      const Where a = pl.at[i], b = pl.at[(i + 1) % n];
      if (a.ring < 0 || a.ring != b.ring) continue;
      const auto& ir = rings_[static_cast<std::size_t>(a.ring)];
      const double L = ir.cum.back();
      double fwd = arc_at(ir, b.s) - arc_at(ir, a.s);
      if (fwd < 0) fwd += L;
      const double bwd = fwd > 0 ? L - fwd : 0;
      const double lim = dist(v[i], v[(i + 1) % n]) + 2 * hair_;
      if (fwd == 0) link[i] = 2;
      else if (fwd <= lim && fwd <= bwd) link[i] = 1;
      else if (bwd <= lim) link[i] = -1;
    }
    // Start after a broken link (a ring that follows the input all the way round: anywhere).
    bool broken = false;
    for (std::size_t i = 0; i < n; ++i)
      if (link[i] == 0) { pl.start = (i + 1) % n; broken = true; break; }
    std::size_t i = 0;
    while (i < n) {
      // Longest run from here with one direction (a ring that follows the input all the way
      // round closes onto its start: n links).
      Run run;
      run.a = (pl.start + i) % n;
      const std::size_t max_len = broken ? n - 1 - i : n - i;
      while (run.len < max_len) {
        const int l = link[(pl.start + i + run.len) % n];
        if (l == 0) break;
        if (l != 2) {
          if (run.dir == 0) run.dir = l;
          else if (l != run.dir) break;
        }
        ++run.len;
      }
      if (run.len == 0) { ++i; continue; }
      const std::size_t step = run.len;
      // Its ends must lie on the input (up to rounding): a run ending at an arc point off the
      // coast would replace the coast's own points next to it by a chord from there.
      if (run.len < n) {
        while (run.len > 0 && pl.at[run.a].d > on_tol_) { run.a = (run.a + 1) % n; --run.len; }
        while (run.len > 0 && pl.at[(run.a + run.len) % n].d > on_tol_) --run.len;
      }
      // A run of one link with no input vertex between changes nothing: not a run.
      if (run.len >= 2 || (run.len == 1 && run.dir != 0)) pl.runs.push_back(run);
      i += step;
    }
  }

  // The ring with every run not switched off replaced by the input's vertices; seg_tag gets,
  // per segment (from vertex k to k+1), the global run id it belongs to or -1.
  std::vector<Point2> build_ring(const Plan& pl, const std::vector<char>& off, std::vector<long>& seg_tag) const {
    const auto& v = pl.v;
    const std::size_t n = v.size();
    std::vector<Point2> out;
    out.reserve(n);
    seg_tag.clear();
    auto push = [&](Point2 p, long tag) {
      if (!out.empty() && out.back() == p) {
        if (tag >= 0) seg_tag.back() = tag;
        return;
      }
      out.push_back(p);
      seg_tag.push_back(tag);
    };
    std::size_t r = 0;  // next run
    for (std::size_t i = 0; i < n;) {
      const std::size_t a = (pl.start + i) % n;
      if (r < pl.runs.size() && pl.runs[r].a == a && !off[pl.first_run + r]) {
        const Run& run = pl.runs[r];
        const long tag = static_cast<long>(pl.first_run + r);
        push(v[a], tag);
        const std::size_t b = (a + run.len) % n;
        if (run.dir != 0) {
          const auto& ir = rings_[static_cast<std::size_t>(pl.at[a].ring)];
          const double m = static_cast<double>(ir.p.size());
          const double s0 = pl.at[a].s;
          double s1 = pl.at[b].s;
          const bool whole = run.len == n;
          if (run.dir > 0) {
            if (s1 < s0 || (whole && s1 == s0)) s1 += m;
            for (double k = std::floor(s0) + 1; k < s1; k += 1)
              push(ir.p[static_cast<std::size_t>(k) % ir.p.size()], tag);
          } else {
            if (s1 > s0 || (whole && s1 == s0)) s1 -= m;
            for (double k = std::ceil(s0) - 1; k > s1; k -= 1)
              push(ir.p[static_cast<std::size_t>(k + 2 * m) % ir.p.size()], tag);
          }
        }
        i += run.len;
        ++r;
        continue;
      }
      if (r < pl.runs.size() && pl.runs[r].a == a) ++r;  // switched off: the buffer's vertices
      push(v[a], -1);
      ++i;
    }
    while (out.size() > 1 && out.front() == out.back()) {
      out.pop_back();
      seg_tag.pop_back();
    }
    return out;
  }

  double hair_;
  double on_tol_ = 0;  // a vertex this close to the input is on it (rounding of the buffers)
  Box2 box_;
  std::vector<InRing> rings_;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> seg_ring_;  // segment id -> (ring, index)
  std::unique_ptr<pslg::SegmentGrid> grid_;
};

// Removed water (input minus result, `gone`), listed piece by piece above list_area; pieces
// thinner than `hair` (the snapping distance) are rounding, not features; a piece holding a
// water body listed as removed (listed_at) is not listed again.
RemovedWater list_removed_water(GeomPtr gone_all, const std::vector<Point2>& listed_at, double hair, double list_area,
                                double close_width) {
  RemovedWater out;
  std::vector<std::unique_ptr<OGRPolygon>> gone;
  polygons_of(gone_all.get(), gone);
  gone_all.reset();
  for (const auto& g : gone) {
    const double a = g->get_Area();
    double per = g->getExteriorRing()->get_Length();
    for (int k = 0; k < g->getNumInteriorRings(); ++k) per += g->getInteriorRing(k)->get_Length();
    if (!(a > 0) || 2 * a <= hair * per) continue;
    bool listed = false;  // a cut-off water body already listed
    OGREnvelope ge;
    g->getEnvelope(&ge);
    for (const Point2 w : listed_at) {
      if (!(ge.MinX <= w.x && w.x <= ge.MaxX && ge.MinY <= w.y && w.y <= ge.MaxY)) continue;
      OGRPoint pt(w.x, w.y);
      if (g->Intersects(&pt)) { listed = true; break; }
    }
    if (listed) continue;
    out.areas.push_back(a);
    if (a < list_area) {
      ++out.corner_pieces;
      continue;
    }
    ++out.closed;
    out.repairs.push_back({"narrow_water_closed", inside_point(g.get()), a,
                           "dead-end water narrower than the resolution (" + num(close_width) +
                               " m, --close-width) removed: " + num(a) + " m^2 (inlet, gap or sliver)",
                           -1});
  }
  return out;
}

// Adds a listing to the result (areas one by one, in order: the same sum as before the listing
// could be deferred).
void add_removed(FeatureFilterResult& res, RemovedWater w) {
  for (const double a : w.areas) res.closed_area += a;
  res.corner_pieces += w.corner_pieces;
  res.closed += w.closed;
  for (auto& r : w.repairs) res.repairs.push_back(std::move(r));
}
}  // namespace


// Closing of W at close_width/2 (land thinner than close_width becomes water), except for tips
// of land (the thin end of a needle, a spit or a cape), which stay land unless other land is
// near their end. Why keep them: the cut leaves a blunt end exactly close_width wide, two
// corners a fraction of hmin apart around which the mesh refines to their distance (West
// Norway, GSHHG-h: 4 % of all edges shorter than hmin/2, 0.6 % with the tips kept), and the tip
// it removes is coast the model loses; a kept tip is a sharp wedge that the resampling and the
// refinement handle with one element. A tip is cut as before when other land lies nearer its far
// end than both `tip_clearance` and 0.9 times the tip's own length (the water between them
// would need elements that narrow), or when it belongs to an island that the closing leaves
// below --min-island (removed as before); a whole island thinner than close_width is kept only
// with no other land within `tip_clearance` of it.
// Ring by ring: the closing of W is the opening of the land, and the opening of disjoint pieces
// of land is the union of their openings, so closed = close(O) - U open(H) for each outer ring O
// and its islands H, and the thin land is (close(O) - O) and (H - open(H)). Small overlays per
// ring instead of one overlay of closed with W (half a second on West Norway).
// *land_cut: the area of thin land that became water.
GeomPtr closing_keep_tips(const OGRGeometry* W, const FeatureFilterOptions& o, FeatureFilterResult& res,
                          double* land_cut) {
  DebugLaps lap("  closing");
  const double clear = o.tip_clearance;
  const double rc = 0.5 * o.close_width;
  const double hair = std::max(1e-6 * o.close_width, 1e-9);
  struct Ring {                  // one land piece: the outside of an outer ring, or an island
    bool outer = false;
    GeomPtr base;                // closing of the outer ring's polygon, or opening of the island
    std::vector<std::size_t> tips;  // indices into `pieces`
  };
  struct PolyRings { std::size_t outer = 0; std::vector<std::size_t> holes; };
  std::vector<Ring> rings;
  std::vector<PolyRings> polys;
  std::vector<std::unique_ptr<OGRPolygon>> pieces;  // thin land
  std::vector<std::size_t> piece_ring;
  // W's vertices: a tip's coast is made of them, its cut of the closing's arc points.
  std::unordered_set<std::uint64_t> wv;
  {
    // Every ring is closed (outer) or opened (island) on its own: the rings are shared out to
    // the threads (an atomic counter), the results kept per ring and combined in ring order, so
    // they do not depend on the thread count.
    std::vector<std::unique_ptr<OGRPolygon>> wps;
    polygons_of(W, wps);
    struct Job {
      const OGRLinearRing* ring;
      bool outer;
      GeomPtr base;
      std::vector<std::unique_ptr<OGRPolygon>> thin;
    };
    std::vector<Job> jobs;
    for (const auto& wp : wps) {
      jobs.push_back({wp->getExteriorRing(), true, nullptr, {}});
      for (int k = 0; k < wp->getNumInteriorRings(); ++k) jobs.push_back({wp->getInteriorRing(k), false, nullptr, {}});
    }
    for (const Job& jb : jobs)
      for (int k = 0; k < jb.ring->getNumPoints(); ++k) wv.insert(point_key(jb.ring->getX(k), jb.ring->getY(k)));
    auto run = [&](Job& j) {
      OGRPolygon rp;
      rp.addRing(const_cast<OGRLinearRing*>(j.ring));
      if (j.outer) {
        GeomPtr grown = checked(rp.Buffer(rc, kQuadSegs), "buffer of an outer ring");
        j.base = offset(*grown, -rc);
        GeomPtr t = difference_contained(*j.base, rp, "thin land outside an outer ring");
        polygons_of(t.get(), j.thin);
      } else {
        j.base = opening(rp, rc);
        if (j.base->IsEmpty()) {
          j.thin.emplace_back(rp.clone());
        } else {
          GeomPtr d = difference_contained(rp, *j.base, "thin land of an island");
          polygons_of(d.get(), j.thin);
        }
      }
    };
    std::atomic<std::size_t> next{0};
    auto worker = [&] {
      GdalQuiet q;
      for (std::size_t i; (i = next.fetch_add(1)) < jobs.size();) run(jobs[i]);
    };
    const unsigned nt = std::min<unsigned>(max_threads(), 2);
    std::vector<std::future<void>> helpers;
    for (unsigned t = 1; t < nt; ++t) helpers.push_back(std::async(std::launch::async, worker));
    worker();
    for (auto& h : helpers) h.get();
    lap("rings");
    std::size_t j = 0;
    for (const auto& wp : wps) {
      PolyRings pr;
      for (int k = -1; k < wp->getNumInteriorRings(); ++k, ++j) {
        Ring r;
        r.outer = jobs[j].outer;
        r.base = std::move(jobs[j].base);
        (k < 0 ? pr.outer : (pr.holes.push_back(0), pr.holes.back())) = rings.size();
        for (auto& q : jobs[j].thin) { pieces.push_back(std::move(q)); piece_ring.push_back(rings.size()); }
        rings.push_back(std::move(r));
      }
      polys.push_back(std::move(pr));
    }
  }
  // Other land: the boundaries of the closed rings (without a tip's own cut), in a bucket grid;
  // islands the closing leaves below --min-island, by their vertices.
  std::vector<Point2> bp;
  std::unordered_set<std::uint64_t> small_island;
  for (const auto& r : rings) {
    std::vector<std::unique_ptr<OGRPolygon>> cps;
    polygons_of(r.base.get(), cps);
    for (const auto& cp : cps) {
      auto add = [&](const OGRLinearRing* lr, bool small) {
        for (int k = 0; k < lr->getNumPoints(); ++k) {
          if (k + 1 < lr->getNumPoints()) {
            bp.push_back({lr->getX(k), lr->getY(k)});
            bp.push_back({lr->getX(k + 1), lr->getY(k + 1)});
          }
          if (small) small_island.insert(point_key(lr->getX(k), lr->getY(k)));
        }
      };
      add(cp->getExteriorRing(), !r.outer && cp->get_Area() < o.min_island_area);
      for (int k = 0; k < cp->getNumInteriorRings(); ++k) add(cp->getInteriorRing(k), false);
    }
  }
  std::vector<char> keep(pieces.size(), 0);
  lap("other land");
  if (!bp.empty() && !pieces.empty()) {
    Box2 box;
    double total = 0;
    for (std::size_t k = 0; k < bp.size(); k += 2) {
      box.add(bp[k]);
      box.add(bp[k + 1]);
      total += dist(bp[k], bp[k + 1]);
    }
    const std::size_t nseg = bp.size() / 2;
    pslg::SegmentGrid grid(box, nseg, std::max(total / static_cast<double>(nseg), 1e-6));
    for (std::size_t k = 0; k < nseg; ++k) grid.add_segment(static_cast<Index>(k), bp[2 * k], bp[2 * k + 1]);
    std::vector<Index> near;
    // True when a segment of other land (no endpoint in `own`) is within lim of p.
    auto land_near = [&](Point2 p, double lim, const std::unordered_set<std::uint64_t>& own) {
      Box2 qb;
      qb.add({p.x - lim, p.y - lim});
      qb.add({p.x + lim, p.y + lim});
      grid.segments_near(qb, &near);
      for (Index k : near) {
        const Point2 s0 = bp[2 * k], s1 = bp[2 * k + 1];
        if (!own.empty() && (own.count(point_key(s0.x, s0.y)) || own.count(point_key(s1.x, s1.y)))) continue;
        if (dist_to_segment(p, s0, s1) < lim) return true;
      }
      return false;
    };
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      const OGRLinearRing* r = pieces[i]->getExteriorRing();
      // Tips: pieces longer than 2 close widths (perimeter > 4 cw). The shorter pieces the
      // closing cuts off convex land corners are kept the same way when the cut would move the
      // coast by more than kCornerKeep close widths (their far end, the corner, is that far from
      // the cut), the piece is one run of coast and one of cut (not a short bridge of land
      // between two waters, which has two of each), and no other land lies within
      // tip_clearance of the corner: the rounding would only move the coast (a reflex corner of
      // the water needs no small elements), and a kept corner keeps the input coast there.
      // Gulf of Maine: input->mesh deviation p99 0.507 hmin without the rule, 0.489 with it.
      // Smaller fractions (0.1-0.35, with the tips' 0.9-far clearance) kept notches of 30 m
      // where f = 100 m on West Norway, and a Steiner vertex came within 34 m of an input
      // vertex (Theorem 4.4 failed); 0.45 with the full clearance keeps every theory table valid.
      const bool long_piece = r->get_Length() > 4 * o.close_width;
      std::vector<Point2> coast, cut;
      std::unordered_set<std::uint64_t> own;
      int runs = 0;  // changes between coast and cut around the ring
      bool prev_on = false;
      for (int k = 0; k < r->getNumPoints(); ++k) {
        const std::uint64_t key = point_key(r->getX(k), r->getY(k));
        const bool on_w = wv.count(key) > 0;
        (on_w ? coast : cut).push_back({r->getX(k), r->getY(k)});
        if (!on_w) own.insert(key);
        if (k > 0 && on_w != prev_on) ++runs;
        prev_on = on_w;
      }
      if (!long_piece && (runs != 2 || coast.empty() || cut.empty())) continue;
      bool crowded = false;
      for (const Point2& q : cut)
        if (small_island.count(point_key(q.x, q.y))) { crowded = true; break; }
      if (crowded) {
      } else if (cut.empty()) {  // a whole thin island
        for (const Point2& c : coast)
          if ((crowded = land_near(c, clear, own))) break;
      } else {
        // The far end: the coast vertex farthest from the cut.
        double far = -1;
        Point2 e{};
        for (const Point2& c : coast) {
          double d = std::numeric_limits<double>::infinity();
          for (const Point2& q : cut) d = std::min(d, dist(c, q));
          if (d > far) { far = d; e = c; }
        }
        constexpr double kCornerKeep = 0.45;
        if (!long_piece && !(far > kCornerKeep * o.close_width)) continue;
        crowded = !(far > 0) || land_near(e, long_piece ? std::min(clear, 0.9 * far) : clear, own);
      }
      if (!crowded) {
        keep[i] = 1;
        rings[piece_ring[i]].tips.push_back(i);
        ++res.tips_kept;
      }
    }
  }
  *land_cut = 0;
  for (std::size_t i = 0; i < pieces.size(); ++i)
    if (!keep[i]) *land_cut += pieces[i]->get_Area();
  lap("tips");
  // Closed water: per polygon, close(O) without its kept tips, minus the islands' openings with
  // theirs.
  auto with_tips = [&](Ring& r) -> GeomPtr {
    if (r.tips.empty()) return std::move(r.base);
    std::vector<std::unique_ptr<OGRPolygon>> ps;
    for (std::size_t i : r.tips) ps.emplace_back(pieces[i]->clone());
    if (!r.outer) polygons_of(r.base.get(), ps);
    GeomPtr u = union_pieces(ps, hair, "kept tips");
    return r.outer ? difference_contained(*r.base, *u, "closed water without kept tips") : std::move(u);
  };
  std::vector<std::unique_ptr<OGRPolygon>> out;
  const bool two = max_threads() >= 2;
  for (auto& pr : polys) {
    // The outer ring's kept tips (an overlay of the closed outer ring) and the islands' (their
    // union) are independent: one on each core when there are two.
    Ring& outer = rings[pr.outer];
    std::future<GeomPtr> b_job;
    if (two && !outer.tips.empty() && !pr.holes.empty())
      b_job = std::async(std::launch::async, [&with_tips, &outer] {
        GdalQuiet q2;
        return with_tips(outer);
      });
    GeomPtr b = b_job.valid() ? nullptr : with_tips(outer);
    std::vector<std::unique_ptr<OGRPolygon>> hs;
    for (std::size_t h : pr.holes) {
      GeomPtr g = with_tips(rings[h]);
      if (g && !g->IsEmpty()) polygons_of(g.get(), hs);
    }
    GeomPtr hu;
    if (!hs.empty()) hu = union_pieces(hs, hair, "union of islands");
    if (b_job.valid()) b = b_job.get();
    if (hu) b = std::getenv("FDR_DIFF_OVERLAY") ? checked(b->Difference(hu.get()), "closed water minus islands")
                                                : minus_disjoint(std::move(b), *hu, "closed water minus islands");
    polygons_of(b.get(), out);
  }
  lap("with tips, minus islands");
  if (out.size() > 1) return union_pieces(out, hair, "union of closed water");
  return GeomPtr(multi(out).release());
}

// How many of a set of polygons a piece meets, the piece grown by `grow` (the count stops at
// two): the openings' pieces are judged by it (a piece and O1 share boundary points only up to
// GEOS rounding) and so are the widened pieces (land thinner than the close width between them
// and another water body would be closed all the same). With `alone_ungrown`, a set of one
// polygon is tested against the piece itself (no buffer per piece).
class Meets {
 public:
  Meets(const std::vector<std::unique_ptr<OGRPolygon>>& ps, double grow, bool alone_ungrown = false)
      : ps_(ps), env_(ps.size()), prep_(ps.size()), grow_(grow), alone_ungrown_(alone_ungrown) {
    for (std::size_t i = 0; i < ps.size(); ++i) ps[i]->getEnvelope(&env_[i]);
  }
  std::size_t count(const OGRPolygon& piece) {
    OGREnvelope e;
    piece.getEnvelope(&e);
    e.MinX -= grow_; e.MinY -= grow_; e.MaxX += grow_; e.MaxY += grow_;
    const bool ungrown = alone_ungrown_ && ps_.size() == 1;
    std::size_t n = 0;
    GeomPtr grown;
    for (std::size_t i = 0; i < ps_.size(); ++i) {
      if (!env_[i].Intersects(e)) continue;
      if (!ungrown && !grown) grown = checked(piece.Buffer(grow_, 1), "buffer of a piece");
      if (!prep_[i]) prep_[i] = std::make_unique<Prepared>(ps_[i].get());
      if (prep_[i]->intersects(ungrown ? static_cast<const OGRGeometry*>(&piece) : grown.get()) && ++n >= 2) break;
    }
    return n;
  }

 private:
  const std::vector<std::unique_ptr<OGRPolygon>>& ps_;
  std::vector<OGREnvelope> env_;
  std::vector<std::unique_ptr<Prepared>> prep_;
  double grow_;
  bool alone_ungrown_;
};

// Thin water widened (README, "Narrow water widened"). The parts of W no disk of radius rw fits
// in, T = W - open(W, rw), that are at least 2 s wide (their core C = (W - s) - open(W, rw), a
// strip w - 2 s wide along a channel w wide) are grown by rw - s: the channel becomes
// w + 2 rw - 4 s >= 2 rw wide (for w >= 2 s), each bank moved by rw - 2 s into the land. Why: a
// channel narrower than the resolution keeps its coast only with elements as narrow as itself
// (every edge across it is < w); widened to 2 rw it holds elements near hmin and the coast moves
// by a fraction of hmin, where closing it would move the coast by its whole length. Convex water
// corners leave core bits too (sharper corners larger ones): they are blunted the same way, as a
// wedge of water would need elements as narrow as itself. A grown piece that would join two
// separate water bodies (come within the close width of another one) is not used; the rest
// stays inside W's bounding box (an open boundary there does not move). The grown pieces are
// simplified (they are new coast; the resampler's tolerance is far coarser).
GeomPtr widen_thin_water(const OGRGeometry& W, double rw, double s, const FeatureFilterOptions& o,
                         FeatureFilterResult& res) {
  DebugLaps lap("  widen");
  const bool dbg = lap.on();
  // The opening and the erosion are independent: one on each core (as the openings below).
  auto we_job = std::async(std::launch::async, [&W, s] {
    GdalQuiet q2;
    return offset(W, -s);
  });
  GeomPtr Wo = opening(W, rw);
  GeomPtr We = we_job.get();
  lap("opening + erosion");
  if (We->IsEmpty()) return GeomPtr(W.clone());
  GeomPtr C = Wo->IsEmpty() ? GeomPtr(We->clone()) : checked(We->Difference(Wo.get()), "thin water core");
  if (C->IsEmpty()) return GeomPtr(W.clone());
  lap("core");
  {  // bits of the core in right-angled water corners (about 0.3 rw - s across) are no channels;
     // those of acute corners are larger and kept: the corner is blunted, as a wedge of water
     // would need elements as narrow as itself
    std::vector<std::unique_ptr<OGRPolygon>> cps, big;
    polygons_of(C.get(), cps);
    for (auto& cp : cps)
      if (cp->get_Area() >= 0.05 * s * s) big.push_back(std::move(cp));
    if (big.size() < cps.size()) C = multi(big);
    if (C->IsEmpty()) return GeomPtr(W.clone());
  }
  // The grown pieces are new coast: their arcs need not be finer than the resampling keeps
  // (a tenth of the move; every arc point would otherwise go through the openings below).
  C = checked(C->SimplifyPreserveTopology(0.1 * (rw - s)), "thin water core simplified");
  lap("grown: simplify core");
  GeomPtr D = offset(*C, rw - s, 2);
  lap("grown: offset");
  D = checked(D->SimplifyPreserveTopology(0.1 * (rw - s)), "widened water simplified");
  lap("grown");
  if (dbg) {
    auto nverts = [](const OGRGeometry* g) {
      std::vector<std::unique_ptr<OGRPolygon>> ps;
      polygons_of(g, ps);
      std::size_t nv = 0;
      for (const auto& p : ps) {
        nv += p->getExteriorRing()->getNumPoints();
        for (int k = 0; k < p->getNumInteriorRings(); ++k) nv += p->getInteriorRing(k)->getNumPoints();
      }
      return nv;
    };
    std::fprintf(stderr, "  widen: W %zu, W-s %zu, open(W) %zu, core %zu, grown %zu vertices\n", nverts(&W), nverts(We.get()),
                 nverts(Wo.get()), nverts(C.get()), nverts(D.get()));
  }
  OGREnvelope we;
  W.getEnvelope(&we);
  {
    OGRLinearRing lr;
    lr.addPoint(we.MinX, we.MinY);
    lr.addPoint(we.MaxX, we.MinY);
    lr.addPoint(we.MaxX, we.MaxY);
    lr.addPoint(we.MinX, we.MaxY);
    lr.closeRings();
    OGRPolygon box;
    box.addRing(&lr);
    D = checked(D->Intersection(&box), "widened water inside the domain's box");
  }
  std::vector<std::unique_ptr<OGRPolygon>> wps, dps;
  polygons_of(&W, wps);
  polygons_of(D.get(), dps);
  std::vector<std::unique_ptr<OGRPolygon>> pieces;
  std::vector<int> family;  // 0: the water bodies, 1: the grown pieces (each set disjoint)
  for (auto& p : wps) {
    pieces.emplace_back(p->clone());
    family.push_back(0);
  }
  // Tested grown by the close width: land thinner than that between a piece and another water
  // body would be removed by the closing below and join them all the same.
  Meets bodies(wps, 2 * s, true);
  for (auto& d : dps) {
    if (!(d->get_Area() > 0)) continue;
    const std::size_t meets = bodies.count(*d);
    if (meets != 1) {  // would join two water bodies (or meets none: cannot happen)
      OGREnvelope e;
      d->getEnvelope(&e);
      if (debug::value(debug::Aid::kFilter))
        std::fprintf(stderr, "widen: piece of %.0f m^2 near %.1f %.1f meets %zu water bodies: not used\n",
                     d->get_Area(), 0.5 * (e.MinX + e.MaxX), 0.5 * (e.MinY + e.MaxY), meets);
      continue;
    }
    ++res.widened;
    const double a = d->get_Area();
    if (a >= o.list_area)
      res.repairs.push_back({"water_widened", inside_point(d.get()), a,
                             "water narrower than " + num(2 * rw) + " m was widened (banks moved by about " +
                                 num(rw - 2 * s) + " m into the land); the widened part covers " + num(a) + " m^2",
                             -1});
    pieces.push_back(std::move(d));
    family.push_back(1);
  }
  lap("pieces");
  const double hair = 1e-6 * rw;
  GeomPtr out = union_pieces(pieces, hair, "union of the widened water", &family);
  lap("union");
  const double added = area_of(out.get()) - area_of(&W);
  if (added > 0) res.widened_area += added;
  return out;
}

void start_removed(FeatureFilterResult& res, bool own_arena) {
  const std::shared_ptr<PendingRemoved> p = res.removed_pending;
  if (!p || !p->job.valid() || p->runner.valid() || max_threads() < 2) return;
  // wait() runs the deferred listing on the runner's thread; its result (or error) stays in job.
  // Its allocations in an arena of its own, which keeps its freed pages through the mesh stages'
  // eager release.
  if (own_arena) p->arena = std::make_shared<OwnArena>();
  p->runner = std::async(std::launch::async, [p] {
    if (p->arena) p->arena->bind();
    p->job.wait();
  });
}

std::vector<pslg::Repair> finish_removed(FeatureFilterResult& res) {
  if (!res.removed_pending || !res.removed_pending->job.valid()) return {};
  if (res.removed_pending->runner.valid()) res.removed_pending->runner.get();
  RemovedWater w = res.removed_pending->job.get();
  res.removed_pending->arena.reset();  // its pages back to the system
  res.removed_pending.reset();
  const std::size_t first = res.repairs.size();
  add_removed(res, std::move(w));
  return {res.repairs.begin() + static_cast<std::ptrdiff_t>(first), res.repairs.end()};
}

Polygons offset_polygons(const Polygons& input, double d) {
  GdalQuiet quiet;
  auto m = std::make_unique<OGRMultiPolygon>();
  for (const auto& rings : input) {
    OGRPolygon p = to_ogr(rings);
    if (!p.IsEmpty()) m->addGeometry(&p);
  }
  GeomPtr g = offset(*m, d);
  std::vector<std::unique_ptr<OGRPolygon>> ps;
  polygons_of(g.get(), ps);
  Polygons out;
  for (const auto& p : ps) {
    Rings rings;
    rings.push_back(ring_points(p->getExteriorRing(), true));
    for (int k = 0; k < p->getNumInteriorRings(); ++k) rings.push_back(ring_points(p->getInteriorRing(k), false));
    if (rings[0].size() >= 3) out.push_back(std::move(rings));
  }
  return out;
}

FeatureFilterResult filter_features(const Polygons& input, const FeatureFilterOptions& o) {
  GdalQuiet quiet;
  DebugLaps lap("filter");
  const bool dbg_time = lap.on();
  FeatureFilterResult res;
  res.close_width = o.close_width;
  if (dbg_time) {
    std::size_t nv = 0, nr = 0;
    for (const auto& rings : input) for (const auto& r : rings) { nv += r.size(); ++nr; }
    std::fprintf(stderr, "filter input: %zu polygons, %zu rings, %zu vertices\n", input.size(), nr, nv);
  }
  // 1. Valid copies of every polygon, then their union: overlapping water polygons from merged
  //    layers become one (the parity rule of the mesher would make the overlap a hole).
  std::vector<std::unique_ptr<OGRPolygon>> valid;
  double sum_area = 0;
  for (const auto& rings : input) {
    OGRPolygon p = to_ogr(rings);
    if (p.IsEmpty()) continue;
    if (!surely_valid(rings) && !p.IsValid()) {
      GeomPtr v = checked(p.MakeValid(), "making a polygon valid");
      polygons_of(v.get(), valid);
    } else {
      valid.emplace_back(p.clone());
    }
  }
  lap("valid");
  for (const auto& p : valid) sum_area += p->get_Area();
  // Overlaps: pairs whose envelopes meet and whose intersection has an area.
  {
    std::vector<OGREnvelope> env(valid.size());
    for (std::size_t i = 0; i < valid.size(); ++i) valid[i]->getEnvelope(&env[i]);
    std::vector<std::unique_ptr<Prepared>> prep(valid.size());
    for (std::size_t i = 0; i < valid.size(); ++i)
      for (std::size_t j = i + 1; j < valid.size(); ++j) {
        if (!env[i].Intersects(env[j])) continue;
        // A prepared test first (a basin polygon with 10 000 holes against its neighbours: the
        // plain predicates cost a second); polygons that only touch have no overlap area.
        if (!prep[i]) prep[i] = std::make_unique<Prepared>(valid[i].get());
        if (!prep[i]->intersects(valid[j].get())) continue;
        GeomPtr x(valid[i]->Intersection(valid[j].get()));
        const double a = x ? area_of(x.get()) : 0;
        if (!(a > 0)) continue;
        ++res.united;
        res.united_overlap_area += a;
        res.repairs.push_back({"polygons_united", inside_point(x.get()), a,
                               "two water polygons overlap by " + num(a) +
                                   " m^2; they were united (the overlap stays water)",
                               -1});
      }
  }
  lap("overlaps");
  GeomPtr W;
  {
    std::vector<std::unique_ptr<OGRPolygon>> vs;
    for (auto& p : valid) vs.emplace_back(p->clone());
    W = union_pieces(vs, 0, "union of the water polygons");
  }
  lap("union");
  res.input_area = area_of(W.get());
  GeomPtr W0(W->clone());  // the input water bodies (ownership of the result's pieces)
  std::unique_ptr<Snapper> snap_to_input;
  if (o.close_width > 0) snap_to_input = std::make_unique<Snapper>(W0.get(), 0.05 * o.close_width);
  {
    std::vector<std::unique_ptr<OGRPolygon>> ps;
    polygons_of(W.get(), ps);
    res.input_pieces = ps.size();
  }
  (void)sum_area;

  // 1b. Islands below the resolution. The tiniest are removed (--min-island); the others smaller
  //     than grow_island_area are grown by grow_island (buffer), so that the mesh keeps them with
  //     elements near hmin instead of elements as small as the island. Why grow rather than drop:
  //     a dropped island near the coast moves the coastline the model sees by its whole distance.
  std::vector<Point2> placed;  // centres of the islets kept as triangles (step 2c keeps them)
  std::vector<double> placed_r;  // their circumradii
  std::vector<Box2> joined_box;  // the boxes of the islets' hulls joined to land (below)
  DiskGrid placed_grid(2 * o.islet_side);
  std::vector<std::uint32_t> cand;
  std::vector<int> placed_ring;  // the ring each replaces (-1: several)
  auto islet_tris = std::make_unique<OGRMultiPolygon>();
  // Islets (README, "Islets"): an island below --min-island with no other land near becomes an
  // equilateral triangle of side islet_side (larger for a long islet, up to 1.6 islet_side) around
  // its centroid, turned to fit the islet, instead of water. Why: a dropped
  // islet moves the coast the model sees by its distance to the next coast (its vertices are
  // input coast too), a kept one forces elements as small as itself; the triangle keeps it within
  // about islet_side / 2 with elements near hmin. Other land (every ring but its own, and the
  // triangles placed before it) must be farther than islet_side / 2 beyond the triangle's corners.
  // Step 1b judges room on the land after the union (later steps only take land away, so room
  // there is room later too); step 2c on the land as it is then.
  const double tri_r = o.islet_side / std::sqrt(3.0);  // circumradius
  // Land as segments of the water's rings (every ring but the islet's own counts as other land).
  struct LandIndex {
    std::unique_ptr<pslg::SegmentGrid> grid;
    std::vector<std::pair<Point2, Point2>> seg;
    std::vector<int> ring;                                // ring id of each segment
    int rings = 0;
    std::unordered_map<const OGRLinearRing*, int> id_of;  // valid while the rings are
    std::vector<char> gone;                               // per ring: removed, not land (empty: none)
    std::vector<std::size_t> first;                       // per ring: its first segment (and one past the last)
  };
  auto build_land = [&](const std::vector<std::unique_ptr<OGRPolygon>>& ps, LandIndex& L) {
    Box2 box;
    for (const auto& p : ps)
      for (int k = -1; k < p->getNumInteriorRings(); ++k) {
        const OGRLinearRing* r = k < 0 ? p->getExteriorRing() : p->getInteriorRing(k);
        const int id = L.rings++;
        L.id_of[r] = id;
        L.first.push_back(L.seg.size());
        for (int i = 0; i + 1 < r->getNumPoints(); ++i) {
          L.seg.push_back({{r->getX(i), r->getY(i)}, {r->getX(i + 1), r->getY(i + 1)}});
          L.ring.push_back(id);
          box.add(L.seg.back().first);
        }
      }
    L.first.push_back(L.seg.size());
    if (L.seg.empty()) return;
    L.grid = std::make_unique<pslg::SegmentGrid>(box, L.seg.size(), o.islet_side);
    for (std::size_t k = 0; k < L.seg.size(); ++k) L.grid->add_segment(static_cast<Index>(k), L.seg[k].first, L.seg[k].second);
  };
  LandIndex land;
  std::vector<Index> near;
  // A moved triangle keeps a little more room (0.55 islet_side beyond its corners instead of
  // 0.5): with 0.5 the moved triangles added 21 edges under hmin/2 on the Gulf of Maine (290 ->
  // 311, input->mesh p99 0.86 hmin), with 0.55 none (289, p99 0.89), 0.6: 287, p99 0.96.
  const double shifted_cl = 0.55;
  auto islet_room = [&](const LandIndex& L, int own, Point2 c, double clf = 0.5, double r = 0) {
    if (r == 0) r = tri_r;
    const double lim = r + clf * o.islet_side;
    placed_grid.near({{c.x - lim, c.y - lim}, {c.x + lim, c.y + lim}}, &cand);
    for (const std::uint32_t k : cand)
      if (dist(placed[k], c) < lim + placed_r[k]) return false;
    Box2 qb;
    qb.add({c.x - lim, c.y - lim});
    qb.add({c.x + lim, c.y + lim});
    L.grid->segments_near(qb, &near);
    for (Index k : near)
      if (L.ring[k] != own && (L.gone.empty() || !L.gone[L.ring[k]]) &&
          dist_to_segment(c, L.seg[k].first, L.seg[k].second) < lim)
        return false;
    return true;
  };
  // The islet of ring `own` (area a) as a triangle around cen or, with no room there, around the
  // first of 24 points near it (8 directions at a third, two thirds and all of islet_shift) that
  // has room; added to `into`. Why the shifts: most islets that were dropped lie within hmin of
  // other land, and the coast the model saw moved by that distance (Gulf of Maine input->mesh
  // p99 1.36 hmin); moved by at most islet_shift they stay.
  auto place_islet = [&](const LandIndex& L, int own, const OGRLinearRing& shape, Point2 cen, double a,
                         const std::string& what, OGRMultiPolygon* into) {
    const int ns = shape.getNumPoints();  // with the closing repeat
    Point2 c = cen;
    // A long islet gets a larger triangle where there is room around its centroid (side up to
    // 1.6 islet_side: the best turn of a triangle of side s leaves the ends of an islet of length
    // len about len / 2 - 0.39 s out; sized for 0.57 islet_side, 0.4 hmin). Gulf of Maine: samples
    // of kept islets beyond hmin/2 44 -> 30, 315 fewer triangles, edges under hmin/2 unchanged.
    double r = tri_r;
    if (ns <= 64) {
      double len = 0;
      for (int i = 0; i + 1 < ns; ++i)
        for (int j = i + 1; j + 1 < ns; ++j)
          len = std::max(len, dist({shape.getX(i), shape.getY(i)}, {shape.getX(j), shape.getY(j)}));
      const double side = std::min(1.6 * o.islet_side, (0.5 * len - 0.57 * o.islet_side) / 0.39);
      if (side > o.islet_side && islet_room(L, own, c, 0.5, side / std::sqrt(3.0))) r = side / std::sqrt(3.0);
    }
    bool room = r > tri_r || islet_room(L, own, c);
    for (int step = 1; !room && step <= 3 && o.islet_shift > 0; ++step)
      for (int d = 0; d < 8 && !room; ++d) {
        const double t = o.islet_shift * step / 3.0, ang = 0.7853981633974483 * d;
        const Point2 q{cen.x + t * std::cos(ang), cen.y + t * std::sin(ang)};
        if (islet_room(L, own, q, shifted_cl)) { c = q; room = true; }
      }
    if (!room) return false;
    placed_grid.add(static_cast<std::uint32_t>(placed.size()), c, r);
    placed.push_back(c);
    placed_r.push_back(r);
    placed_ring.push_back(own);
    // The turn of the triangle: the one of 40 turns 3 degrees apart (from apex up; the first of
    // equals) that keeps the islet's farthest vertex nearest the triangle's sides. The room test
    // above is the same for every turn (a disk around the circumcircle). Why: with the apex always
    // up, the ends of an islet longer than the triangle stuck out by up to 0.6 islet_side, which
    // the model sees as coast moved by that much (Gulf of Maine: 85 of the 376 input vertices
    // farther than hmin/2 from the mesh's coast were vertices of islets kept as triangles).
    auto corner = [&](double t0, int k) {
      const double t = t0 - 2.0943951023931957 * k;  // clockwise
      return Point2{c.x + r * std::cos(t), c.y + r * std::sin(t)};
    };
    double turn = 1.5707963267948966, best = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 40; ++k) {
      const double t0 = 1.5707963267948966 + k * (2.0943951023931957 / 40);
      const Point2 p0 = corner(t0, 0), p1 = corner(t0, 1), p2 = corner(t0, 2);
      double worst = 0;
      for (int i = 0; i + 1 < ns && worst < best; ++i) {
        const Point2 v{shape.getX(i), shape.getY(i)};
        worst = std::max(worst, std::min({dist_to_segment(v, p0, p1), dist_to_segment(v, p1, p2),
                                          dist_to_segment(v, p2, p0)}));
      }
      if (worst < best) {
        best = worst;
        turn = t0;
      }
    }
    OGRLinearRing tr;
    for (int k = 0; k < 3; ++k) {
      const Point2 q = corner(turn, k);
      tr.addPoint(q.x, q.y);
    }
    tr.closeRings();
    auto tp = std::make_unique<OGRPolygon>();
    tp->addRing(&tr);
    const double ta = tp->get_Area();
    const double moved = dist(c, cen);
    ++res.islets_replaced;
    res.repairs.push_back({"islet_simplified", c, a,
                           what + " is smaller than " + num(o.min_island_area) +
                               " m^2 (--min-island); kept as a triangle of side " + num(r * std::sqrt(3.0)) + " m (" +
                               num(ta) + " m^2) " +
                               (moved > 0 ? "around a point " + num(moved) +
                                                " m from its centroid (other land too near the centroid)"
                                          : std::string("around its centroid")),
                           -1});
    into->addGeometryDirectly(tp.release());
    return true;
  };
  // The convex polygon h keeps cl from the input's box, the placed triangles and the joined
  // hulls and, with `rings`, from every ring of L that is land (not gone).
  auto hull_clear = [&](const LandIndex& L, const std::vector<Point2>& h, const Box2& inbox,
                        const std::vector<std::vector<Point2>>& joined, double cl, bool rings) {
    const Box2 hb = box_of(h);
    if (hb.lo.x < inbox.lo.x + cl || hb.lo.y < inbox.lo.y + cl || hb.hi.x > inbox.hi.x - cl || hb.hi.y > inbox.hi.y - cl)
      return false;
    if (rings && L.grid) {
      L.grid->segments_near({{hb.lo.x - cl, hb.lo.y - cl}, {hb.hi.x + cl, hb.hi.y + cl}}, &near);
      for (Index j : near) {
        const int r = L.ring[j];
        if (!L.gone.empty() && L.gone[static_cast<std::size_t>(r)]) continue;
        if (convex_distance(L.seg[j].first, L.seg[j].second, h) < cl) return false;
      }
    }
    placed_grid.near({{hb.lo.x - cl, hb.lo.y - cl}, {hb.hi.x + cl, hb.hi.y + cl}}, &cand);
    for (const std::size_t t : cand) {
      if (beyond(placed[t], placed_r[t] + cl, hb)) continue;
      if (inside_convex(placed[t], h)) return false;
      for (std::size_t i = 0; i < h.size(); ++i)
        if (dist_to_segment(placed[t], h[i], h[(i + 1) % h.size()]) < placed_r[t] + cl) return false;
    }
    for (std::size_t k = 0; k < joined.size(); ++k) {
      if (apart(joined_box[k], hb, cl)) continue;
      const auto& g = joined[k];
      for (std::size_t i = 0; i < g.size(); ++i)
        if (convex_distance(g[i], g[(i + 1) % g.size()], h) < cl) return false;
    }
    return true;
  };
  // An islet with no room for its triangle, joined to the nearest other land when that is
  // nearer than islet_side: the convex hull of the islet and of that land's coast within
  // rho = len / 2 + d + 0.1 islet_side of the nearest point (len: the islet's length, d: the gap)
  // becomes land. Why: dropped, the islet moves the coast the model sees by its distance to the
  // next coast (Gulf of Maine: most yardstick samples beyond hmin/2 were such islets, 0.1-0.6
  // hmin from other land); joined, its outer side stays coast and the gap, narrower than an
  // element, is no longer water. The hull must meet the land's ring along that one run of coast
  // only (so no water is cut off: the land grows by a convex piece whose intersection with it is
  // connected; it may touch the run between its ends, round a convex corner), keep islet_side / 4
  // from every other ring, placed triangle and earlier join, stay inside the input's box (open
  // boundaries do not move) and hold at most 3 islet_side^2.
  // Returns the hull (empty: not joined) and the water it takes (*taken).
  auto join_islet = [&](const LandIndex& L, int own, const OGRLinearRing& shape, const Box2& inbox,
                        const std::vector<std::vector<Point2>>& joined, double* taken, double* gap) {
    std::vector<Point2> isl;
    for (int i = 0; i + 1 < shape.getNumPoints(); ++i) isl.push_back({shape.getX(i), shape.getY(i)});
    const std::size_t ni = isl.size();
    if (ni < 3 || !L.grid) return std::vector<Point2>{};
    Box2 ib;
    for (Point2 q : isl) ib.add(q);
    const double dmax = o.islet_side, cl = 0.25 * o.islet_side;
    Box2 qb{{ib.lo.x - dmax, ib.lo.y - dmax}, {ib.hi.x + dmax, ib.hi.y + dmax}};
    L.grid->segments_near(qb, &near);
    std::sort(near.begin(), near.end());  // the first of equals, whatever the grid's order
    double best = std::numeric_limits<double>::infinity();
    Index kb = kNoId;
    Point2 pb{};
    auto closest_on = [](Point2 q, Point2 a, Point2 b) {
      const Point2 ab = b - a;
      const double l2 = norm2(ab);
      const double t = l2 > 0 ? std::clamp(dot(q - a, ab) / l2, 0.0, 1.0) : 0.0;
      return Point2{a.x + t * ab.x, a.y + t * ab.y};
    };
    for (Index k : near) {
      const int r = L.ring[k];
      if (r == own || (!L.gone.empty() && L.gone[static_cast<std::size_t>(r)])) continue;
      const auto [a, b] = L.seg[k];
      for (std::size_t i = 0; i < ni; ++i) {  // islet vertices to the segment
        const Point2 c = closest_on(isl[i], a, b);
        if (const double d = dist(isl[i], c); d < best) { best = d; kb = k; pb = c; }
      }
      for (const Point2 e : {a, b})  // segment ends to the islet's sides
        for (std::size_t i = 0; i < ni; ++i)
          if (const double d = dist_to_segment(e, isl[i], isl[(i + 1) % ni]); d < best) { best = d; kb = k; pb = e; }
    }
    if (kb == kNoId || !(best > 0) || best > dmax) return std::vector<Point2>{};
    const int ra = L.ring[kb];
    const std::size_t f0 = L.first[static_cast<std::size_t>(ra)], f1 = L.first[static_cast<std::size_t>(ra) + 1];
    const std::size_t nseg = f1 - f0;
    double len = 0;
    for (std::size_t i = 0; i < ni; ++i)
      for (std::size_t j = i + 1; j < ni; ++j) len = std::max(len, dist(isl[i], isl[j]));
    const double rho = 0.5 * len + best + 0.1 * o.islet_side;
    // The run of ring ra's coast within arc length rho of pb, both ways: its vertices in ring
    // order from the backward end e0 to the forward end e1 (on segments s0 and s1). A walk that
    // comes back to a segment already in the run (the whole ring is that near) finds no run.
    std::vector<char> in_run(nseg, 0);
    in_run[kb - f0] = 1;
    std::vector<Point2> fwd, bwd;
    Point2 e1{}, e0{};
    std::size_t s1 = kb, s0 = kb;
    auto walk = [&](bool forward, std::vector<Point2>& passed, Point2& end, std::size_t& end_seg) {
      double acc = 0;
      std::size_t k = kb;
      Point2 at = pb;
      for (std::size_t steps = 0; steps <= nseg; ++steps) {
        const Point2 v = forward ? L.seg[k].second : L.seg[k].first;
        const double l = dist(at, v);
        if (acc + l >= rho) {
          const double t = l > 0 ? (rho - acc) / l : 0;
          end = {at.x + t * (v.x - at.x), at.y + t * (v.y - at.y)};
          end_seg = k;
          return true;
        }
        acc += l;
        passed.push_back(v);
        at = v;
        k = forward ? (k + 1 == f1 ? f0 : k + 1) : (k == f0 ? f1 - 1 : k - 1);
        // Backward, the forward walk's last segment may be met: the ends' check below rejects it.
        if (in_run[k - f0] && (forward || k != s1)) return false;
        in_run[k - f0] = 1;
      }
      return false;
    };
    if (!walk(true, fwd, e1, s1) || !walk(false, bwd, e0, s0)) return std::vector<Point2>{};
    if (s0 == s1 && s0 != kb) return std::vector<Point2>{};  // met going round
    std::vector<Point2> run{e0};
    run.insert(run.end(), bwd.rbegin(), bwd.rend());
    run.insert(run.end(), fwd.begin(), fwd.end());
    run.push_back(e1);
    std::vector<Point2> all = isl;
    all.insert(all.end(), run.begin(), run.end());
    std::vector<Point2> h = convex_hull(all);
    if (h.size() < 3) return std::vector<Point2>{};
    auto index_of = [&](Point2 q) {
      for (std::size_t i = 0; i < h.size(); ++i)
        if (h[i].x == q.x && h[i].y == q.y) return i;
      return h.size();
    };
    const std::size_t i0 = index_of(e0), i1 = index_of(e1);
    if (i0 == h.size() || i1 == h.size()) return std::vector<Point2>{};
    const Box2 hb = box_of(h);
    const double harea = signed_area(h);
    if (harea > 3 * o.islet_side * o.islet_side) return std::vector<Point2>{};
    // The water side: the hull's chain from e1 round to e0 (counter-clockwise) or from e0 to e1,
    // whichever holds an islet vertex; with the run it bounds the water taken (and the islet).
    auto chain = [&](std::size_t from, std::size_t to) {
      std::vector<Point2> c;
      for (std::size_t i = from;; i = (i + 1) % h.size()) {
        c.push_back(h[i]);
        if (i == to) break;
      }
      return c;
    };
    auto holds_islet = [&](const std::vector<Point2>& c) {
      for (std::size_t i = 1; i + 1 < c.size(); ++i)
        for (Point2 q : isl)
          if (q.x == c[i].x && q.y == c[i].y) return true;
      return false;
    };
    std::vector<Point2> wc = chain(i1, i0), lc = chain(i0, i1);  // from e1 to e0, from e0 to e1
    const bool w1 = holds_islet(wc), w2 = holds_islet(lc);
    if (w1 == w2) return std::vector<Point2>{};
    std::vector<Point2> water = w1 ? wc : lc;  // ends e1 ... e0 or e0 ... e1
    if (!w1) std::reverse(water.begin(), water.end());  // now e1 ... e0
    // Closed by the run from e0 forward to e1 (without the ends, which the chain has).
    water.insert(water.end(), run.begin() + 1, run.end() - 1);
    const double taken_area = std::fabs(signed_area(water)) - std::fabs(signed_area(isl));
    // Room: the rings near the hull.
    Box2 cb{{hb.lo.x - cl, hb.lo.y - cl}, {hb.hi.x + cl, hb.hi.y + cl}};
    L.grid->segments_near(cb, &near);
    for (Index j : near) {
      const int r = L.ring[j];
      if (r == own || (!L.gone.empty() && L.gone[static_cast<std::size_t>(r)])) continue;
      const auto [a, b] = L.seg[j];
      if (r != ra) {
        if (convex_distance(a, b, h) < cl) return std::vector<Point2>{};
        continue;
      }
      if (j == s0 && j == s1) {  // the run lies inside one segment: the parts beyond its ends
        if (convex_distance(a, {e0.x + 1e-6 * (a.x - e0.x), e0.y + 1e-6 * (a.y - e0.y)}, h) == 0 ||
            convex_distance({e1.x + 1e-6 * (b.x - e1.x), e1.y + 1e-6 * (b.y - e1.y)}, b, h) == 0)
          return std::vector<Point2>{};
      } else if (j == s0) {  // the part before e0
        if (convex_distance(a, {e0.x + 1e-6 * (a.x - e0.x), e0.y + 1e-6 * (a.y - e0.y)}, h) == 0) return std::vector<Point2>{};
      } else if (j == s1) {  // the part after e1
        if (convex_distance({e1.x + 1e-6 * (b.x - e1.x), e1.y + 1e-6 * (b.y - e1.y)}, b, h) == 0) return std::vector<Point2>{};
      } else if (!in_run[j - f0]) {
        if (convex_distance(a, b, h) == 0) return std::vector<Point2>{};
      }
    }
    if (!hull_clear(L, h, inbox, joined, cl, false)) return std::vector<Point2>{};
    *taken = std::max(0.0, taken_area);
    *gap = best;
    return h;
  };
  {
    std::vector<std::unique_ptr<OGRPolygon>> wps;
    polygons_of(W.get(), wps);
    auto grown = std::make_unique<OGRMultiPolygon>();
    struct Homeless {  // an islet with no room for its triangle among the land as it is
      int ring;
      OGRLinearRing shape;
      Point2 centroid;
      double area;
      std::string what;
      Point2 inside;
    };
    std::vector<Homeless> homeless;
    std::vector<std::vector<Point2>> joined;  // hulls of the islets joined to land
    auto joins = std::make_unique<OGRMultiPolygon>();
    if (o.islet_side > 0 && o.min_island_area > 0) build_land(wps, land);
    const bool changed = filter_holes(wps, [&](const OGRLinearRing* h, double a) {
      OGRPolygon hp;
      hp.addRing(const_cast<OGRLinearRing*>(h));
      // An island above --min-island whose parts wider than close_width (what the closing leaves)
      // are below it is an islet too: removed as a remnant after the closing (step 2c), its
      // vertices were 43 of the 193 islets the Gulf of Maine lost, up to 2.5 hmin from the mesh.
      double a_wide = a;
      if (land.grid && !(a < o.min_island_area) && a < 4 * o.min_island_area && o.close_width > 0) {
        GeomPtr op = opening(hp, 0.5 * o.close_width);
        a_wide = area_of(op.get());
      }
      const bool thin = !(a < o.min_island_area) && a_wide < o.min_island_area;
      if (a_wide < o.min_island_area && land.grid) {
        const std::string what = thin ? "island of " + num(a) + " m^2 (" + num(a_wide) + " m^2 of it wider than " +
                                            num(o.close_width) + " m)"
                                      : "island of " + num(a) + " m^2";
        OGRPoint cen;
        if (hp.Centroid(&cen) == OGRERR_NONE) {
          if (place_islet(land, land.id_of.at(h), *h, {cen.getX(), cen.getY()}, a, what, islet_tris.get()))
            return false;
          if (!thin) {  // judged again below, when every islet without room is known
            homeless.push_back({land.id_of.at(h), *h, {cen.getX(), cen.getY()}, a, what, inside_point(&hp)});
            return false;
          }
        }
      }
      if (thin) return true;  // the closing and step 2c judge it
      if (a < o.min_island_area) {
        ++res.islands_removed;
        res.islands_area += a;
        res.repairs.push_back({"island_removed", inside_point(&hp), a,
                               "island of " + num(a) + " m^2 is smaller than " + num(o.min_island_area) +
                                   " m^2 (--min-island); it became water",
                               -1});
        return false;
      }
      if (a < o.grow_island_area && o.grow_island > 0) {
        GeomPtr g = checked(hp.Buffer(o.grow_island, kQuadSegs), "buffer of a small island");
        ++res.islands_grown;
        res.islands_grown_area += area_of(g.get()) - a;
        res.repairs.push_back({"island_enlarged", inside_point(&hp), area_of(g.get()) - a,
                               "island of " + num(a) + " m^2 is below the resolution; grown by " +
                                   num(o.grow_island) + " m so that elements near hmin fit around it",
                               -1});
        std::vector<std::unique_ptr<OGRPolygon>> gps;
        polygons_of(g.get(), gps);
        for (auto& gp : gps) grown->addGeometryDirectly(gp.release());
      }
      return true;
    });
    // Islets without room next to other islets without room (ledges, clusters of rocks): each
    // was judged with the others as land, so none got a triangle. They are all water unless
    // placed, so they are judged again with the others left out (in input order; the triangles
    // placed meanwhile count). Gulf of Maine (hmin 500): 87 of the 321 yardstick samples farther
    // than hmin/2 from the mesh's coast were vertices of islets whose nearest land was such an
    // islet.
    if (!homeless.empty()) {
      land.gone.assign(static_cast<std::size_t>(land.rings), 0);
      for (const Homeless& hl : homeless) land.gone[static_cast<std::size_t>(hl.ring)] = 1;
      std::vector<const Homeless*> still, lost;
      for (const Homeless& hl : homeless)
        if (!place_islet(land, hl.ring, hl.shape, hl.centroid, hl.area, hl.what, islet_tris.get())) still.push_back(&hl);
      OGREnvelope env;
      W->getEnvelope(&env);
      const Box2 inbox{{env.MinX, env.MinY}, {env.MaxX, env.MaxY}};
      for (const Homeless* hp : still) {
        const Homeless& hl = *hp;
        double taken = 0, gap = 0;
        std::vector<Point2> h = o.join_islets ? join_islet(land, hl.ring, hl.shape, inbox, joined, &taken, &gap)
                                              : std::vector<Point2>{};
        if (!h.empty()) {
          ++res.islets_joined;
          res.islets_joined_area += taken;
          res.repairs.push_back({"islet_joined", hl.inside, taken,
                                 hl.what + " is smaller than " + num(o.min_island_area) +
                                     " m^2 (--min-island) with no room for a triangle; joined to the land " +
                                     num(gap) + " m away: " + num(taken) + " m^2 of water between them became land",
                                 -1});
          OGRLinearRing jr;
          for (Point2 q : h) jr.addPoint(q.x, q.y);
          jr.closeRings();
          auto jp = std::make_unique<OGRPolygon>();
          jp->addRing(&jr);
          joins->addGeometryDirectly(jp.release());
          joined_box.push_back(box_of(h));
          joined.push_back(std::move(h));
          continue;
        }
        lost.push_back(&hl);
      }
      // An islet left next to an islet's triangle (nearer than islet_side): the convex hull of
      // the two replaces the triangle where it has room (as for a join). Why: the triangles
      // placed take the room of the islets around them (Gulf of Maine: 13 of the 66 islets left).
      if (o.join_islets) {
        std::vector<const Homeless*> rest;
        for (const Homeless* hp : lost) {
          std::vector<Point2> isl;
          for (int k = 0; k + 1 < hp->shape.getNumPoints(); ++k) isl.push_back({hp->shape.getX(k), hp->shape.getY(k)});
          double ext = 0;
          for (Point2 q : isl) ext = std::max(ext, dist(q, hp->centroid));
          std::size_t tb = placed.size();
          double db = o.islet_side;
          std::vector<Point2> corners_b;
          const double reach = ext + o.islet_side;
          placed_grid.near({{hp->centroid.x - reach, hp->centroid.y - reach}, {hp->centroid.x + reach, hp->centroid.y + reach}},
                           &cand);
          const std::vector<std::uint32_t> near_placed = cand;
          for (const std::size_t t : near_placed) {
            if (t >= static_cast<std::size_t>(islet_tris->getNumGeometries())) continue;
            if (dist(placed[t], hp->centroid) > placed_r[t] + ext + o.islet_side) continue;
            const OGRLinearRing* tr = islet_tris->getGeometryRef(static_cast<int>(t))->getExteriorRing();
            std::vector<Point2> cs;
            for (int k = 0; k + 1 < tr->getNumPoints(); ++k) cs.push_back({tr->getX(k), tr->getY(k)});
            double d = std::numeric_limits<double>::infinity();
            for (std::size_t a = 0; a < isl.size(); ++a)
              for (std::size_t b = 0; b < cs.size(); ++b)
                d = std::min(d, segment_distance(isl[a], isl[(a + 1) % isl.size()], cs[b], cs[(b + 1) % cs.size()]));
            if (d < db) { db = d; tb = t; corners_b = cs; }
          }
          bool done = false;
          if (tb < placed.size()) {
            std::vector<Point2> all = isl;
            all.insert(all.end(), corners_b.begin(), corners_b.end());
            std::vector<Point2> h = convex_hull(all);
            const double ha = h.size() >= 3 ? signed_area(h) : 0;
            const double ta = std::fabs(signed_area(corners_b));
            // The triangle's own islet and the triangle itself are not in the way.
            const int jr_ring = placed_ring[tb];
            const Point2 pc = placed[tb];
            const double pr = placed_r[tb];
            placed[tb] = {std::numeric_limits<double>::infinity(), 0.0};
            if (jr_ring >= 0) land.gone[static_cast<std::size_t>(jr_ring)] = 1;
            const bool ok = ha > 0 && ha - ta - hp->area <= 1.5 * o.islet_side * o.islet_side && hull_clear(land, h, inbox, joined, 0.5 * o.islet_side, true);
            placed[tb] = pc;
            if (ok) {
              double rr = 0;
              Point2 hc{0, 0};
              for (Point2 q : h) hc = hc + q;
              hc = (1.0 / static_cast<double>(h.size())) * hc;
              for (Point2 q : h) rr = std::max(rr, dist(q, hc));
              placed[tb] = hc;
              placed_r[tb] = rr;
              placed_grid.add(static_cast<std::uint32_t>(tb), hc, rr);
              placed_ring[tb] = -1;
              OGRLinearRing jr;
              for (Point2 q : h) jr.addPoint(q.x, q.y);
              jr.closeRings();
              OGRPolygon* tp = islet_tris->getGeometryRef(static_cast<int>(tb));
              tp->empty();
              tp->addRing(&jr);
              ++res.islets_joined;
              res.islets_joined_area += ha - ta - hp->area;
              res.repairs.push_back({"islet_joined", hp->inside, ha - ta - hp->area,
                                     hp->what + " is smaller than " + num(o.min_island_area) +
                                         " m^2 (--min-island) with no room for a triangle; joined to the triangle of an islet " +
                                         num(db) + " m away (their convex hull, " + num(ha) + " m^2)",
                                     -1});
              done = true;
            } else if (jr_ring >= 0 && !land.gone.empty()) {
              land.gone[static_cast<std::size_t>(jr_ring)] = 0;
            }
            (void)pr;
          }
          if (!done) rest.push_back(hp);
        }
        lost = std::move(rest);
      }
      // Clusters of the islets left (single link: nearer than islet_side to each other; ledges,
      // chains of rocks): the convex hull of a cluster becomes one island when it is at least
      // --min-island and has room (islet_side / 2 from other land, placed triangles and joins),
      // else one triangle for the cluster where there is room; otherwise each becomes water.
      const std::size_t nl = lost.size();
      std::vector<std::size_t> up(nl);
      for (std::size_t i = 0; i < nl; ++i) up[i] = i;
      auto root = [&](std::size_t i) {
        while (up[i] != i) i = up[i] = up[up[i]];
        return i;
      };
      std::vector<Box2> lb(nl);
      std::vector<std::vector<Point2>> lp(nl);
      for (std::size_t i = 0; i < nl; ++i) {
        const OGRLinearRing& r = lost[i]->shape;
        for (int k = 0; k + 1 < r.getNumPoints(); ++k) {
          lp[i].push_back({r.getX(k), r.getY(k)});
          lb[i].add(lp[i].back());
        }
      }
      const double dmax = o.islet_side;
      if (o.join_islets)
        for (std::size_t i = 0; i < nl; ++i)
          for (std::size_t j = i + 1; j < nl; ++j) {
            if (lb[j].lo.x > lb[i].hi.x + dmax || lb[i].lo.x > lb[j].hi.x + dmax || lb[j].lo.y > lb[i].hi.y + dmax ||
                lb[i].lo.y > lb[j].hi.y + dmax)
              continue;
            double d = std::numeric_limits<double>::infinity();
            for (std::size_t a = 0; a < lp[i].size(); ++a)
              for (std::size_t b = 0; b < lp[j].size(); ++b)
                d = std::min(d, segment_distance(lp[i][a], lp[i][(a + 1) % lp[i].size()], lp[j][b],
                                                 lp[j][(b + 1) % lp[j].size()]));
            if (d < dmax) up[root(i)] = root(j);
          }
      std::vector<std::vector<std::size_t>> members(nl);
      for (std::size_t i = 0; i < nl; ++i) members[root(i)].push_back(i);
      for (std::size_t c = 0; c < nl; ++c) {
        const auto& ms = members[c];
        if (ms.empty()) continue;
        if (ms.size() > 1) {
          std::vector<Point2> all;
          double sum = 0;
          for (std::size_t i : ms) {
            all.insert(all.end(), lp[i].begin(), lp[i].end());
            sum += lost[i]->area;
          }
          std::vector<Point2> h = convex_hull(all);
          const double ha = h.size() >= 3 ? signed_area(h) : 0;
          if (ha > 0 && ha - sum <= 1.5 * o.islet_side * o.islet_side * static_cast<double>(ms.size()) &&
              hull_clear(land, h, inbox, joined, 0.5 * o.islet_side, true)) {
            OGRLinearRing jr;
            for (Point2 q : h) jr.addPoint(q.x, q.y);
            jr.closeRings();
            const std::string what = std::to_string(ms.size()) + " islets of " + num(sum) + " m^2 in all, each nearer than " +
                                     num(dmax) + " m to the next";
            bool kept = false;
            if (!(ha < o.min_island_area)) {
              auto jp = std::make_unique<OGRPolygon>();
              jp->addRing(&jr);
              joins->addGeometryDirectly(jp.release());
              joined_box.push_back(box_of(h));
              joined.push_back(h);
              ++res.islets_joined;
              res.islets_joined_area += ha - sum;
              res.repairs.push_back({"islet_joined", lost[ms[0]]->inside, ha - sum,
                                     what + ", too small one by one (--min-island " + num(o.min_island_area) +
                                         " m^2): kept as one island, their convex hull of " + num(ha) + " m^2; " +
                                         num(ha - sum) + " m^2 of water between them became land",
                                     -1});
              kept = true;
            } else {
              Point2 cen{0, 0};
              for (Point2 q : h) cen = cen + q;
              cen = (1.0 / static_cast<double>(h.size())) * cen;
              kept = place_islet(land, -1, jr, cen, sum, what + " (their convex hull: " + num(ha) + " m^2)", islet_tris.get());
            }
            if (kept) continue;
          }
        }
        for (std::size_t i : ms) {
          const Homeless& hl = *lost[i];
          ++res.islands_removed;
          res.islands_area += hl.area;
          res.repairs.push_back({"island_removed", hl.inside, hl.area,
                                 "island of " + num(hl.area) + " m^2 is smaller than " + num(o.min_island_area) +
                                     " m^2 (--min-island) with no room for a triangle of side " +
                                     num(o.islet_side) + " m; it became water",
                                 -1});
        }
      }
      land.gone.clear();
    }
    if (changed || !grown->IsEmpty()) {
      GeomPtr w2 = multi(wps);
      if (!joins->IsEmpty())  // disjoint hulls, islet_side / 2 apart
        w2 = minus_touching(std::move(w2), *joins, "water minus islets joined to land");
      if (!grown->IsEmpty()) {
        GeomPtr gu = grown->getNumGeometries() > 1 ? checked(grown->UnionCascaded(), "union of grown islands")
                                                   : GeomPtr(grown.release());
        w2 = checked(w2->Difference(gu.get()), "water minus grown islands");
      }
      W = std::move(w2);
    }
  }
  lap("islands");

  // 1b'. Narrow water widened (see widen_thin_water): channels from close_width to widen_width wide.
  if (o.widen_width > o.close_width && o.close_width > 0) {
    W = widen_thin_water(*W, 0.5 * o.widen_width, 0.5 * o.close_width, o, res);
    lap("widen");
    if (dbg_time) {
      std::vector<std::unique_ptr<OGRPolygon>> ps;
      polygons_of(W.get(), ps);
      std::size_t nr = 0, nv = 0;
      for (const auto& p : ps) {
        nr += 1 + p->getNumInteriorRings();
        nv += p->getExteriorRing()->getNumPoints();
        for (int k = 0; k < p->getNumInteriorRings(); ++k) nv += p->getInteriorRing(k)->getNumPoints();
      }
      std::fprintf(stderr, "widened: %zu polygons, %zu rings, %zu vertices\n", ps.size(), nr, nv);
    }
  }

  // 1b''. The islets' triangles go in after the widening: placed before it, the narrow water they
  //       leave to the next land (at least islet_side / 2 at the corners) was widened into them,
  //       and they came out with sides of 0.4-0.55 hmin (Gulf of Maine: 18 more edges under hmin/2).
  //       The triangles are disjoint and inside the water with room around them (islet_room; the
  //       widening only added water): they become holes without an overlay (minus_disjoint; on a
  //       GSHHG-h basin the overlay with the whole water took 2.5 s).
  if (!islet_tris->IsEmpty()) {
    W = minus_disjoint(std::move(W), *islet_tris, "water minus islets");
    lap("islets");
  }

  // 1c. Closing at the same scale: land thinner than close_width (spits, slivers of land between
  //     two waters, thin islands) becomes water. Why: a sliver of land leaves two coast segments
  //     a fraction of hmin apart, and the water around it would need elements that small.
  //     Tips are the exception (below).
  if (o.close_width > 0) {
    const double rc = 0.5 * o.close_width;
    double land_cut = -1;  // >= 0 when the tips were judged one by one
    GeomPtr closed;
    if (o.tip_clearance > 0) {
      closed = closing_keep_tips(W.get(), o, res, &land_cut);
    } else {
      GeomPtr dil = offset(*W, rc);
      closed = offset(*dil, -rc);
    }
    // Closing never removes water; what it adds is reported (land taken away).
    const double added = land_cut >= 0 ? land_cut : area_of(closed.get()) - area_of(W.get());
    if (added > 0) res.land_removed_area += added;
    W = std::move(closed);
  }
  lap("closing");

  // 2. Openings; the pieces of O2 - O1 are judged one by one.
  GeomPtr R;
  std::vector<std::unique_ptr<OGRPolygon>> dropped;  // dead-end water closed
  if (o.close_width > 0) {
    const double r1 = 0.5 * o.close_width;
    const double r2 = 0.5 * std::clamp(o.min_feature, 0.0, o.close_width);
    // The two openings are independent: one on each core (OGR gives every GEOS call its own
    // context, so this is thread-safe; the result does not depend on the thread count).
    // Each opening gives the closed water's exact coast back where it runs within the snapping
    // distance of it (CoastRestorer), so O1 and O2 coincide bitwise there.
    const double hair = 0.05 * o.close_width;
    DebugLaps l1("  O1");
    const CoastRestorer restorer(W.get(), hair);  // read by both (restore() is const)
    l1("restorer");
    auto o2_job = std::async(std::launch::async, [&W, &restorer, r2] {
      GdalQuiet q2;
      DebugLaps l2("  O2");
      GeomPtr op = r2 > 0 ? opening(*W, r2) : nullptr;
      l2("opening");
      GeomPtr res = r2 > 0 ? restorer.restore(std::move(op)) : GeomPtr(W->clone());
      l2("restore");
      return res;
    });
    GeomPtr op1 = opening(*W, r1);
    l1("opening");
    GeomPtr O1 = restorer.restore(std::move(op1));
    l1("restore");
    GeomPtr O2 = o2_job.get();
    lap("O1+O2");
    std::vector<std::unique_ptr<OGRPolygon>> comps;
    polygons_of(O1.get(), comps);
    GeomPtr rest = O1->IsEmpty() ? GeomPtr(O2->clone())
                                   : std::getenv("FDR_DIFF_OVERLAY") ? checked(O2->Difference(O1.get()), "difference of openings")
                                   : difference_by_faces(O2.get(), O1.get(), "difference of openings");
    std::vector<std::unique_ptr<OGRPolygon>> pieces;
    polygons_of(rest.get(), pieces);
    lap("diff");
    std::vector<std::unique_ptr<OGRPolygon>> keep;
    for (auto& c : comps) keep.emplace_back(c->clone());
    // Pieces are tested against slightly grown copies: a piece and O1 share boundary points up
    // to GEOS rounding.
    const double grow = std::max(1e-6 * o.close_width, 1e-9);
    Meets o1_parts(comps, grow);
    for (auto& piece : pieces) {
      if (!(piece->get_Area() > 0)) continue;
      const std::size_t touching = o1_parts.count(*piece);
      if (touching == 1) {  // dead end: inlet, gap, corner or sliver (closed)
        dropped.push_back(std::move(piece));
        continue;
      }
      if (touching >= 2) ++res.channels_kept;  // a connection between water bodies
      keep.push_back(std::move(piece));         // or a water body of its own
    }
    if (dbg_time) {
      std::size_t nk = 0, vk = 0;
      for (const auto& k : keep) {
        ++nk;
        vk += k->getExteriorRing()->getNumPoints();
        for (int q = 0; q < k->getNumInteriorRings(); ++q) vk += k->getInteriorRing(q)->getNumPoints();
      }
      std::fprintf(stderr, "filter pieces %zu (O1 comps %zu), kept %zu with %zu vertices, dropped %zu\n", pieces.size(),
                   comps.size(), nk, vk, dropped.size());
    }
    lap("classify");
    R = union_pieces(keep, grow, "union of the kept water");
    lap("union kept");
    // Dropping a dead end next to a kept channel can leave two kept parts touching at a point
    // (GEOS calls that valid, the mesher would need zero-size elements there): open once more at
    // the connection scale.
    // Only where such a point exists: GEOS writes every point where rings meet as a vertex of
    // each, so a vertex that occurs twice (or a ring that repeats one) finds them all.
    // The opening is done locally, in squares around the pinch points: opening(R) at a point
    // depends on R within 2 r2 of it, so R clipped to squares 3 r2 larger gives the same result
    // in the inner squares (an ocean basin: 9.5 s for the whole of R).
    if (r2 > 0) {
      const std::vector<Point2> pins = pinch_points(R.get());
      if (dbg_time) for (const Point2& p : pins) std::fprintf(stderr, "pinch at %.3f %.3f\n", p.x, p.y);
      if (!pins.empty()) {
        auto squares = [&](double half) {
          std::vector<std::unique_ptr<OGRPolygon>> sq;
          for (const Point2& p : pins) {
            OGRLinearRing lr;
            lr.addPoint(p.x - half, p.y - half);
            lr.addPoint(p.x + half, p.y - half);
            lr.addPoint(p.x + half, p.y + half);
            lr.addPoint(p.x - half, p.y + half);
            lr.closeRings();
            auto poly = std::make_unique<OGRPolygon>();
            poly->addRing(&lr);
            sq.push_back(std::move(poly));
          }
          return union_pieces(sq, 0, "squares around pinch points");
        };
        const GeomPtr D = squares(3 * r2), D2 = squares(6 * r2);
        std::vector<std::unique_ptr<OGRPolygon>> rps, near_ps, far_ps;
        polygons_of(R.get(), rps);
        OGREnvelope de;
        D2->getEnvelope(&de);
        for (auto& rp : rps) {
          OGREnvelope re;
          rp->getEnvelope(&re);
          (re.Intersects(de) ? near_ps : far_ps).push_back(std::move(rp));
        }
        GeomPtr Rn = multi(near_ps);
        GeomPtr local = checked(Rn->Intersection(D2.get()), "water near pinch points");
        GeomPtr opened = opening(*local, r2);
        // (Rn - D) + (opened & D) = Rn - ((Rn & D) - opened), as opened lies in Rn: one overlay of
        // the big polygon with the small removed part instead of a difference and a union; the
        // coordinates go back to the input's in step 3.
        GeomPtr in_d = checked(local->Intersection(D.get()), "water near pinch points");
        GeomPtr removed = checked(in_d->Difference(opened.get()), "water the local opening removes");
        GeomPtr Rn2 = removed->IsEmpty() ? std::move(Rn) : checked(Rn->Difference(removed.get()), "water with opened pinch points");
        polygons_of(Rn2.get(), far_ps);
        R = multi(far_ps);
      }
    }
    lap("final opening");
  } else {
    R.reset(W->clone());
  }

  // 2b. One mesh piece per input water body: pieces cut off by a closed connection are removed
  //     (a water body the model cannot reach), keeping the largest piece of each input body.
  {
    std::vector<std::unique_ptr<OGRPolygon>> wps, rps;
    polygons_of(W0.get(), wps);
    polygons_of(R.get(), rps);
    std::vector<int> owner(rps.size(), -1);
    std::vector<Point2> rin(rps.size());  // inner points, computed once
    std::vector<char> has_rin(rps.size(), 0);
    for (std::size_t i = 0; i < wps.size() && rps.size() > 1; ++i) {
      Prepared pw(wps[i].get());
      OGREnvelope we;
      wps[i]->getEnvelope(&we);
      for (std::size_t j = 0; j < rps.size(); ++j) {
        if (owner[j] >= 0) continue;
        if (!has_rin[j]) { rin[j] = inside_point(rps[j].get()); has_rin[j] = 1; }
        const Point2 q = rin[j];
        if (!(we.MinX <= q.x && q.x <= we.MaxX && we.MinY <= q.y && q.y <= we.MaxY)) continue;
        OGRPoint pt(q.x, q.y);
        if (pw.intersects(&pt)) owner[j] = static_cast<int>(i);
      }
    }
    // A piece whose inner point lies outside every input body (water the closing added between
    // land that was thinner than --close-width): its owner is the input body it overlaps most.
    for (std::size_t j = 0; j < rps.size() && rps.size() > 1; ++j) {
      if (owner[j] >= 0) continue;
      OGREnvelope re;
      rps[j]->getEnvelope(&re);
      // (by its vertices, most of which are input coast: an overlay with a basin polygon costs seconds)
      int best = 0;
      const OGRLinearRing* ring = rps[j]->getExteriorRing();
      const int nv = ring->getNumPoints();
      for (std::size_t i = 0; i < wps.size(); ++i) {
        OGREnvelope we;
        wps[i]->getEnvelope(&we);
        if (!we.Intersects(re)) continue;
        Prepared pw(wps[i].get());
        int hits = 0;
        for (int k = 0; k < nv; k += std::max(1, nv / 16)) {
          OGRPoint pt(ring->getX(k), ring->getY(k));
          hits += pw.intersects(&pt);
        }
        if (hits > best) {
          best = hits;
          owner[j] = static_cast<int>(i);
        }
      }
      // (water the widening added: its vertices lie on former land; the body it meets owns it)
      for (std::size_t i = 0; i < wps.size() && owner[j] < 0; ++i) {
        OGREnvelope we;
        wps[i]->getEnvelope(&we);
        if (!we.Intersects(re)) continue;
        Prepared pw(wps[i].get());
        if (pw.intersects(rps[j].get())) owner[j] = static_cast<int>(i);
      }
    }
    std::vector<int> best(wps.size(), -1);
    for (std::size_t j = 0; j < rps.size(); ++j) {
      if (owner[j] < 0) continue;
      int& b = best[static_cast<std::size_t>(owner[j])];
      if (b < 0 || rps[j]->get_Area() > rps[static_cast<std::size_t>(b)]->get_Area()) b = static_cast<int>(j);
    }
    std::vector<std::unique_ptr<OGRPolygon>> kept;
    for (std::size_t j = 0; j < rps.size(); ++j) {
      if (owner[j] >= 0 && best[static_cast<std::size_t>(owner[j])] != static_cast<int>(j)) {
        const double a = rps[j]->get_Area();
        ++res.cut_off;
        res.cut_off_area += a;
        res.repairs.push_back({"cut_off_water_removed", inside_point(rps[j].get()), a,
                               "water body of " + num(a) + " m^2 joined to the rest only through a connection "
                               "narrower than " + num(o.min_feature) + " m (--min-feature); it was removed",
                               -1});
        continue;
      }
      kept.push_back(std::move(rps[j]));
    }
    R = multi(kept);
  }
  lap("owners");

  // 2c. Islands that the closing shrank below the resolution (thin islands leave small remnants).
  if (o.min_island_area > 0) {
    std::vector<std::unique_ptr<OGRPolygon>> rps;
    polygons_of(R.get(), rps);
    auto remnant_tris = std::make_unique<OGRMultiPolygon>();
    // Room for a remnant's triangle is judged on the land as it is now (the remnant's own island
    // may have left other, larger parts).
    LandIndex now;
    if (o.islet_side > 0) build_land(rps, now);
    lap("remnants: land index");
    const bool changed = filter_holes(rps, [&](const OGRLinearRing* h, double a) {
      if (!(a < o.min_island_area)) return true;
      OGRPolygon hp;
      hp.addRing(const_cast<OGRLinearRing*>(h));
      if (!placed.empty()) {  // an islet's triangle stays
        OGRPoint cen;
        if (hp.Centroid(&cen) == OGRERR_NONE)
          for (const Point2& q : placed)
            if (dist(q, {cen.getX(), cen.getY()}) < 0.1 * o.islet_side) return true;
      }
      const std::string what = "island remnant of " + num(a) + " m^2 (land thinner than " + num(o.close_width) +
                               " m became water)";
      if (now.grid) {  // a triangle where there is room, as for the islets of step 1b
        OGRPoint cen;
        if (hp.Centroid(&cen) == OGRERR_NONE &&
            place_islet(now, now.id_of.at(h), *h, {cen.getX(), cen.getY()}, a, what, remnant_tris.get()))
          return false;
      }
      ++res.islands_removed;
      res.islands_area += a;
      res.repairs.push_back({"island_removed", inside_point(&hp), a,
                             what + " is smaller than " + num(o.min_island_area) + " m^2 (--min-island); it became water",
                             -1});
      return false;
    });
    if (changed) R = multi(rps);
    lap("remnants: holes");
    if (!remnant_tris->IsEmpty()) R = minus_disjoint(std::move(R), *remnant_tris, "water minus remnants' triangles");
  }

  // 3. Back to the input's coordinates: buffers return the unchanged coast only up to rounding
  //    (and a vertex with a slight turn as two close arc points). Every result vertex within
  //    5 % of --close-width of an input vertex takes that vertex's exact coordinates, so coast,
  //    breaklines, open boundaries and fixed points still meet exactly where nothing was removed.
  lap("remnants");
  if (o.close_width > 0) {
    R = CoastRestorer(W0.get(), 0.05 * o.close_width).restore(std::move(R));
  }
  lap("restore");
  std::future<GeomPtr> gone_job;  // W0 - result
  bool early = false;  // the listing starts at once (early_listing_rss)
  std::vector<std::unique_ptr<OGRPolygon>> outp;
  polygons_of(R.get(), outp);
  if (o.close_width > 0) {
    std::vector<std::unique_ptr<OGRPolygon>> wps;
    polygons_of(W0.get(), wps);
    // A snap that makes a polygon invalid (a vertex moved across a nearby edge) is not taken:
    // that polygon keeps the buffers' coordinates.
    for (auto& p : outp) {
      std::unique_ptr<OGRPolygon> q(p->clone());
      snap_to_input->snap(q.get());
      // (the exact sufficient test first: GEOS's IsValid on a polygon with a thousand holes
      // costs a tenth of a second)
      Rings qr;
      qr.push_back(ring_points(q->getExteriorRing(), true));
      for (int k = 0; k < q->getNumInteriorRings(); ++k) qr.push_back(ring_points(q->getInteriorRing(k), false));
      if (surely_valid(qr) || q->IsValid()) p = std::move(q);
    }
    // The input minus the result (for the listing of removed water below), computed on the other
    // core while this one checks the water bodies and cleans tiny edges (results in the same
    // order; GEOS on its own copies).
    {
      auto rm = std::make_unique<OGRMultiPolygon>();
      for (const auto& p : outp) rm->addGeometry(p.get());
      auto job = [w0 = GeomPtr(W0->clone()), rm = std::move(rm)]() mutable {
        GdalQuiet q2;
        return std::getenv("FDR_DIFF_OVERLAY") ? checked(w0->Difference(rm.get()), "difference input - result")
                                               : difference_by_faces(w0.get(), rm.get(), "difference input - result");
      };
      // Deferred with the listing (defer_removed): the caller starts both where a core is free,
      // unless the input is large (early_listing_rss): then at once, on the read's arena (its
      // freed pages are kept and on huge pages while the read runs, and a large input's read
      // goes on long enough that the listing is done before the mesh stages release pages
      // eagerly; an arena of its own raised the GSHHG-h basin's peak by 100-130 MB).
      if (o.defer_removed && o.early_listing_rss > 0 && max_threads() >= 2) {
        const std::optional<ProcessMemory> mm = process_memory();
        early = mm && mm->rss >= o.early_listing_rss;
      }
      gone_job = std::async(max_threads() >= 2 && (early || !o.defer_removed) ? std::launch::async : std::launch::deferred,
                            std::move(job));
    }
    // Whole input water bodies nowhere --min-feature wide.
    // (each result piece's inner point computed once, each input body prepared once: an ocean
    // basin spent 0.7 s here recomputing them per pair)
    std::vector<std::unique_ptr<OGRPolygon>> rps;
    polygons_of(R.get(), rps);
    std::vector<OGREnvelope> renv(rps.size());
    for (std::size_t j = 0; j < rps.size(); ++j) rps[j]->getEnvelope(&renv[j]);
    std::vector<std::unique_ptr<OGRPoint>> rin(rps.size());
    for (const auto& w : wps) {
      OGREnvelope we;
      w->getEnvelope(&we);
      bool any = false;
      std::unique_ptr<Prepared> pw;
      for (std::size_t j = 0; j < rps.size(); ++j) {
        if (!we.Intersects(renv[j])) continue;
        if (!rin[j]) {
          const Point2 q = inside_point(rps[j].get());
          rin[j] = std::make_unique<OGRPoint>(q.x, q.y);
        }
        if (!pw) pw = std::make_unique<Prepared>(w.get());
        if (pw->intersects(rin[j].get())) { any = true; break; }
      }
      if (any) continue;
      const double a = w->get_Area();
      ++res.closed;
      res.closed_area += a;
      res.repairs.push_back({"water_body_removed", inside_point(w.get()), a,
                             "water body of " + num(a) + " m^2 is nowhere " + num(o.min_feature) +
                                 " m wide (--min-feature); it was removed",
                             -1});
    }
  }
  lap("removed (start)");
  // Input vertices (exact coordinates), for the tiny-edge clean-up below.
  std::unordered_set<std::uint64_t> input_vertex;
  if (o.close_width > 0) {
    std::vector<std::unique_ptr<OGRPolygon>> wps;
    polygons_of(W0.get(), wps);
    for (const auto& w : wps)
      for (int k = -1; k < w->getNumInteriorRings(); ++k) {
        const OGRLinearRing* r = k < 0 ? w->getExteriorRing() : w->getInteriorRing(k);
        for (int i = 0; i < r->getNumPoints(); ++i) input_vertex.insert(point_key(r->getX(i), r->getY(i)));
      }
  }
  for (const auto& p : outp) {
    if (p->IsEmpty()) continue;
    Rings rings;
    rings.push_back(ring_points(p->getExteriorRing(), true));
    for (int k = 0; k < p->getNumInteriorRings(); ++k) rings.push_back(ring_points(p->getInteriorRing(k), false));
    if (rings[0].size() < 3) continue;
    if (o.close_width > 0) {
      // Tiny edges: where a cut or a widened bank meets the input coast, GEOS leaves a vertex a
      // few metres from a corner (an arc point, an intersection point); the mesh would refine to
      // that distance around it. A corner (turning by more than 30 degrees) that is not an input
      // vertex and is nearer than a quarter of --close-width to a neighbour is dropped (the coast
      // moves by less than that), when the polygon stays valid.
      const double tiny = o.close_width / 4;
      Rings cleaned = rings;
      bool changed = false;
      for (int pass = 0; pass < 3; ++pass) {  // capped; a pass without a drop ends it
      const Rings cur = cleaned;
      // Every segment of the polygon in a grid: a drop replaces p-v-n by p-n, which keeps the
      // polygon valid when no other segment meets p-n and no other vertex lies in the triangle
      // (exact orientation tests). Drops in one pass never touch neighbours.
      std::vector<std::size_t> first(cur.size() + 1, 0);
      for (std::size_t k = 0; k < cur.size(); ++k) first[k + 1] = first[k] + cur[k].size();
      std::unique_ptr<pslg::SegmentGrid> grid;
      std::vector<Index> near;
      auto seg_of = [&](Index id, std::size_t* rk, std::size_t* j) {
        *rk = static_cast<std::size_t>(std::upper_bound(first.begin(), first.end(), static_cast<std::size_t>(id)) - first.begin()) - 1;
        *j = id - first[*rk];
      };
      auto inside_tri = [](Point2 a, Point2 b, Point2 c, Point2 q) {  // closed triangle
        const int o1 = predicates::orient2d(a, b, q), o2 = predicates::orient2d(b, c, q), o3 = predicates::orient2d(c, a, q);
        return (o1 >= 0 && o2 >= 0 && o3 >= 0) || (o1 <= 0 && o2 <= 0 && o3 <= 0);
      };
      auto meets = [](Point2 a, Point2 b, Point2 c, Point2 d) {  // closed segments
        const int o1 = predicates::orient2d(a, b, c), o2 = predicates::orient2d(a, b, d);
        const int o3 = predicates::orient2d(c, d, a), o4 = predicates::orient2d(c, d, b);
        if (o1 == 0 && o2 == 0)
          return std::max(std::min(a.x, b.x), std::min(c.x, d.x)) <= std::min(std::max(a.x, b.x), std::max(c.x, d.x)) &&
                 std::max(std::min(a.y, b.y), std::min(c.y, d.y)) <= std::min(std::max(a.y, b.y), std::max(c.y, d.y));
        return o1 * o2 <= 0 && o3 * o4 <= 0;
      };
      auto drop_ok = [&](std::size_t rk, std::size_t i, Point2 p, Point2 v, Point2 n) {
        if (!grid) {
          Box2 box;
          double total = 0;
          for (const auto& r : cur)
            for (std::size_t q = 0; q < r.size(); ++q) { box.add(r[q]); total += dist(r[q], r[(q + 1) % r.size()]); }
          grid = std::make_unique<pslg::SegmentGrid>(box, first.back(), std::max(total / static_cast<double>(first.back()), 1e-6));
          for (std::size_t k = 0; k < cur.size(); ++k)
            for (std::size_t q = 0; q < cur[k].size(); ++q)
              grid->add_segment(static_cast<Index>(first[k] + q), cur[k][q], cur[k][(q + 1) % cur[k].size()]);
        }
        Box2 qb;
        qb.add(p); qb.add(v); qb.add(n);
        grid->segments_near(qb, &near);
        const std::size_t m = cur[rk].size();
        for (Index id : near) {
          std::size_t sk, j;
          seg_of(id, &sk, &j);
          if (sk == rk && (j == i || j == (i + m - 1) % m)) continue;  // p-v and v-n themselves
          const Point2 c = cur[sk][j], d = cur[sk][(j + 1) % cur[sk].size()];
          const bool cp = c == p || c == n, dp = d == p || d == n;
          if (cp && dp) return false;
          if (!cp && !dp) {
            if (meets(p, n, c, d) || inside_tri(p, v, n, c) || inside_tri(p, v, n, d)) return false;
          } else if (inside_tri(p, v, n, cp ? d : c)) {
            return false;
          }
        }
        return true;
      };
      bool pass_changed = false;
      for (std::size_t rk = 0; rk < cleaned.size(); ++rk) {
        auto& r = cleaned[rk];
        std::vector<char> drop(r.size(), 0);
        std::size_t drops = 0;
        const std::size_t n = r.size();
        for (std::size_t i = 0; i < n && n - drops > 3; ++i) {
          const std::size_t ip = (i + n - 1) % n, in = (i + 1) % n;
          if (drop[ip] || (in == 0 && drop[0])) continue;  // never two neighbours
          const Point2 v = r[i], pv = r[ip], nv = r[in];
          if (input_vertex.count(point_key(v.x, v.y))) continue;
          if (!(dist(v, pv) < tiny || dist(v, nv) < tiny)) continue;
          // only a corner (turning by more than 30 degrees): the points of a rounded corner turn
          // less (22.5 degrees at most), and dropping one next to a long edge would tilt that edge
          const Point2 e0 = v - pv, e1 = nv - v;
          const double cr = e0.x * e1.y - e0.y * e1.x, dt = e0.x * e1.x + e0.y * e1.y;
          if (!(std::atan2(std::fabs(cr), dt) > 0.5235987755982988)) continue;  // pi / 6
          if (!drop_ok(rk, i, pv, v, nv)) continue;
          drop[i] = 1;
          ++drops;
        }
        if (drops == 0) continue;
        std::vector<Point2> kept;
        kept.reserve(n - drops);
        for (std::size_t i = 0; i < n; ++i)
          if (!drop[i]) kept.push_back(r[i]);
        r = std::move(kept);
        changed = pass_changed = true;
      }
      if (!pass_changed) break;
      }
      if (changed) {
        bool ok = surely_valid(cleaned);
        if (!ok) {
          OGRPolygon q = to_ogr(cleaned);
          ok = q.IsValid();
        }
        if (ok) rings = std::move(cleaned);
        if (dbg_time) std::fprintf(stderr, "tiny edges: polygon of %zu rings cleaned: %s\n", rings.size(), ok ? "valid" : "invalid, kept");
      }
    }
    res.output_area += std::fabs(signed_area(rings[0]));
    for (std::size_t k = 1; k < rings.size(); ++k) res.output_area -= std::fabs(signed_area(rings[k]));
    res.polygons.push_back(std::move(rings));
  }
  if (o.close_width > 0) {
    // The places of the water bodies already listed as removed (collected once: the repairs list
    // holds thousands of entries, the removed pieces are thousands too).
    std::vector<Point2> listed_at;
    for (const auto& r : res.repairs)
      if (r.kind == "cut_off_water_removed" || r.kind == "water_body_removed") listed_at.push_back(r.where);
    auto listing = [gone = std::move(gone_job), listed_at = std::move(listed_at), hair = 0.05 * o.close_width,
                    list_area = o.list_area, close_width = o.close_width]() mutable {
      GdalQuiet q2;
      DebugLaps l3("  listing");
      GeomPtr g = gone.get();
      l3("difference");
      RemovedWater w = list_removed_water(std::move(g), listed_at, hair, list_area, close_width);
      l3("list");
      return w;
    };
    if (o.defer_removed) {
      // Started by the caller (start_removed) where a core is free; finish_removed() takes it.
      res.removed_pending = std::make_shared<PendingRemoved>();
      res.removed_pending->job = std::async(std::launch::deferred, std::move(listing));
      if (early) start_removed(res, false);  // its difference already runs: the listing goes on from it
    } else {
      add_removed(res, listing());
    }
  }
  lap("removed");
  res.output_pieces = res.polygons.size();
  if (const char* dbg = debug::value(debug::Aid::kFilter)) {  // developer aid: WKT of the result
    if (FILE* fp = std::fopen(dbg, "w")) {
      for (const auto& p : outp) {
        char* wkt = nullptr;
        p->exportToWkt(&wkt);
        std::fprintf(fp, "%s\n", wkt);
        CPLFree(wkt);
      }
      std::fclose(fp);
    }
  }
  if (res.polygons.empty())
    throw Error(ExitCode::kInvalidGeometry,
                "no water wider than " + num(o.close_width) +
                    " m (--close-width, default --hmin) is left; lower --hmin or give --close-width 0");
  return res;
}

}  // namespace fdr::gis
