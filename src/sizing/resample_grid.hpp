// Grids resampled onto the cells of another grid (the spacing grid `like`).
#pragma once
#include "sizing/grid.hpp"

namespace fdr::sizing {

// `g` resampled onto the cells of `like` (bilinear between cell centres, clamped to their hull as
// GridField does). A non-finite corner with a non-zero weight is passed through (NaN before +inf),
// so nodata and "no constraint" areas are not smeared into finite values. Returns `g` itself
// when both grids have the same cells.
Grid resample_like(const Grid& g, const Grid& like);

// An explicit size raster `s` (metres) as a rule on the cells of `like`: nearest cell when the
// grids differ (NaN and non-positive cells are "no constraint" first), then every non-positive or
// non-finite value becomes +inf (no constraint).
Grid size_raster_rule(Grid s, const Grid& like);

}  // namespace fdr::sizing
