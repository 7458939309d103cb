// Spacing functions in 3D: the f(p) that drives the tetrahedral mesher, with a constant and a
// regular 3D grid (trilinear). Expressions are in spacing3d_expression.hpp, the gradient limiter
// in spacing3d_limiter.hpp.
#pragma once
#include <cstddef>
#include <limits>
#include <memory>
#include <string>
#include <vector>
#include "base/point3.hpp"

namespace fdr::sizing {

// f(p) > 0 is the desired local edge length at p (mesh coordinates). Every implementation is
// deterministic and safe to call from several threads at once: the 3D mesher evaluates it at
// circumcentres on every worker.
class SizingField3 {
 public:
  virtual ~SizingField3() = default;
  virtual double operator()(Point3 p) const = 0;
  // Known Lipschitz constant alpha (|f(p) - f(q)| <= alpha |p - q|), or negative if unknown.
  virtual double lipschitz() const { return -1.0; }
  // An upper bound of f over space, or +infinity if unknown.
  virtual double upper_bound() const { return std::numeric_limits<double>::infinity(); }
  // Human description for reports, e.g. "constant 0.5".
  virtual std::string describe() const = 0;
};

using SizingPtr3 = std::shared_ptr<const SizingField3>;

// f = h everywhere. Throws Error(kInvalidSpacing) unless h is a positive finite number.
class ConstantField3 final : public SizingField3 {
 public:
  explicit ConstantField3(double h);
  double operator()(Point3) const override { return h_; }
  double lipschitz() const override { return 0.0; }
  double upper_bound() const override { return h_; }
  std::string describe() const override;

 private:
  double h_;
};

// A regular 3D raster, cell-centre sampled as the 2D Grid: value (i, j, k) sits at
// (x0 + (i + 0.5) dx, y0 + (j + 0.5) dy, z0 + (k + 0.5) dz); values x fastest, then y, then z.
// Missing data are NaN.
struct Grid3 {
  std::size_t nx = 0, ny = 0, nz = 0;
  double x0 = 0, y0 = 0, z0 = 0;  // lowest corner
  double dx = 1, dy = 1, dz = 1;  // cell size (> 0)
  std::vector<double> v;          // nx * ny * nz values, v[(k * ny + j) * nx + i]

  std::size_t index(std::size_t i, std::size_t j, std::size_t k) const { return (k * ny + j) * nx + i; }
  double& at(std::size_t i, std::size_t j, std::size_t k) { return v[index(i, j, k)]; }
  double at(std::size_t i, std::size_t j, std::size_t k) const { return v[index(i, j, k)]; }
  Point3 center(std::size_t i, std::size_t j, std::size_t k) const {
    return {x0 + (static_cast<double>(i) + 0.5) * dx, y0 + (static_cast<double>(j) + 0.5) * dy,
            z0 + (static_cast<double>(k) + 0.5) * dz};
  }
};

// Trilinear interpolation between the eight surrounding cell centres; outside the hull of the
// centres each coordinate is clamped, so the boundary cells extend to infinity.
// Construction validates the grid: nx, ny, nz >= 1, positive finite cell sizes and every cell a
// positive finite number; otherwise throws Error(kInvalidSpacing) naming the first bad cell
// (i, j, k) and its centre (run limit_gradient3 first to turn +inf cells into numbers).
class GridField3 final : public SizingField3 {
 public:
  explicit GridField3(Grid3 g, std::string label = "grid");
  double operator()(Point3 p) const override;
  // Exact Lipschitz bound of the interpolant: on a cell each gradient component is a convex
  // combination of the four edge differences along its axis, so |grad| is at most the root of
  // the sum over axes of (largest edge difference / cell size)^2, maximised over cells.
  double lipschitz() const override { return lipschitz_; }
  double upper_bound() const override { return max_; }  // trilinear: never above the largest cell
  std::string describe() const override;
  const Grid3& grid() const { return g_; }

 private:
  Grid3 g_;
  std::string label_;
  double lipschitz_ = 0;
  double max_ = 0;
};

}  // namespace fdr::sizing
