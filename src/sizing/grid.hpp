// Grid: a regular raster in the mesh's local frame (values row-major, row 0 = lowest y).
#pragma once
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>
#include "base/types.hpp"

namespace fdr::sizing {

// Cell-centre sampling: value (i, j) sits at (x0 + (i + 0.5) dx, y0 + (j + 0.5) dy),
// i = column (0..nx-1, increasing x), j = row (0..ny-1, increasing y).
// Missing data are NaN (readers convert a raster's nodata value to NaN).
struct Grid {
  std::size_t nx = 0, ny = 0;
  double x0 = 0, y0 = 0;   // lower-left corner of the grid in the local frame
  double dx = 1, dy = 1;   // cell size (> 0)
  std::vector<double> v;   // nx * ny values, v[j * nx + i]

  double& at(std::size_t i, std::size_t j) { return v[j * nx + i]; }
  double at(std::size_t i, std::size_t j) const { return v[j * nx + i]; }
  Point2 center(std::size_t i, std::size_t j) const {
    return {x0 + (static_cast<double>(i) + 0.5) * dx, y0 + (static_cast<double>(j) + 0.5) * dy};
  }
  Box2 extent() const {
    Box2 b;
    b.add({x0, y0});
    b.add({x0 + static_cast<double>(nx) * dx, y0 + static_cast<double>(ny) * dy});
    return b;
  }
};

}  // namespace fdr::sizing
