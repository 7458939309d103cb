// Raster output: a sizing::Grid written as a GeoTIFF in the frame's CRS (for --write-spacing).
#pragma once
#include <string>
#include "gis/crs.hpp"
#include "sizing/grid.hpp"

namespace fdr::gis {

// Float32 GeoTIFF, NaN = nodata, north-up, georeferenced in world coordinates of `frame`.
// Atomic: written to a temporary name in the same folder, then renamed. kOutputError on failure.
void write_grid_geotiff(const sizing::Grid& g, const Frame& frame, const std::string& path);

}  // namespace fdr::gis
