// Brute-force distance from a point to the nearest of a set of segments, with the same
// arithmetic as sizing::distance_to_shore (so that tests may compare bit for bit).
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>
#include "base/types.hpp"

namespace fdr::sizing::testing {

inline double brute_dist(Point2 p, const std::vector<std::pair<Point2, Point2>>& segs) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& [a, b] : segs) {
    const Point2 d = b - a, w = p - a;
    const double dd = dot(d, d), inv = dd > 0 ? 1.0 / dd : 0.0;  // distance_to_shore's arithmetic
    const double t = std::clamp(dot(w, d) * inv, 0.0, 1.0);
    best = std::min(best, norm2(p - (a + t * d)));
  }
  return std::sqrt(best);
}

}  // namespace fdr::sizing::testing
