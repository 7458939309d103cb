// The depth-graded spacing grid: geometry, values and the 3D gradient limit.
#include <gtest/gtest.h>
#include <cmath>
#include "base/error.hpp"
#include "terrain/depth_spacing.hpp"

namespace fdr::terrain {
namespace {

Box3 box(double wx, double wy, double wz) {
  Box3 b;
  b.add({0, 0, -wz});
  b.add({wx, wy, 0});
  return b;
}

TEST(DepthSpacing, GridCoversTheBoxWithinTheBudget) {
  const sizing::Grid3 g = spacing_grid_geometry(box(1000, 500, 20), 1e4);
  EXPECT_LE(static_cast<double>(g.nx * g.ny * g.nz), 1.6e4);
  EXPECT_GE(g.nz, 9u);
  EXPECT_LE(g.x0, 0.0);
  EXPECT_GE(g.x0 + g.nx * g.dx, 1000.0);
  EXPECT_GE(g.z0 + g.nz * g.dz, 0.0);
  EXPECT_EQ(column_centres(g).size(), g.nx * g.ny);
  EXPECT_GE(spacing_grid_geometry(box(1000, 500, 20), 1e4, 100).dx, 100.0);
}

TEST(DepthSpacing, GrowsWithDepthAndIsClamped) {
  sizing::Grid3 g = spacing_grid_geometry(box(100, 100, 100), 4000);
  const std::size_t cols = g.nx * g.ny;
  const std::vector<double> h2(cols, 5.0), top(cols, 0.0);
  fill_depth_spacing(g, h2, top, {.hmin = 2, .hmax = 40, .grade = 0.5, .alpha = 10});
  for (std::size_t k = 0; k < g.nz; ++k) {
    const double z = g.center(0, 0, k).z;
    EXPECT_DOUBLE_EQ(g.at(0, 0, k), std::clamp(5.0 + 0.5 * std::max(0.0, -z), 2.0, 40.0)) << k;
  }
}

TEST(DepthSpacing, GradientLimitedIn3D) {
  sizing::Grid3 g = spacing_grid_geometry(box(100, 100, 100), 4000);
  const std::size_t cols = g.nx * g.ny;
  std::vector<double> h2(cols, 50.0), top(cols, 0.0);
  h2[cols / 2] = 1.0;
  const double alpha = 0.2;
  fill_depth_spacing(g, h2, top, {.hmin = 1, .hmax = 50, .grade = 0, .alpha = alpha});
  const sizing::GridField3 f(g);
  EXPECT_LE(f.lipschitz(), alpha * (1 + 1e-9));
  EXPECT_THROW(fill_depth_spacing(g, h2, top, {.hmin = 0, .hmax = 50, .grade = 0, .alpha = alpha}), Error);
}

}  // namespace
}  // namespace fdr::terrain
