// The spacing grid's geometry for GIS runs: its box, its cell size and its cells.
#pragma once
#include "base/types.hpp"
#include "sizing/grid.hpp"

namespace fdr::sizing {

// The box the spacing grid covers: the domain's bounding box grown by 2 % of its diagonal on
// every side (the raster is warped over the same box).
Box2 spacing_box(const Box2& domain_bbox);

// Cell size (metres) of the spacing grid over `box` (spacing_box()) when --cell-size is not given.
// `native` is the raster's resolution in metres (0 without a raster).
double spacing_grid_cell(const Box2& box, double hmin, double native);

// Cells of `cell` metres covering `box` with one extra cell on every side (values 0).
Grid spacing_grid(const Box2& box, double cell);

}  // namespace fdr::sizing
