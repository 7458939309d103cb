// The spacing grid's geometry for GIS runs: its box, its cell size and its cells.
#pragma once
#include "base/types.hpp"
#include "sizing/grid.hpp"

namespace fdr::sizing {

// The box the spacing grid covers: the domain's bounding box grown by 2 % of its diagonal on
// every side (the raster is warped over the same box).
Box2 spacing_box(const Box2& domain_bbox);

// Cell size (metres) of the spacing grid over `box` (spacing_box()) when --cell-size is not given:
//   cell = max(hmin, sqrt(box area / 4e6)).
// Why hmin: f never goes below hmin, so finer cells add nothing the mesh can show (a raster finer
// than hmin is sampled at hmin; the raster's own resolution no longer sets the cell). Why the
// budget: the grid stays within about 4 M cells (32 MB per grid of doubles) however small hmin
// is against the domain; the gradient limiter keeps f smooth at that scale.
double spacing_grid_cell(const Box2& box, double hmin);

// Cells of `cell` metres covering `box` with one extra cell on every side (values 0).
Grid spacing_grid(const Box2& box, double cell);

}  // namespace fdr::sizing
