// Step: tiny edges dropped where new coast meets the input's (tiny_edges.hpp).
#include "coast/tiny_edges.hpp"

#include <algorithm>
#include <numbers>
#include <cmath>
#include <cstdio>
#include <memory>

#include "base/debug.hpp"
#include "coast/geometry_ops.hpp"
#include "coast/validity.hpp"
#include "predicates/predicates.hpp"
#include "pslg/segment_grid.hpp"

namespace fdr::coast {
namespace {

// One pass over every ring of `cleaned`: the corners that may go are dropped, never two
// neighbours. True when something was dropped.
bool tiny_pass(Rings& cleaned, const std::unordered_set<std::uint64_t>& input_vertex, double tiny) {
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
      if (!(std::atan2(std::fabs(cr), dt) > std::numbers::pi / 6)) continue;
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
    pass_changed = true;
  }
  return pass_changed;
}

}  // namespace

Rings drop_tiny_edges(Rings rings, const std::unordered_set<std::uint64_t>& input_vertex, double tiny) {
  Rings cleaned = rings;
  bool changed = false;
  for (int pass = 0; pass < 3; ++pass) {  // capped; a pass without a drop ends it
    if (!tiny_pass(cleaned, input_vertex, tiny)) break;
    changed = true;
  }
  if (changed) {
    bool ok = surely_valid(cleaned);
    if (!ok) {
      OGRPolygon q = to_ogr(cleaned);
      ok = q.IsValid();
    }
    if (ok) rings = std::move(cleaned);
    if (debug::on(debug::Aid::kFilter))
      std::fprintf(stderr, "tiny edges: polygon of %zu rings cleaned: %s\n", rings.size(), ok ? "valid" : "invalid, kept");
  }
  return rings;
}

}  // namespace fdr::coast
