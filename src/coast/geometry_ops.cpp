// The GEOS adapter of the coast generalisation (geometry_ops.hpp).
#include "coast/geometry_ops.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>

#include "base/error.hpp"
#include "base/parallel.hpp"
#include "coast/box_index.hpp"
#include "coast/convex.hpp"
#include "coast/faces.hpp"
#include "coast/report.hpp"
#include "pslg/contained_difference.hpp"

namespace fdr::coast {

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

namespace {

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

}  // namespace

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

namespace {

// p grown by `hair` (one segment per quarter circle) for contact tests: its outer ring grown and
// its holes shrunk, each on its own. Why: GEOS buffers a polygon with thousands of holes by
// placing every hole of its result in a shell with a point index built anew for each test,
// quadratic in the holes; the rings of this polygon are the same buffers, and they cannot meet
// (each is at least `hair` from the input's rings), so they go together without an overlay.
GeomPtr grown_for_contact(const OGRPolygon& p, double hair) {
  if (p.getNumInteriorRings() == 0) return checked(p.Buffer(hair, 1), "buffer");
  OGRPolygon outer;
  outer.addRing(const_cast<OGRLinearRing*>(p.getExteriorRing()));
  GeomPtr b = checked(outer.Buffer(hair, 1), "buffer of an outer ring");
  std::vector<std::unique_ptr<OGRPolygon>> bs;
  polygons_of(b.get(), bs);
  if (bs.size() != 1) return checked(p.Buffer(hair, 1), "buffer");
  auto out = std::move(bs[0]);
  for (int k = 0; k < p.getNumInteriorRings(); ++k) {
    const OGRLinearRing* h = p.getInteriorRing(k);
    OGREnvelope e;
    h->getEnvelope(&e);
    if (std::min(e.MaxX - e.MinX, e.MaxY - e.MinY) <= 2 * hair) continue;  // nothing left of it
    OGRPolygon hp;
    hp.addRing(const_cast<OGRLinearRing*>(h));
    GeomPtr hb = checked(hp.Buffer(-hair, 1), "buffer of a hole");
    std::vector<std::unique_ptr<OGRPolygon>> hps;
    polygons_of(hb.get(), hps);
    for (const auto& q : hps) out->addRing(const_cast<OGRLinearRing*>(q->getExteriorRing()));
  }
  return GeomPtr(out.release());
}

}  // namespace

// The union of polygon pieces, overlaid only where they meet. Why: GEOS's cascaded union of a
// polygon with a thousand holes and fifty small pieces overlays the big one at every level of
// its tree; most pieces meet nothing, and the few that meet the big one
// are united first and overlaid with it once. Pieces are grouped when their envelopes, grown by
// `hair`, meet and the pieces (the smaller one grown by `hair`) intersect; the result equals the
// union of all pieces.
// `family` (optional, one label per piece): pieces with the same label have disjoint interiors
// (the polygons of one valid multipolygon); the others of a group that all share one label are
// overlaid with the big one as they are, without a cascaded union among themselves (the widened
// water: many grown pieces that never overlap each other).
GeomPtr union_pieces(std::vector<std::unique_ptr<OGRPolygon>>& ps, double hair, const char* what,
                     const std::vector<int>* family) {
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
      // Pieces that meet as they are meet grown too: the buffer only for those that do not.
      bool meet = prep[big]->intersects(ps[small].get());
      if (!meet && hair > 0) {
        if (!grown[small]) grown[small] = grown_for_contact(*ps[small], hair);
        meet = prep[big]->intersects(grown[small].get());
      }
      if (meet) parent[find(i)] = find(j);
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

namespace {

// Whether the boundary of a polygon with many rings meets a small polygon without holes: a
// segment of one crosses or touches the other's, or a whole ring lies inside it. Why not GEOS's
// prepared test of the boundary against the polygon: after the segments it locates one point of
// every ring of the boundary in the polygon, for every polygon tested.
class RingsNear {
 public:
  RingsNear(const OGRGeometry& b, const OGRGeometry& boundary) : segs_(&boundary) {
    polygons_of(&b, ps_);
    for (const auto& p : ps_)
      for (int k = -1; k < p->getNumInteriorRings(); ++k) {
        rings_.push_back(k < 0 ? p->getExteriorRing() : p->getInteriorRing(k));
        env_.emplace_back();
        rings_.back()->getEnvelope(&env_.back());
      }
    index_ = std::make_unique<BoxIndex>(env_);
  }
  bool meets(const OGRPolygon& hp) const {
    OGRLineString line;
    line.addSubLineString(hp.getExteriorRing());
    if (segs_.intersects(&line)) return true;
    OGREnvelope he;
    hp.getEnvelope(&he);
    std::vector<std::size_t> near;
    index_->near(he, &near);
    for (const std::size_t i : near) {
      if (!he.Contains(env_[i])) continue;
      const OGRPoint pt(rings_[i]->getX(0), rings_[i]->getY(0));
      if (hp.Intersects(&pt)) return true;
    }
    return false;
  }

 private:
  Prepared segs_;
  OwnedPolygons ps_;
  std::vector<const OGRLinearRing*> rings_;
  std::vector<OGREnvelope> env_;
  std::unique_ptr<BoxIndex> index_;
};

}  // namespace

// b minus u, where u's polygons are disjoint (a union's pieces). Those strictly inside b (touching
// neither its boundary nor each other) become holes directly; the overlay gets only the others
// (see detach_far_holes: GEOS places every hole of an overlay's result by a linear scan).
// A polygon without holes that misses b's boundary is connected, so it lies wholly inside b or
// wholly outside: one of its vertices says which (GEOS's containment test of the whole polygon
// locates every vertex and crosses every segment again).
GeomPtr minus_disjoint(GeomPtr b, const OGRGeometry& u, const char* what) {
  std::vector<std::unique_ptr<OGRPolygon>> hps, over;
  polygons_of(&u, hps);
  std::vector<std::unique_ptr<OGRLinearRing>> free_holes;
  if (hps.size() >= 32) {
    GeomPtr bnd(b->Boundary());
    Prepared pb(b.get());
    const RingsNear near_b(*b, *bnd);
    auto inside_b = [&pb](const OGRPolygon& hp) {
      const OGRLinearRing* r = hp.getExteriorRing();
      const OGRPoint pt(r->getX(0), r->getY(0));
      return pb.contains(&pt);
    };
    for (auto& hp : hps) {
      if (hp->getNumInteriorRings() == 0 && !hp->IsEmpty() && !near_b.meets(*hp) && inside_b(*hp))
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


namespace {

// Ring r without the vertices that lie within eps of the vertex kept before them (and the
// closure's). Why: an earlier buffer's output can hold a cluster of vertices 1e-10 m apart (where
// an islet joined to land rounded a corner); buffering such a ring again, GEOS's noding fails and
// it retries the whole ring at reduced precision, ten times slower. Nothing else moves; a ring
// that would lose its area is left as it is.
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

}  // namespace

// Offset of valid polygons by r (> 0 grows, < 0 shrinks), ring by ring: for a polygon with
// outer ring O and holes H_i, (O - U H_i) (+) r = (O (+) r) - U (H_i (-) r), and the same with
// the signs swapped for shrinking. Why: GEOS buffers a simple ring far faster than a polygon with
// a thousand holes, and the holes are independent.
// g grown by r (shrunk for r < 0); near_repeats: g is an earlier buffer's output, its clusters
// of vertices within 1e-6 r are merged first (drop_near_repeats).
GeomPtr offset(const OGRGeometry& g, double r, int quad_segs, bool near_repeats) {
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
    // The outer ring's buffer and the holes' on two cores when both are big; the same geometries
    // in the same order either way.
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
// whole of both, slowly (mostly in its snapping fallback where two rings differ by a vertex). The boundary of a - b lies on the segments that are not shared with the same
// interior side (such a segment has a and b on the same side, so a - b on neither), so every
// face of the arrangement of the non-shared segments lies wholly inside a - b or wholly outside
// it: the segments are noded, polygonized, and each face is kept when an inner point lies in a
// and not in b. (A shared ring inside a face, an island both keep, cannot border a - b, so such a
// face is outside it, and any inner point says so.) `overlay`: GEOS's overlay (for the test
// that the results are the same).
GeomPtr difference_by_faces(const OGRGeometry* a, const OGRGeometry* b, const char* what, bool overlay) {
  if (overlay) return checked(a->Difference(b), what);
  using Key = std::array<std::uint64_t, 4>;
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
  // Each side's segments as a sorted vector (searched by bisection): a hash set of hundreds of
  // thousands of segments costs more in its nodes than the sort.
  auto keys_of = [&](const std::vector<Ring>& rs) {
    std::size_t n = 0;
    for (const Ring& q : rs) n += static_cast<std::size_t>(std::max(0, q.r->getNumPoints() - 1));
    std::vector<Key> s;
    s.reserve(n);
    for (const Ring& q : rs)
      for (int i = 0; i + 1 < q.r->getNumPoints(); ++i)
        s.push_back(key(q.r->getX(i), q.r->getY(i), q.r->getX(i + 1), q.r->getY(i + 1), q.left));
    std::sort(s.begin(), s.end());
    return s;
  };
  FilterLaps dl("  by faces");
  std::vector<Key> ka, kb;
  run_beside([&] { ka = keys_of(ra); }, [&] { kb = keys_of(rb); });
  dl("keys");
  // The non-shared segments, as maximal runs.
  OGRMultiLineString lines;
  auto add_runs = [&](const std::vector<Ring>& rs, const std::vector<Key>& other) {
    for (const Ring& q : rs) {
      const OGRLinearRing* r = q.r;
      const int n = r->getNumPoints();
      if (n < 2) continue;
      std::vector<char> own(static_cast<std::size_t>(n - 1));
      bool any = false, all = true;
      for (int i = 0; i + 1 < n; ++i) {
        const Key k = key(r->getX(i), r->getY(i), r->getX(i + 1), r->getY(i + 1), q.left);
        own[static_cast<std::size_t>(i)] = std::binary_search(other.begin(), other.end(), k) ? 0 : 1;
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
  std::vector<std::unique_ptr<OGRPolygon>> fs, out;
  if (!arrangement_faces(lines, fs)) return fallback();
  dl("noded and polygonized");
  const Prepared in_a(a), in_b(b);
  for (auto& f : fs) {
    Point2 p;
    if (!face_point(*f, p)) continue;  // no interior: no area
    const OGRPoint pt(p.x, p.y);
    if (in_a.contains(&pt) && !in_b.contains(&pt)) out.push_back(std::move(f));
  }
  dl("faces");
  if (debug::value(debug::Aid::kFilter))
    std::fprintf(stderr, "difference by faces: %d lines, %zu faces, %zu pieces\n", lines.getNumGeometries(), fs.size(), out.size());
  return GeomPtr(multi(out).release());
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
// noding; null when that refuses (it says why under the kFilter developer aid) or with `overlay`
// (the callers then overlay with GEOS, to compare).
GeomPtr traced_difference(const OGRGeometry& a, const OGRGeometry& b, const char* what, bool overlay) {
  if (!overlay) {
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
      return GeomPtr(m.release());
    }
    if (debug::value(debug::Aid::kFilter))
      std::fprintf(stderr, "%s: not traced (%s)\n", what, st.refused ? st.refused : "?");
  }
  return nullptr;
}

GeomPtr difference_contained(const OGRGeometry& a, const OGRGeometry& b, const char* what, bool overlay) {
  if (GeomPtr r = traced_difference(a, b, what, overlay)) return r;
  return checked(a.Difference(&b), what);
}

OGRPolygon box_polygon(const OGREnvelope& e) {
  OGRLinearRing lr;
  lr.addPoint(e.MinX, e.MinY);
  lr.addPoint(e.MaxX, e.MinY);
  lr.addPoint(e.MaxX, e.MaxY);
  lr.addPoint(e.MinX, e.MaxY);
  lr.closeRings();
  OGRPolygon p;
  p.addRing(&lr);
  return p;
}

}  // namespace fdr::coast
