// The spacing of a terrain volume: the 2D spacing of the surface run, growing with depth below
// the top, on a 3D grid gradient-limited in 3D.
#pragma once
#include <array>
#include <cstddef>
#include <vector>
#include "base/point3.hpp"
#include "base/types.hpp"
#include "sizing/spacing3d.hpp"

namespace fdr::terrain {

struct DepthSpacing {
  double hmin = 0;   // > 0: no value below it
  double hmax = 0;   // >= hmin: no value above it
  double grade = 0;  // G >= 0: the spacing grows by G metres per metre of depth below the top
  double alpha = 0;  // > 0: the gradient limit |grad f| <= alpha in 3D
  // Segments (wells) along which f is at most near_h (cap_near_segments, before the limiter).
  std::vector<std::array<Point3, 2>> near_segments;
  double near_h = 0;
};

// An empty grid (no values) over `box` with at most about max_cells cells: square cells in x and
// y no smaller than min_cell (a spacing need not be sampled much finer than its smallest value),
// and in z the same size or smaller so that the box's height has at least 8 cells.
sizing::Grid3 spacing_grid_geometry(const Box3& box, double max_cells, double min_cell = 0);

// The centres (x, y) of the grid's columns, i fastest: where the caller samples the 2D spacing
// and the top surface.
std::vector<Point2> column_centres(const sizing::Grid3& g);

// Fills g: f(x, y, z) = clamp(h2[c] + G * max(0, top[c] - z), hmin, hmax) for the column c of the
// cell, then gradient-limited so that the trilinear field (GridField3) is alpha-Lipschitz. h2 and top hold one value per column (column_centres order).
// Throws Error(kInvalidSpacing) on a spacing that is not positive, Error(kUsage) on bad options.
void fill_depth_spacing(sizing::Grid3& g, const std::vector<double>& h2, const std::vector<double>& top,
                        const DepthSpacing& opt);

}  // namespace fdr::terrain
