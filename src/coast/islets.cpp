// Steps: islets replaced or joined, and island remnants after the closing (islets.hpp).
#include "coast/islets.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "coast/islet_clusters.hpp"
#include "coast/report.hpp"

namespace fdr::coast {
namespace {

struct Homeless {  // an islet with no room for its triangle among the land as it is
  int ring;
  OGRLinearRing shape;
  Point2 centroid;
  double area;
  std::string what;
  Point2 inside;
};

// The islet step on one water geometry: the islands judged one by one (judge), then the islets
// without room judged again together (rejudge).
class IsletStep {
 public:
  IsletStep(IsletPlacer& placer, const Options& options, Result& report) : P(placer), o(options), res(report) {}
  GeomPtr run(GeomPtr W);

 private:
  bool judge(const OGRLinearRing* h, double a);
  void rejudge(const Box2& inbox);
  std::vector<const Homeless*> place_clusters(const Box2& inbox);
  bool place_cluster(const std::vector<std::size_t>& members, const Box2& inbox);
  void add_join(std::vector<Point2> h);
  std::vector<const Homeless*> join_to_land(const std::vector<const Homeless*>& still, const Box2& inbox);
  std::vector<const Homeless*> join_to_triangles(const std::vector<const Homeless*>& lost, const Box2& inbox);
  void join_clusters(const std::vector<const Homeless*>& lost, const Box2& inbox);

  IsletPlacer& P;
  const Options& o;
  Result& res;
  LandIndex land;
  std::unique_ptr<OGRMultiPolygon> grown = std::make_unique<OGRMultiPolygon>();
  std::vector<Homeless> homeless;
  std::unique_ptr<OGRMultiPolygon> joins = std::make_unique<OGRMultiPolygon>();
};

// One island (hole h of area a): kept (true), or replaced, joined or removed (false); an islet
// without room for its triangle waits for rejudge.
bool IsletStep::judge(const OGRLinearRing* h, double a) {
  OGRPolygon hp;
  hp.addRing(const_cast<OGRLinearRing*>(h));
  // An island above --min-island whose parts wider than close_width (what the closing leaves)
  // are below it is an islet too: removed as a remnant after the closing, its vertices would be
  // lost far from the mesh.
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
      if (P.place(land, land.id_of.at(h), *h, {cen.getX(), cen.getY()}, a, what, P.tris.get()))
        return false;
      if (!thin) {  // judged again below, when every islet without room is known
        homeless.push_back({land.id_of.at(h), *h, {cen.getX(), cen.getY()}, a, what, inside_point(&hp)});
        return false;
      }
    }
  }
  if (thin) return true;  // the closing and the remnant step judge it
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
}

// Islets without room next to other islets without room (ledges, clusters of rocks): each was
// judged with the others as land, so none got a triangle. They are all water unless placed, so
// they are judged again with the others left out (in input order; the triangles placed
// meanwhile count), then joined to land, to a triangle or to each other where they can be.
void IsletStep::rejudge(const Box2& inbox) {
  land.gone.assign(static_cast<std::size_t>(land.rings), 0);
  for (const Homeless& hl : homeless) land.gone[static_cast<std::size_t>(hl.ring)] = 1;
  std::vector<const Homeless*> still;
  for (const Homeless* hl : place_clusters(inbox))
    if (!P.place(land, hl->ring, hl->shape, hl->centroid, hl->area, hl->what, P.tris.get())) still.push_back(hl);
  std::vector<const Homeless*> lost = join_to_land(still, inbox);
  if (o.join_islets) lost = join_to_triangles(lost, inbox);
  join_clusters(lost, inbox);
  land.gone.clear();
}

// The islets without room nearer than islet_clearance to each other (islet_clusters), each
// cluster as one (place_cluster); returns the islets left (alone, or of a cluster that found no
// place), in input order. Nothing is clustered without islet_clearance.
std::vector<const Homeless*> IsletStep::place_clusters(const Box2& inbox) {
  std::vector<char> done(homeless.size(), 0);
  if (o.islet_clearance > 0) {
    std::vector<std::vector<Point2>> shapes;
    for (const Homeless& hl : homeless) {
      shapes.emplace_back();
      for (int k = 0; k + 1 < hl.shape.getNumPoints(); ++k) shapes.back().push_back({hl.shape.getX(k), hl.shape.getY(k)});
    }
    for (const auto& g : islet_clusters(shapes, o.islet_clearance))
      if (g.size() > 1 && place_cluster(g, inbox))
        for (const std::size_t i : g) done[i] = 1;
  }
  std::vector<const Homeless*> rest;
  for (std::size_t i = 0; i < homeless.size(); ++i)
    if (!done[i]) rest.push_back(&homeless[i]);
  return rest;
}

void IsletStep::add_join(std::vector<Point2> h) {
  OGRLinearRing jr;
  for (Point2 q : h) jr.addPoint(q.x, q.y);
  jr.closeRings();
  auto jp = std::make_unique<OGRPolygon>();
  jp->addRing(&jr);
  joins->addGeometryDirectly(jp.release());
  P.add_joined(std::move(h));
}

// A cluster of islets (indices into homeless) as one: their convex hull becomes an island when
// it is at least --min-island, else one triangle stands for them (IsletPlacer::place on the
// hull), either with the room a triangle needs; failing that the hull is joined to nearby land
// (IsletPlacer::join). Why the hull: the water between the islets, narrower than an element,
// becomes land, and the cluster's outer coast stays where it was. False: none of these fits.
bool IsletStep::place_cluster(const std::vector<std::size_t>& members, const Box2& inbox) {
  std::vector<Point2> all;
  double sum = 0;
  for (const std::size_t i : members) {
    const OGRLinearRing& r = homeless[i].shape;
    for (int k = 0; k + 1 < r.getNumPoints(); ++k) all.push_back({r.getX(k), r.getY(k)});
    sum += homeless[i].area;
  }
  std::vector<Point2> h = convex_hull(std::move(all));
  const double ha = h.size() >= 3 ? signed_area(h) : 0;
  if (!(ha > 0)) return false;
  const Homeless& first = homeless[members.front()];
  const std::string what = std::to_string(members.size()) + " islets of " + num(sum) + " m^2 in all, each nearer than " +
                           num(o.islet_clearance) + " m to the next";
  const double n = static_cast<double>(members.size());
  if (!(ha < o.min_island_area)) {
    if (ha - sum <= 1.5 * o.islet_side * o.islet_side * n && P.hull_clear(land, h, inbox, P.tri_cl, true)) {
      ++res.islets_joined;
      res.islets_joined_area += ha - sum;
      res.repairs.push_back({"islet_joined", first.inside, ha - sum,
                             what + ", too small one by one (--min-island " + num(o.min_island_area) +
                                 " m^2): kept as one island, their convex hull of " + num(ha) + " m^2; " +
                                 num(ha - sum) + " m^2 of water between them became land",
                             -1});
      add_join(std::move(h));
      return true;
    }
  } else {
    // The hull's centroid (by area), where the cluster's triangle goes first.
    Point2 c{0, 0};
    for (std::size_t i = 0; i < h.size(); ++i) {
      const Point2 a = h[i] - h[0], b = h[(i + 1) % h.size()] - h[0];
      c = c + ((a.x * b.y - a.y * b.x) / (6 * ha)) * (a + b);
    }
    c = h[0] + c;
    if (P.place(land, -1, closed_ring(h), c, sum, what + " (their convex hull: " + num(ha) + " m^2)", P.tris.get()))
      return true;
  }
  if (!o.join_islets) return false;
  double taken = 0, gap = 0;
  std::vector<Point2> j = P.join(land, -1, closed_ring(h), inbox, &taken, &gap);
  if (j.empty()) return false;
  ++res.islets_joined;
  res.islets_joined_area += taken + (ha - sum);
  res.repairs.push_back({"islet_joined", first.inside, taken + (ha - sum),
                         what + ", too small one by one (--min-island " + num(o.min_island_area) +
                             " m^2) with no room for a triangle; joined together to the land " + num(gap) + " m away: " +
                             num(taken + ha - sum) + " m^2 of water became land",
                         -1});
  add_join(std::move(j));
  return true;
}

// The islets still without room joined to land where they can be (IsletPlacer::join); returns
// the others.
std::vector<const Homeless*> IsletStep::join_to_land(const std::vector<const Homeless*>& still, const Box2& inbox) {
  std::vector<const Homeless*> lost;
  for (const Homeless* hp : still) {
    const Homeless& hl = *hp;
    double taken = 0, gap = 0;
    std::vector<Point2> h = o.join_islets ? P.join(land, hl.ring, hl.shape, inbox, &taken, &gap)
                                          : std::vector<Point2>{};
    if (!h.empty()) {
      ++res.islets_joined;
      res.islets_joined_area += taken;
      res.repairs.push_back({"islet_joined", hl.inside, taken,
                             hl.what + " is smaller than " + num(o.min_island_area) +
                                 " m^2 (--min-island) with no room for a triangle; joined to the land " +
                                 num(gap) + " m away: " + num(taken) + " m^2 of water between them became land",
                             -1});
      add_join(std::move(h));
      continue;
    }
    lost.push_back(&hl);
  }
  return lost;
}

// An islet left next to an islet's triangle (nearer than islet_side): the convex hull of the two
// replaces the triangle where it has room (as for a join). Why: the triangles placed take the
// room of the islets around them. Returns the islets left.
std::vector<const Homeless*> IsletStep::join_to_triangles(const std::vector<const Homeless*>& lost,
                                                          const Box2& inbox) {
  auto& placed = P.placed;
  auto& placed_r = P.placed_r;
  auto& placed_ring = P.placed_ring;
  auto& placed_grid = P.placed_grid;
  auto& cand = P.cand;
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
      if (t >= static_cast<std::size_t>(P.tris->getNumGeometries())) continue;
      if (dist(placed[t], hp->centroid) > placed_r[t] + ext + o.islet_side) continue;
      const OGRLinearRing* tr = P.tris->getGeometryRef(static_cast<int>(t))->getExteriorRing();
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
      std::vector<Point2> own_poly;
      std::swap(own_poly, P.placed_poly[tb]);
      if (jr_ring >= 0) land.gone[static_cast<std::size_t>(jr_ring)] = 1;
      const bool ok = ha > 0 && ha - ta - hp->area <= 1.5 * o.islet_side * o.islet_side &&
                      P.hull_clear(land, h, inbox, P.tri_cl, true);
      std::swap(own_poly, P.placed_poly[tb]);
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
        P.placed_poly[tb] = h;
        OGRLinearRing jr;
        for (Point2 q : h) jr.addPoint(q.x, q.y);
        jr.closeRings();
        OGRPolygon* tp = P.tris->getGeometryRef(static_cast<int>(tb));
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
    }
    if (!done) rest.push_back(hp);
  }
  return rest;
}

// Clusters of the islets left (single link: nearer than islet_side to each other; ledges, chains
// of rocks): the convex hull of a cluster becomes one island when it is at least --min-island
// and has room (IsletPlacer::tri_cl from other land, placed triangles and joins), else one triangle
// for the cluster where there is room; otherwise each becomes water.
void IsletStep::join_clusters(const std::vector<const Homeless*>& lost, const Box2& inbox) {
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
          P.hull_clear(land, h, inbox, P.tri_cl, true)) {
        const std::string what = std::to_string(ms.size()) + " islets of " + num(sum) + " m^2 in all, each nearer than " +
                                 num(dmax) + " m to the next";
        bool kept = false;
        if (!(ha < o.min_island_area)) {
          add_join(h);
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
          kept = P.place(land, -1, closed_ring(h), cen, sum, what + " (their convex hull: " + num(ha) + " m^2)",
                         P.tris.get());
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
}

GeomPtr IsletStep::run(GeomPtr W) {
  std::vector<std::unique_ptr<OGRPolygon>> wps;
  polygons_of(W.get(), wps);
  if (o.islet_side > 0 && o.min_island_area > 0) P.build_land(wps, land);
  const bool changed = filter_holes(wps, [&](const OGRLinearRing* h, double a) { return judge(h, a); });
  if (!homeless.empty()) {
    OGREnvelope env;
    W->getEnvelope(&env);
    rejudge(Box2{{env.MinX, env.MinY}, {env.MaxX, env.MaxY}});
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
  return W;
}

}  // namespace

GeomPtr replace_islets(GeomPtr W, IsletPlacer& placer, const Options& o, Result& res) {
  FilterLaps lap("  islets");
  W = IsletStep(placer, o, res).run(std::move(W));
  lap("islands");
  return W;
}

GeomPtr add_islet_triangles(GeomPtr W, const IsletPlacer& placer) {
  if (!placer.tris->IsEmpty()) W = minus_disjoint(std::move(W), *placer.tris, "water minus islets");
  return W;
}

GeomPtr replace_remnants(GeomPtr R, IsletPlacer& P, const Options& o, Result& res) {
  if (!(o.min_island_area > 0)) return R;
  FilterLaps lap("  remnants");
  const auto& placed = P.placed;
  std::vector<std::unique_ptr<OGRPolygon>> rps;
  polygons_of(R.get(), rps);
  auto remnant_tris = std::make_unique<OGRMultiPolygon>();
  // Room for a remnant's triangle is judged on the land as it is now (the remnant's own island
  // may have left other, larger parts).
  LandIndex now;
  if (o.islet_side > 0) P.build_land(rps, now);
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
    if (now.grid) {  // a triangle where there is room, as for the islets
      OGRPoint cen;
      if (hp.Centroid(&cen) == OGRERR_NONE &&
          P.place(now, now.id_of.at(h), *h, {cen.getX(), cen.getY()}, a, what, remnant_tris.get()))
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
  return R;
}

}  // namespace fdr::coast
