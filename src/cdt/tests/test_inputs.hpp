// Shared generators of test PSLGs (random, lattice, wedges) for cdt and refine tests.
#pragma once
#include <cmath>
#include <numbers>
#include <functional>
#include <random>
#include <string>
#include <vector>
#include "pslg/pslg.hpp"
#include "predicates/predicates.hpp"

namespace fdr::testing {

inline bool segments_cross_or_touch(Point2 a, Point2 b, Point2 c, Point2 d) {
  using predicates::orient2d;
  const int o1 = orient2d(a, b, c), o2 = orient2d(a, b, d), o3 = orient2d(c, d, a), o4 = orient2d(c, d, b);
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  auto on = [](Point2 p, Point2 q, Point2 r) {  // r on closed segment pq (collinear assumed)
    return std::min(p.x, q.x) <= r.x && r.x <= std::max(p.x, q.x) && std::min(p.y, q.y) <= r.y && r.y <= std::max(p.y, q.y);
  };
  if (o1 == 0 && on(a, b, c)) return true;
  if (o2 == 0 && on(a, b, d)) return true;
  if (o3 == 0 && on(c, d, a)) return true;
  if (o4 == 0 && on(c, d, b)) return true;
  return false;
}

// Box [0,w]x[0,h] boundary (4 segments, marker 1) plus n random interior points and up to m
// random non-crossing interior segments between them.
inline pslg::Pslg random_pslg(unsigned seed, int n, int m, double w = 10, double h = 10) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> ux(0.0, w), uy(0.0, h);
  pslg::Pslg p;
  p.points = {{0, 0}, {w, 0}, {w, h}, {0, h}};
  for (Index i = 0; i < 4; ++i) p.segments.push_back({i, (i + 1) % 4, 1, 0});
  for (int i = 0; i < n; ++i) {
    Point2 q{ux(rng), uy(rng)};
    if (q.x <= 0 || q.y <= 0 || q.x >= w || q.y >= h) continue;
    p.points.push_back(q);
  }
  std::uniform_int_distribution<std::size_t> ui(4, p.points.size() - 1);
  for (int tries = 0; tries < 20 * m && static_cast<int>(p.segments.size()) < m + 4; ++tries) {
    const Index a = static_cast<Index>(ui(rng)), b = static_cast<Index>(ui(rng));
    if (a == b) continue;
    bool bad = false;
    for (const auto& s : p.segments) {
      if (s.a == a || s.a == b || s.b == a || s.b == b) {
        // sharing an endpoint: reject only if collinear overlap
        const Index o = (s.a == a || s.a == b) ? s.b : s.a;
        const Index sh = (s.a == a || s.a == b) ? s.a : s.b;
        const Index other = sh == a ? b : a;
        if (predicates::orient2d(p.points[sh], p.points[other], p.points[o]) == 0) { bad = true; break; }
        continue;
      }
      if (segments_cross_or_touch(p.points[a], p.points[b], p.points[s.a], p.points[s.b])) { bad = true; break; }
    }
    // no other vertex on the segment
    for (Index v = 0; v < p.points.size() && !bad; ++v) {
      if (v == a || v == b) continue;
      if (predicates::orient2d(p.points[a], p.points[b], p.points[v]) == 0 &&
          predicates::diametral(p.points[a], p.points[b], p.points[v]) > 0) bad = true;
    }
    if (!bad) p.segments.push_back({a, b, 4, 1});
  }
  return p;
}

// The (n+1)^2 integer lattice on [0,n]^2 with its boundary as 4n unit segments (marker 1).
inline pslg::Pslg lattice_square(int n) {
  pslg::Pslg p;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) p.points.push_back({double(i), double(j)});
  auto id = [n](int i, int j) { return static_cast<Index>(j * (n + 1) + i); };
  for (int i = 0; i < n; ++i) {
    p.segments.push_back({id(i, 0), id(i + 1, 0), 1, 0});
    p.segments.push_back({id(n, i), id(n, i + 1), 1, 0});
    p.segments.push_back({id(i + 1, n), id(i, n), 1, 0});
    p.segments.push_back({id(0, i + 1), id(0, i), 1, 0});
  }
  return p;
}

// Two segments from the origin at `deg` degrees inside a box, closed by an arc-free polygon:
// a wedge-shaped domain with a small input angle at (0,0).
inline pslg::Pslg wedge(double deg, double len = 10) {
  const double t = deg * std::numbers::pi / 180.0;
  pslg::Pslg p;
  p.points = {{0, 0}, {len, 0}, {len * std::cos(t), len * std::sin(t)}};
  p.segments = {{0, 1, 1, 0}, {1, 2, 1, 0}, {2, 0, 1, 0}};
  return p;
}

}  // namespace fdr::testing
