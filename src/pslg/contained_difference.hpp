// a - b for two polygon sets whose boundaries run together, b inside a: the thin land a closing
// adds to a coast (closing(O) - O), an island minus its opening, closed water minus the tips
// cut from it. Why not a general overlay: such boundaries run within rounding of each other
// (one is an offset of an offset of the other), so the floating-point noding of an overlay fails
// and GEOS redoes it with snapping, which is slow on long rings. Here the near contacts are made
// exact first, and then no noding is needed at all.
#pragma once
#include <cstddef>
#include <optional>
#include <vector>
#include "base/types.hpp"

namespace fdr::pslg {

// One polygon: its outer ring, then its holes; rings open (no closing repeat), either orientation.
using PolygonRings = std::vector<std::vector<Point2>>;
using PolygonSet = std::vector<PolygonRings>;

struct ContainedDifferenceStats {
  std::size_t snapped = 0;   // vertices of a moved onto a vertex of b (within eps)
  std::size_t inserted = 0;  // vertices of one set inserted into a segment of the other (within eps)
  std::size_t cancelled = 0; // segments the two boundaries share (dropped from the result)
  std::size_t dropped = 0;   // slivers where b sticks out of a (not in a - b)
  std::size_t cut = 0;       // crossings and touches cut into both boundaries
  const char* refused = nullptr;  // why the fast path did not apply (nullopt returned)
};

// a - b when b lies inside a. First the boundaries are made to meet exactly: a vertex of a
// within eps of a vertex of b moves onto it, and a vertex of either within eps of a segment of
// the other (not of its ends) is inserted into that segment; so both sets change by at most
// eps. Then the segments the two share (with their interiors on the same side) cancel; where a
// segment of one still crosses or touches one of the other, the (rounded) contact point is
// inserted into both and the round is redone, at most 4 times. The rest is traced into loops
// (at a vertex where several meet, the sharpest left turn, or the sharpest right one beside a
// sliver; a walk that passes a vertex twice is split there), and each loop is judged by the sum
// of the other loops' winding numbers at one of its vertices: a counter-clockwise loop with sum
// 0 is a piece of a - b, a clockwise one with sum 1 its hole, the others slivers where b sticks
// out of a (not in a - b). Holes go to the smallest shell around them. Every decision is exact
// (orient2d).
// Returns nullopt (the caller overlays instead) when it cannot vouch for the result, e.g. a segment
// shared in the same direction (b beside a), crossings left after 4 rounds, a loop with every
// vertex on other loops, a ring that degenerates.
std::optional<PolygonSet> contained_difference(PolygonSet a, PolygonSet b, double eps,
                                               ContainedDifferenceStats* stats = nullptr);

}  // namespace fdr::pslg
