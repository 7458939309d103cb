// Raster sizing rules on grids in the local metric frame (all sizes and distances in metres).
#pragma once
#include <utility>
#include <vector>
#include "sizing/grid.hpp"

namespace fdr::sizing {

// Conventions for every rule below:
// - the output has the input's geometry (nx, ny, x0, y0, dx, dy);
// - NaN input cells (no data) give NaN output cells;
// - +inf means "this rule imposes no constraint here"; combine_min() ignores it against
//   finite values and clamp(g, hmin, hmax) turns it into hmax;
// - bad parameters throw Error(kUsage, ...).

// Euclidean distance from every cell centre of `like` (its values are ignored) to the nearest of
// the segments (degenerate segments act as points), in O(cells + segments):
//  1. each segment is listed in every cell its closed square meets ("shore cells");
//  2. an exact Euclidean distance transform of the shore cells (nearest_seed,
//     distance_transform.hpp) gives every cell its nearest shore cell;
//  3. per cell, the segment nearest to that shore cell's centre, improved along its chain
//     (consecutive segments sharing an endpoint) while the distance decreases;
//  4. per cell, the best of the 3 x 3 neighbourhood's step-3 segments: d~ >= d;
//  5. where d~ <= 3.5 cells (of the larger side), every segment listed in the cells whose centre
//     is within d~ + half a cell along x and y: a shore point at distance d lies in a cell whose
//     centre is that close, so the minimum is exact.
// Hence:
// - exact (equal bit for bit to the minimum over all segments) wherever d <= (3.5 - sqrt 2) cells
//   (d~ <= d + a cell diagonal), and in practice wherever d <= 3.5 cells: the narrow water the
//   channel rule measures and the coast's first cells;
// - farther out, the distance to one particular segment: never below the exact distance, at most
//   a cell diagonal above it, usually equal; the relative error shrinks with the distance, where
//   the distance rule's spacing is coarse anyway.
// Rows run on max_threads() threads; the result does not depend on the thread count. No
// segments: +inf everywhere. A non-finite coordinate throws Error(kInvalidGeometry) naming the
// segment. Segments reaching outside the grid (or exact = true) take a bounding-volume hierarchy
// queried cell by cell instead: exact everywhere, O(cells log segments), several times slower.
Grid distance_to_shore(const Grid& like, const std::vector<std::pair<Point2, Point2>>& shore_segments);
Grid distance_to_shore(const Grid& like, const std::vector<std::pair<Point2, Point2>>& shore_segments, bool exact);

// h = hmin + g * d  (hmin > 0, g >= 0): spacing growing linearly away from the shore.
Grid rule_distance(const Grid& dist, double hmin, double g);
// The same in place over the distance grid (no second grid of fresh pages).
Grid rule_distance(Grid&& dist, double hmin, double g);

// OceanMesh2D slope rule, depth positive down: h = (2 pi / slp) * depth / |grad depth|,
// i.e. about slp elements per "slope length" depth/|grad depth|. Land (depth <= 0) and flat
// cells (|grad| = 0) get +inf. Gradient by central differences, one-sided next to missing
// data or the grid edge (a direction without any valid neighbour contributes 0).
Grid rule_slope(const Grid& depth, double slp);

// Shallow-water wavelength rule: h = T * sqrt(9.81 * depth) / wl for depth > 0 (wl elements
// per wavelength of a wave of period T seconds); land (depth <= 0) gets +inf.
Grid rule_wavelength(const Grid& depth, double period_s, double wl);

// Terrain curvature rule: h = sqrt(8 * tol / kappa), kappa = largest absolute eigenvalue of
// the Hessian of the DEM (finite differences: central, shifted one-sided at edges and next to
// missing data; a mixed term whose 2x2 stencil is incomplete is left out). kappa is the
// largest principal curvature in the small-slope approximation and bounds the true one, so
// a straight edge of length h stays within tol of the surface (h^2 kappa / 8 <= tol); inside
// an equilateral triangle the bound is 4/3 of that — pass a smaller tol for a strict bound.
// kappa = 0 gives +inf.
Grid rule_curvature(const Grid& dem, double tol);

// Cell-wise minimum; NaN cells are ignored against numbers (NaN only where all are NaN).
// Throws Error(kInternal) on an empty list or grids of different geometry.
Grid combine_min(const std::vector<Grid>& grids);

// Cell-wise min(max(v, hmin), hmax), 0 < hmin <= hmax; +inf becomes hmax; NaN stays NaN.
Grid clamp(const Grid& g, double hmin, double hmax);

// Replaces NaN (no data) cells by `value`, e.g. hmax on land before building a GridField,
// which refuses NaN cells. Other cells are unchanged.
Grid fill_nan(const Grid& g, double value);

}  // namespace fdr::sizing
