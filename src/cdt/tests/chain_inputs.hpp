// Generators of degenerate PSLGs that defeat a naive insertion order or a naive resolution:
// long collinear chains, concentric rings of cocircular points and (test_inputs.hpp
// lattice_square) lattices, plus random points of a given count for comparison. The cdt tests
// and tools/bench/fdr use them.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <utility>
#include <vector>
#include "cdt/tests/test_inputs.hpp"
#include "pslg/pslg.hpp"

namespace fdr::testing {

// The square [0, side]^2 whose four sides carry k vertices each (corners included once), as one
// closed chain of 4k boundary segments (marker 1): what resampling a box edge to a fine spacing
// gives. Every side's vertices are exactly collinear (one coordinate is 0 or side); the other
// coordinate is side * i / k rounded.
inline pslg::Pslg collinear_square(int k, double side = 1000) {
  pslg::Pslg p;
  for (int s = 0; s < 4; ++s)
    for (int i = 0; i < k; ++i) {
      const double t = side * i / k;
      const Point2 q[4] = {{t, 0}, {side, t}, {side - t, side}, {0, side - t}};
      p.points.push_back(q[s]);
    }
  const auto n = static_cast<Index>(p.points.size());
  for (Index i = 0; i < n; ++i) p.segments.push_back({i, (i + 1) % n, 1, 0});
  return p;
}

// The integer points on the circle x^2 + y^2 = R^2 with R = 5*13*17*29*37 (972 of them, every
// prime factor 1 mod 4), in counter-clockwise order: exactly cocircular points with exact
// coordinates.
inline std::vector<std::pair<std::int64_t, std::int64_t>> integer_circle_points() {
  constexpr std::int64_t R = 5 * 13 * 17 * 29 * 37;
  std::vector<std::pair<std::int64_t, std::int64_t>> q;  // first quadrant, x > 0, y >= 0
  for (std::int64_t x = 1; x <= R; ++x) {
    const std::int64_t r = R * R - x * x;
    auto y = static_cast<std::int64_t>(std::llround(std::sqrt(static_cast<double>(r))));
    while (y * y > r) --y;
    while ((y + 1) * (y + 1) <= r) ++y;
    if (y * y == r) q.push_back({x, y});
  }
  std::sort(q.begin(), q.end(), [](auto a, auto b) { return a.first > b.first; });  // angle 0 .. 90 degrees
  std::vector<std::pair<std::int64_t, std::int64_t>> all;
  for (int quarter = 0; quarter < 4; ++quarter)
    for (const auto& e : q) {  // rotated by quarter * 90 degrees
      std::int64_t x = e.first, y = e.second;
      for (int r = 0; r < quarter; ++r) {
        const std::int64_t t = x;
        x = -y;
        y = t;
      }
      all.push_back({x, y});
    }
  return all;
}

// `rings` concentric rings of `per_ring` points (at most 972) exactly on circles of radii
// j * R (j = 1..rings), every point of ring j being j times a point of the first ring (so the
// points are also exactly collinear along rays from the centre). The outer ring is the boundary
// (marker 1); every other inner ring is a closed breakline (marker pslg::kBreaklineMarker).
// The centre point is included.
inline pslg::Pslg concentric_rings(int rings, int per_ring) {
  const auto base = integer_circle_points();
  const std::size_t step = std::max<std::size_t>(1, base.size() / static_cast<std::size_t>(per_ring));
  std::vector<std::pair<std::int64_t, std::int64_t>> pick;
  for (std::size_t i = 0; i < base.size() && pick.size() < static_cast<std::size_t>(per_ring); i += step)
    pick.push_back(base[i]);
  pslg::Pslg p;
  p.points.push_back({0, 0});
  for (int j = 1; j <= rings; ++j) {
    const auto first = static_cast<Index>(p.points.size());
    for (auto [x, y] : pick) p.points.push_back({double(j * x), double(j * y)});
    const auto m = static_cast<Index>(pick.size());
    const bool outer = j == rings, breakline = j % 2 == 0;
    if (!outer && !breakline) continue;
    for (Index i = 0; i < m; ++i)
      p.segments.push_back({first + i, first + (i + 1) % m, outer ? 1 : pslg::kBreaklineMarker, 0});
  }
  return p;
}

// The square [0, side]^2 (4 corners, marker 1) crossed by `chains` horizontal breaklines at
// exact heights side * (c + 1) / (chains + 1) rounded, each a chain of `per_chain` collinear
// vertices from x = side / 8 to 7 side / 8 with a segment between consecutive ones, plus one
// diagonal chain on y = x between 0.88 side and 0.99 side of `per_chain` vertices (exactly
// collinear): long collinear interior constraints.
inline pslg::Pslg breaklines(int chains, int per_chain, double side = 1000) {
  pslg::Pslg p;
  p.points = {{0, 0}, {side, 0}, {side, side}, {0, side}};
  for (Index i = 0; i < 4; ++i) p.segments.push_back({i, (i + 1) % 4, 1, 0});
  auto chain = [&](auto point_at) {
    const auto first = static_cast<Index>(p.points.size());
    for (int i = 0; i < per_chain; ++i) p.points.push_back(point_at(i));
    for (int i = 0; i + 1 < per_chain; ++i)
      p.segments.push_back({first + static_cast<Index>(i), first + static_cast<Index>(i + 1), pslg::kBreaklineMarker, 0});
  };
  const double x0 = side / 8, len = 0.75 * side;
  for (int c = 0; c < chains; ++c) {
    const double y = side * (c + 1) / (chains + 1) + side / (4.0 * (chains + 1));
    chain([&](int i) { return Point2{x0 + len * i / (per_chain - 1), y}; });
  }
  // The diagonal stays right of the horizontal chains (x > 7 side / 8): no crossing.
  chain([&](int i) {
    const double t = 0.88 * side + 0.11 * side * i / (per_chain - 1);
    return Point2{t, t};
  });
  return p;
}

// n random points in the square [0, side]^2 plus its 4 corners and sides (marker 1): the
// reference for an input of the same size.
inline pslg::Pslg random_points(int n, double side = 1000, unsigned seed = 7) {
  std::mt19937_64 rng(seed);
  pslg::Pslg p;
  p.points = {{0, 0}, {side, 0}, {side, side}, {0, side}};
  for (Index i = 0; i < 4; ++i) p.segments.push_back({i, (i + 1) % 4, 1, 0});
  while (static_cast<int>(p.points.size()) < n) {
    // 53 random bits per coordinate, strictly inside the square.
    const double x = side * (static_cast<double>(rng() >> 11) + 0.5) / 9007199254740992.0;
    const double y = side * (static_cast<double>(rng() >> 11) + 0.5) / 9007199254740992.0;
    p.points.push_back({x, y});
  }
  return p;
}

}  // namespace fdr::testing
