// Channel (feature-size) rule: narrow water gets a spacing that puts at least N elements across
// it, the rule OceanMesh2D calls "fs". The width of the water at a point is taken from the
// distance-to-shore grid: on the medial axis of the water (cells where the distance has a ridge)
// the distance is the half-width w/2, so the rule sets h = w / N = 2 d / N there; the gradient
// limiter then carries it to the banks. Cells outside the water (even-odd over the boundary
// segments, scanline) are left without constraint, so a thin spit of land does not refine the
// water beside it.
#pragma once
#include <utility>
#include <vector>
#include "sizing/grid.hpp"

namespace fdr::sizing {

// +1 inside the region bounded by the segments (even-odd rule, cell centres), 0 outside.
std::vector<char> inside_mask(const Grid& like, const std::vector<std::pair<Point2, Point2>>& boundary);

// h = 2 d / n_elements on water cells where `dist` has a ridge along a row, a column or a
// diagonal (a local maximum against both neighbours), +inf elsewhere (no constraint). `dist` is
// distance_to_shore() on the same grid; `water` from inside_mask(). n_elements >= 1.
Grid rule_channel(const Grid& dist, const std::vector<char>& water, double n_elements);

}  // namespace fdr::sizing
