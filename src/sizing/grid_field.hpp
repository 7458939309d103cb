// GridField: a SizingField sampled on a Grid, bilinear between cell centres.
#pragma once
#include "sizing/grid.hpp"
#include "sizing/sizing_field.hpp"

namespace fdr::sizing {

// Bilinear interpolation between the four surrounding cell centres; outside the hull of
// the centres the coordinate is clamped, so the edge cells extend to infinity.
// Construction validates the grid: nx, ny >= 1, dx, dy > 0 and every cell a positive finite
// number; otherwise throws Error(kInvalidSpacing) naming the first bad cell (i, j) and its centre.
// (Run clamp() or limit_gradient() first to turn +inf "no constraint" cells into numbers.)
class GridField final : public SizingField {
 public:
  explicit GridField(Grid g, std::string label = "grid");
  double operator()(Point2 p) const override;
  // Exact Lipschitz bound of the bilinear interpolant: on each cell the gradient components
  // are convex combinations of the two edge differences in that direction, so
  // |grad| <= sqrt(max|dv_x|^2/dx^2 + max|dv_y|^2/dy^2), maximised over cells.
  double lipschitz() const override { return lipschitz_; }
  bool thread_safe() const override { return true; }
  double upper_bound() const override { return max_; }  // bilinear: never above the largest cell
  std::string describe() const override;
  const Grid& grid() const { return g_; }

 private:
  Grid g_;
  std::string label_;
  double lipschitz_ = 0;
  double max_ = 0;
};

}  // namespace fdr::sizing
