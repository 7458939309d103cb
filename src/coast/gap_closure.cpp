// Step: water narrower than the minimum feature width closed or widened (gap_closure.hpp).
#include "coast/gap_closure.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "coast/convex.hpp"
#include "coast/narrow_gaps.hpp"
#include "coast/reconnect.hpp"
#include "coast/report.hpp"

namespace fdr::coast {
namespace {

// p inside the polygon of `rings` (even-odd over all its rings).
bool holds(const Rings& rings, Point2 p) {
  bool in = false;
  for (const auto& r : rings) in ^= inside_ring(p, r);
  return in;
}

Box2 rings_box(const Rings& rings) {
  Box2 b;
  for (const auto& r : rings)
    for (const Point2& p : r) b.add(p);
  return b;
}

// The signed area of ring r clipped to the convex polygon h (counter-clockwise), by
// Sutherland-Hodgman: its output may hold zero-width bridges, which add no area.
double clipped_area(const std::vector<Point2>& r, const std::vector<Point2>& h) {
  std::vector<Point2> cur = r, next;
  for (std::size_t i = 0, n = h.size(); i < n && !cur.empty(); ++i) {
    const Point2 a = h[i], b = h[(i + 1) % n];
    auto side = [&](Point2 p) { return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x); };
    next.clear();
    for (std::size_t k = 0, m = cur.size(); k < m; ++k) {
      const Point2 p = cur[k], q = cur[(k + 1) % m];
      const double sp = side(p), sq = side(q);
      if (sp >= 0) next.push_back(p);
      if ((sp >= 0) != (sq >= 0)) next.push_back(p + (sp / (sp - sq)) * (q - p));
    }
    std::swap(cur, next);
  }
  return cur.size() >= 3 ? signed_area(cur) : 0.0;
}

// The water of `rings` inside the convex polygon h (m^2).
double water_in(const Rings& rings, const std::vector<Point2>& h) {
  const Box2 hb = box_of(h);
  double a = 0;
  for (const auto& r : rings) {
    const Box2 rb = box_of(r);
    if (rb.hi.x < hb.lo.x || rb.lo.x > hb.hi.x || rb.hi.y < hb.lo.y || rb.lo.y > hb.hi.y) continue;
    a += clipped_area(r, h);
  }
  return std::max(0.0, a);
}

struct Bridge {
  NarrowGap gap;
  std::vector<Point2> hull;
  bool widen = false;    // closing it would cut off a large water body: not closed
  bool widened = false;  // ... and widened (else kept as it is)
};

Rings rings_of(const OGRPolygon& p) {
  Rings rings;
  rings.push_back(ring_points(p.getExteriorRing(), true));
  for (int k = 0; k < p.getNumInteriorRings(); ++k) rings.push_back(ring_points(p.getInteriorRing(k), false));
  return rings;
}

// One polygon with its bridges: the widened ones added to the water, the others taken out; a
// bridge whose closing cuts off a piece of at least gap_body_area is widened instead. Returns
// the polygon's new pieces (the largest first), none when nothing changed; repairs and figures
// into res.
std::vector<Rings> close_in_polygon(const Rings& rings, std::vector<Bridge>& bridges, const Options& o,
                                    const OGREnvelope& inbox, const std::vector<const OGRPolygon*>& others,
                                    Result& res) {
  const OGRPolygon P = to_ogr(rings);
  OwnedPolygons pieces;
  std::size_t largest = 0;
  GeomPtr water;
  for (int pass = 0;; ++pass) {
    water.reset(P.clone());
    for (Bridge& b : bridges) {
      b.widened = false;
      if (!b.widen) continue;
      const OGRPolygon hp = to_ogr({b.hull});
      GeomPtr conn = checked(hp.Intersection(&P), "water under a narrow gap's bridge");
      GeomPtr g = conn->IsEmpty() ? nullptr : widened_connection(*conn, o.connect_width, inbox, others);
      if (!g) continue;
      water = checked(water->Union(g.get()), "a narrow gap widened");
      b.widened = true;
    }
    auto cut = std::make_unique<OGRMultiPolygon>();
    for (const Bridge& b : bridges)
      if (!b.widen) {
        OGRPolygon hp = to_ogr({b.hull});
        cut->addGeometry(&hp);
      }
    GeomPtr u = cut->IsEmpty() ? nullptr : checked(cut->UnionCascaded(), "narrow gaps' bridges");
    GeomPtr d = u ? minus_touching(GeomPtr(water->clone()), *u, "narrow gaps closed") : GeomPtr(water->clone());
    pieces.clear();
    polygons_of(d.get(), pieces);
    largest = 0;
    for (std::size_t k = 1; k < pieces.size(); ++k)
      if (pieces[k]->get_Area() > pieces[largest]->get_Area()) largest = k;
    // A large piece cut off: the bridges that touch it are widened instead (at most twice over).
    bool changed = false;
    if (pass == 2) break;
    for (std::size_t k = 0; k < pieces.size(); ++k) {
      if (k == largest || !(pieces[k]->get_Area() >= o.gap_body_area)) continue;
      const Prepared piece(pieces[k].get());  // tested against every bridge
      for (Bridge& b : bridges) {
        if (b.widen) continue;
        const OGRPolygon hp = to_ogr({b.hull});
        if (piece.intersects(&hp)) b.widen = changed = true;
      }
    }
    if (!changed) break;
  }
  // Nothing closed or widened: the polygon stays as given (GEOS would renumber its rings).
  if (std::all_of(bridges.begin(), bridges.end(), [](const Bridge& b) { return b.widen && !b.widened; })) return {};
  for (const Bridge& b : bridges) {
    const double w = b.gap.width;
    if (b.widen) {
      if (!b.widened) continue;  // listed as a narrow gap kept
      ++res.reconnected;
      res.repairs.push_back({"narrow_gap_widened", b.gap.where, w,
                             "water " + num(w) + " m wide, narrower than " + num(o.min_feature) +
                                 " m, joins a water body closing it would cut off; widened to " + num(o.connect_width) + " m",
                             -1});
      continue;
    }
    const double area = water_in(rings, b.hull);
    ++res.closed;
    res.closed_area += area;
    res.repairs.push_back({"narrow_gap_closed", b.gap.where, area,
                           "water " + num(w) + " m wide is narrower than " + num(o.min_feature) +
                               " m (--min-feature): the land on both sides joined across it, " + num(area) +
                               " m^2 of water removed",
                           -1});
  }
  std::vector<Rings> out;
  out.push_back(rings_of(*pieces[largest]));
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    if (k == largest) continue;
    const double a = pieces[k]->get_Area();
    if (a >= o.gap_body_area) {
      out.push_back(rings_of(*pieces[k]));
      continue;
    }
    ++res.cut_off;
    res.cut_off_area += a;
    res.repairs.push_back({"cut_off_water_removed", inside_point(pieces[k].get()), a,
                           "water body of " + num(a) + " m^2 cut off where a narrow gap was closed; removed", -1});
  }
  return out;
}

}  // namespace

std::vector<Point2> gap_bridge(const Rings& rings, Point2 c, double r, double snap) {
  std::vector<Point2> pts;
  const double r2 = r * r;
  for (const auto& ring : rings)
    for (std::size_t i = 0, n = ring.size(); i < n; ++i) {
      const Point2 a = ring[i], b = ring[(i + 1) % n];
      const bool ain = norm2(a - c) <= r2;
      if (ain) pts.push_back(a);
      // Where ab crosses the circle: |a + t (b - a) - c| = r, t in [0, 1].
      const Point2 d = b - a, f = a - c;
      const double A = norm2(d), B = 2 * dot(f, d), C = norm2(f) - r2;
      const double disc = B * B - 4 * A * C;
      if (!(A > 0) || disc < 0) continue;
      const double s = std::sqrt(disc);
      const double len = std::sqrt(A);
      for (const double t : {(-B - s) / (2 * A), (-B + s) / (2 * A)}) {
        if (!(t > 0 && t < 1)) continue;
        if (t * len < snap) pts.push_back(a);
        else if ((1 - t) * len < snap) pts.push_back(b);
        else pts.push_back(a + t * d);
      }
    }
  std::vector<Point2> h = convex_hull(std::move(pts));
  if (h.size() < 3 || !(std::fabs(signed_area(h)) > 0)) h.clear();
  return h;
}

void close_narrow_gaps(const Options& o, const OGREnvelope& inbox, Result& res) {
  if (!(o.close_width > 0) || !(o.min_feature > 0) || !(o.gap_body_area > 0)) return;
  FilterLaps lap("  narrow gaps closed");
  for (int round = 0; round < 3; ++round) {
    const std::vector<NarrowGap> gaps = narrow_gaps(res.polygons, o.min_feature, nullptr);
    lap("found");
    if (gaps.empty()) break;
    // Each gap to the polygon whose water holds its middle.
    std::vector<Box2> boxes;
    for (const Rings& p : res.polygons) boxes.push_back(rings_box(p));
    std::map<std::size_t, std::vector<Bridge>> by_poly;
    for (const NarrowGap& g : gaps)
      for (std::size_t k = 0; k < res.polygons.size(); ++k) {
        const Box2& b = boxes[k];
        if (g.where.x < b.lo.x || g.where.x > b.hi.x || g.where.y < b.lo.y || g.where.y > b.hi.y ||
            !holds(res.polygons[k], g.where))
          continue;
        std::vector<Point2> h = gap_bridge(res.polygons[k], g.where, o.min_feature, o.close_width / 4);
        if (!h.empty()) by_poly[k].push_back({g, std::move(h)});
        break;
      }
    if (lap.on()) {  // developer aid: what each round finds
      std::size_t bridged = 0;
      for (const auto& [k, bs] : by_poly) bridged += bs.size();
      std::fprintf(stderr, "narrow gaps closed: round %d, %zu gaps below %g, %zu bridged\n", round, gaps.size(),
                   o.min_feature, bridged);
    }
    if (by_poly.empty()) break;
    std::vector<OGRPolygon> ogr(res.polygons.size());
    std::vector<char> made(res.polygons.size(), 0);
    std::map<std::size_t, std::vector<Rings>> replaced;
    bool any_closed = false;
    for (auto& [k, bridges] : by_poly) {
      std::vector<const OGRPolygon*> others;
      for (std::size_t j = 0; j < res.polygons.size(); ++j) {
        if (j == k || apart(boxes[j], boxes[k], o.connect_width)) continue;
        if (!made[j]) ogr[j] = to_ogr(res.polygons[j]), made[j] = 1;
        others.push_back(&ogr[j]);
      }
      std::vector<Rings> pieces = close_in_polygon(res.polygons[k], bridges, o, inbox, others, res);
      if (!pieces.empty()) replaced[k] = std::move(pieces);
      lap("bridged");
      for (const Bridge& b : bridges) any_closed = any_closed || !b.widen;
    }
    Polygons next;
    for (std::size_t k = 0; k < res.polygons.size(); ++k) {
      auto it = replaced.find(k);
      if (it == replaced.end()) {
        next.push_back(std::move(res.polygons[k]));
        continue;
      }
      for (const auto& r : res.polygons[k]) res.output_area -= signed_area(r);
      for (Rings& piece : it->second) {
        for (const auto& r : piece) res.output_area += signed_area(r);
        next.push_back(std::move(piece));
      }
    }
    res.polygons = std::move(next);
    if (!any_closed) break;  // what is left is widened or kept: another round finds the same
  }
  lap("closed");
}

}  // namespace fdr::coast
