// Steps of contained_difference that are tested on their own (src/pslg/tests).
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>
#include "base/types.hpp"

namespace fdr::pslg::cd_steps {

// A ring of a or b, oriented (once oriented) with the result's interior on its left.
struct Ring {
  std::vector<Point2> p;
  bool from_a;
  int want;  // orientation with the result's interior on the left: +1 ccw, -1 cw
};

// A directed segment u -> v of a ring: u = rings[ring].p[at].
struct Edge {
  Point2 u, v;
  std::uint32_t ring, at;
};

// The segments of the rings less those the two sets share: a's u -> v cancels b's v -> u.
// Returns why it cannot go on (a segment twice in one set, in the same direction in both, in
// more than two rings), else null; `cancelled` counts the cancelled pairs.
const char* cancel_shared(const std::vector<Ring>& rings, std::vector<Edge>& rest, std::size_t& cancelled);

// A closed walk over rest (segment indices, each starting where the previous ends) split into
// simple loops where it passes a vertex twice; a walk through distinct vertices stays whole.
std::vector<std::vector<std::uint32_t>> split_closed_walk(const std::vector<std::uint32_t>& walk,
                                                          const std::vector<Edge>& rest);

// True if w comes before z turning clockwise around v from the ray v -> r (a direction equal
// to the ray's counts as a full turn).
bool cw_before(Point2 v, Point2 r, Point2 w, Point2 z);

// Exact point-in-ring: +1 inside, -1 outside, 0 on the boundary.
int locate(Point2 h, const std::vector<Point2>& ring);

}  // namespace fdr::pslg::cd_steps
