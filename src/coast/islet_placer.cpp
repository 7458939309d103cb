// Islet placement (islet_placer.hpp).
#include "coast/islet_placer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "coast/report.hpp"

namespace fdr::coast {

IsletPlacer::IsletPlacer(const Options& options, Result& report)
    : o(options), res(report), tri_r(options.islet_side / std::sqrt(3.0)),
      tri_cl(options.islet_clearance > 0 ? options.islet_clearance : 0.5 * options.islet_side),
      shift_cl(options.islet_clearance > 0 ? options.islet_clearance : 0.55 * options.islet_side),
      join_cl(options.islet_clearance > 0 ? options.islet_clearance : 0.25 * options.islet_side),
      placed_grid(2 * options.islet_side), joined_grid(2 * options.islet_side), tris(std::make_unique<OGRMultiPolygon>()) {}

std::size_t IsletPlacer::add_placed(std::vector<Point2> poly, int ring) {
  Point2 c{0, 0};
  for (Point2 q : poly) c = c + q;
  c = (1.0 / static_cast<double>(poly.size())) * c;
  double r = 0;
  for (Point2 q : poly) r = std::max(r, dist(q, c));
  const std::size_t k = placed.size();
  placed_grid.add(static_cast<std::uint32_t>(k), c, r);
  placed.push_back(c);
  placed_r.push_back(r);
  placed_ring.push_back(ring);
  placed_poly.push_back(std::move(poly));
  return k;
}

void IsletPlacer::add_joined(std::vector<Point2> hull) {
  const Box2 b = box_of(hull);
  joined_grid.add(static_cast<std::uint32_t>(joined.size()), 0.5 * (b.lo + b.hi), 0.5 * dist(b.lo, b.hi));
  joined_box.push_back(b);
  joined.push_back(std::move(hull));
}

void IsletPlacer::build_land(const std::vector<std::unique_ptr<OGRPolygon>>& ps, LandIndex& L) const {
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
}

bool IsletPlacer::has_room(const LandIndex& L, int own, Point2 c, double cl, double r) {
  if (r == 0) r = tri_r;
  const double lim = r + cl;
  placed_grid.near({{c.x - lim, c.y - lim}, {c.x + lim, c.y + lim}}, &cand);
  auto near_convex = [&](const std::vector<Point2>& g) {  // g within lim of c
    if (inside_convex(c, g)) return true;
    for (std::size_t i = 0; i < g.size(); ++i)
      if (dist_to_segment(c, g[i], g[(i + 1) % g.size()]) < lim) return true;
    return false;
  };
  for (const std::uint32_t k : cand)
    if (!placed_poly[k].empty() && dist(placed[k], c) < lim + placed_r[k] && near_convex(placed_poly[k])) return false;
  Box2 qb;
  qb.add({c.x - lim, c.y - lim});
  qb.add({c.x + lim, c.y + lim});
  joined_grid.near(qb, &cand);
  for (const std::uint32_t k : cand)
    if (!beyond(c, lim, joined_box[k]) && near_convex(joined[k])) return false;
  L.grid->segments_near(qb, &near);
  for (Index k : near)
    if (L.ring[k] != own && (L.gone.empty() || !L.gone[L.ring[k]]) &&
        dist_to_segment(c, L.seg[k].first, L.seg[k].second) < lim)
      return false;
  return true;
}

bool IsletPlacer::land_clear(const LandIndex& L, int own, const std::vector<Point2>& poly, double cl) {
  const Box2 hb = box_of(poly);
  const Box2 qb{{hb.lo.x - cl, hb.lo.y - cl}, {hb.hi.x + cl, hb.hi.y + cl}};
  if (L.grid) {
    L.grid->segments_near(qb, &near);
    for (Index j : near) {
      const int r = L.ring[j];
      if (r == own || (!L.gone.empty() && L.gone[static_cast<std::size_t>(r)])) continue;
      if (convex_distance(L.seg[j].first, L.seg[j].second, poly) < cl) return false;
    }
  }
  placed_grid.near(qb, &cand);
  for (const std::size_t t : cand) {
    if (placed_poly[t].empty() || beyond(placed[t], placed_r[t] + cl, hb)) continue;
    if (convex_gap(placed_poly[t], poly) < cl) return false;
  }
  joined_grid.near(qb, &cand);
  for (const std::uint32_t k : cand) {
    if (apart(joined_box[k], hb, cl)) continue;
    if (convex_gap(joined[k], poly) < cl) return false;
  }
  return true;
}

namespace {

// Corner k (clockwise) of the equilateral triangle of circumradius r around c whose corner 0
// points at angle t0.
Point2 corner(Point2 c, double r, double t0, int k) {
  const double t = t0 - 2.0943951023931957 * k;
  return Point2{c.x + r * std::cos(t), c.y + r * std::sin(t)};
}
std::vector<Point2> triangle(Point2 c, double r, double t0) {  // counter-clockwise
  return {corner(c, r, t0, 0), corner(c, r, t0, 2), corner(c, r, t0, 1)};
}

// The 40 turns 3 degrees apart (from apex up) of a triangle of circumradius r around c, ordered
// by how far the islet's farthest vertex lies from the triangle's sides (the first of equals
// first). Why: with the apex always up, the ends of an islet longer than the triangle stuck out
// by up to 0.6 islet_side, which the model sees as coast moved by that much.
std::vector<double> turns_by_fit(const OGRLinearRing& shape, Point2 c, double r) {
  const int ns = shape.getNumPoints();  // with the closing repeat
  std::vector<std::pair<double, int>> fit;
  for (int k = 0; k < 40; ++k) {
    const double t0 = 1.5707963267948966 + k * (2.0943951023931957 / 40);
    const Point2 p0 = corner(c, r, t0, 0), p1 = corner(c, r, t0, 1), p2 = corner(c, r, t0, 2);
    double worst = 0;
    for (int i = 0; i + 1 < ns; ++i) {
      const Point2 v{shape.getX(i), shape.getY(i)};
      worst = std::max(worst, std::min({dist_to_segment(v, p0, p1), dist_to_segment(v, p1, p2),
                                        dist_to_segment(v, p2, p0)}));
    }
    fit.push_back({worst, k});
  }
  std::sort(fit.begin(), fit.end());
  std::vector<double> out;
  for (const auto& [w, k] : fit) out.push_back(1.5707963267948966 + k * (2.0943951023931957 / 40));
  return out;
}

// The ring's coast beyond a join's run end e (on segment s of the ring's segments f0 .. f1,
// going forward or backward from e) keeps away from the hull h: a point at arc length a from e
// lies at least min(cl, a sin 60 deg) from it. Why: the water between the hull and that coast
// then opens at 60 degrees or more from e and is cl wide beyond cl / sin 60 deg, where a coast
// that turned back along the hull (a bay's side) would leave a notch narrower than an element.
// The segments passed are marked 2 in mark (1: the run's; the tests after it read both as
// "checked").
bool ends_clear(const LandIndex& L, std::size_t f0, std::size_t f1, std::size_t s, Point2 e, bool forward,
                const std::vector<Point2>& h, double cl, std::vector<char>& mark) {
  constexpr double kSin60 = 0.8660254037844386;
  const double reach = cl / kSin60;
  double acc = 0;
  Point2 at = e;
  std::size_t k = s;
  for (std::size_t steps = 0; steps <= f1 - f0; ++steps) {
    const Point2 v = forward ? L.seg[k].second : L.seg[k].first;
    const double l = dist(at, v);
    if (acc + l >= reach) {
      const Point2 p = l > 0 ? at + ((reach - acc) / l) * (v - at) : at;
      return convex_distance(p, v, h) >= cl;
    }
    acc += l;
    if (convex_distance(v, v, h) < kSin60 * acc) return false;
    at = v;
    k = forward ? (k + 1 == f1 ? f0 : k + 1) : (k == f0 ? f1 - 1 : k - 1);
    if (mark[k - f0] == 1) return true;  // round the ring to the run
    mark[k - f0] = 2;
  }
  return true;
}

}  // namespace

bool IsletPlacer::place(const LandIndex& L, int own, const OGRLinearRing& shape, Point2 cen, double a,
                        const std::string& what, OGRMultiPolygon* into) {
  const int ns = shape.getNumPoints();  // with the closing repeat
  // A long islet gets a larger triangle where there is room around its centroid (side up to
  // 1.6 islet_side: the best turn of a triangle of side s leaves the ends of an islet of length
  // len about len / 2 - 0.39 s out; sized for 0.57 islet_side, 0.4 hmin), so that fewer
  // vertices of long islets lie far from the mesh's coast.
  double r = tri_r;
  if (ns <= 64) {
    double len = 0;
    for (int i = 0; i + 1 < ns; ++i)
      for (int j = i + 1; j + 1 < ns; ++j)
        len = std::max(len, dist({shape.getX(i), shape.getY(i)}, {shape.getX(j), shape.getY(j)}));
    const double side = std::min(1.6 * o.islet_side, (0.5 * len - 0.57 * o.islet_side) / 0.39);
    if (side > o.islet_side && has_room(L, own, cen, tri_cl, side / std::sqrt(3.0))) r = side / std::sqrt(3.0);
  }
  // The places tried in order: the centroid, then 8 directions at a third, two thirds and all of
  // islet_shift. At each, room for every turn (the circumcircle clear) takes the best fitting
  // turn; else the best fitting of the turns that keep clear, when the inscribed circle is.
  std::vector<Point2> at{cen};
  for (int step = 1; step <= 3 && o.islet_shift > 0; ++step)
    for (int d = 0; d < 8; ++d) {
      const double t = o.islet_shift * step / 3.0, ang = 0.7853981633974483 * d;
      at.push_back({cen.x + t * std::cos(ang), cen.y + t * std::sin(ang)});
    }
  std::vector<Point2> tri;
  Point2 c = cen;
  for (std::size_t i = 0; i < at.size() && tri.empty(); ++i) {
    const double cl = i == 0 ? tri_cl : shift_cl;
    if ((i == 0 && r > tri_r) || has_room(L, own, at[i], cl, r)) {
      tri = triangle(at[i], r, turns_by_fit(shape, at[i], r).front());
    } else if (o.islet_clearance > 0 && has_room(L, own, at[i], cl, 0.5 * r)) {
      for (const double turn : turns_by_fit(shape, at[i], r)) {
        std::vector<Point2> t = triangle(at[i], r, turn);
        if (land_clear(L, own, t, cl)) {
          tri = std::move(t);
          break;
        }
      }
    }
    if (!tri.empty()) c = at[i];
  }
  if (tri.empty()) return false;
  OGRLinearRing tr;
  for (const Point2 q : tri) tr.addPoint(q.x, q.y);
  tr.closeRings();
  auto tp = std::make_unique<OGRPolygon>();
  tp->addRing(&tr);
  const double ta = tp->get_Area();
  const double moved = dist(c, cen);
  add_placed(std::move(tri), own);
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
}

bool IsletPlacer::hull_clear(const LandIndex& L, const std::vector<Point2>& h, const Box2& inbox, double cl,
                             bool rings) {
  const Box2 hb = box_of(h);
  if (hb.lo.x < inbox.lo.x + cl || hb.lo.y < inbox.lo.y + cl || hb.hi.x > inbox.hi.x - cl || hb.hi.y > inbox.hi.y - cl)
    return false;
  if (rings) return land_clear(L, -1, h, cl);
  static const LandIndex none;
  return land_clear(none, -1, h, cl);
}

std::vector<Point2> IsletPlacer::join(const LandIndex& L, int own, const OGRLinearRing& shape, const Box2& inbox,
                                      double* taken, double* gap) {
  std::vector<Point2> isl;
  for (int i = 0; i + 1 < shape.getNumPoints(); ++i) isl.push_back({shape.getX(i), shape.getY(i)});
  const std::size_t ni = isl.size();
  if (ni < 3 || !L.grid) return std::vector<Point2>{};
  Box2 ib;
  for (Point2 q : isl) ib.add(q);
  const double dmax = o.islet_side;
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
  double len = 0;
  for (std::size_t i = 0; i < ni; ++i)
    for (std::size_t j = i + 1; j < ni; ++j) len = std::max(len, dist(isl[i], isl[j]));
  // Where the ring's own coast beyond the run comes back near the hull (a bay's side, the far
  // bank of a cove), a longer run takes that corner of water in as well.
  const double rho = 0.5 * len + best + 0.1 * o.islet_side;
  const int tries = o.islet_clearance > 0 ? 3 : 1;
  for (int k = 1; k <= tries; ++k) {
    std::vector<Point2> h = join_along(L, own, isl, kb, pb, k * rho, inbox, taken);
    if (!h.empty()) {
      *gap = best;
      return h;
    }
  }
  return std::vector<Point2>{};
}

std::vector<Point2> IsletPlacer::join_along(const LandIndex& L, int own, const std::vector<Point2>& isl, Index kb,
                                            Point2 pb, double rho, const Box2& inbox, double* taken) {
  const double cl = join_cl;
  const int ra = L.ring[kb];
  const std::size_t f0 = L.first[static_cast<std::size_t>(ra)], f1 = L.first[static_cast<std::size_t>(ra) + 1];
  const std::size_t nseg = f1 - f0;
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
  // With a clearance, the ring's own coast beyond the run keeps it too (ends_clear near the
  // ends, all of cl farther along).
  if (o.islet_clearance > 0) {
    if (!ends_clear(L, f0, f1, s0, e0, false, h, cl, in_run) || !ends_clear(L, f0, f1, s1, e1, true, h, cl, in_run))
      return std::vector<Point2>{};
    for (Index j : near)
      if (L.ring[j] == ra && !in_run[j - f0] && convex_distance(L.seg[j].first, L.seg[j].second, h) < cl)
        return std::vector<Point2>{};
  }
  if (!hull_clear(L, h, inbox, cl, false)) return std::vector<Point2>{};
  *taken = std::max(0.0, taken_area);
  return h;
}

}  // namespace fdr::coast
