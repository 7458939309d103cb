// The spacing bounded by the layers' thickness: the bound near a thin layer, its grading away
// from it, the places listed, pinched-out triangles.
#include <gtest/gtest.h>
#include <cmath>
#include "base/error.hpp"
#include "terrain/depth_spacing.hpp"
#include "terrain/layer_spacing.hpp"
#include "terrain_fixture.hpp"

namespace fdr::terrain {
namespace {

using testing::lattice_tin;
using testing::plane;

// A grid over the lattice TIN's box ([0, 2]^2 x [zlo, zhi]) filled with a constant.
sizing::Grid3 constant_grid(double zlo, double zhi, double value) {
  Box3 b;
  b.add({0, 0, zlo});
  b.add({2, 2, zhi});
  sizing::Grid3 g = spacing_grid_geometry(b, 4000);
  g.v.assign(g.nx * g.ny * g.nz, value);
  return g;
}

TEST(LayerSpacing, ThinLayerBoundsTheSpacingAndIsListed) {
  const Tin tin = lattice_tin();
  // top 0, h1 -0.1 (a layer 0.1 thick), base -10.
  const std::vector<Surface> stack{plane(tin, "top", 0), plane(tin, "h1", -0.1), plane(tin, "base", -10)};
  sizing::Grid3 g = constant_grid(-10, 0, 5.0);
  const LayerSpacingResult r = bound_by_layer_thickness(g, tin, stack, {.factor = 1.0, .grade = 0.5, .hmin = 1.0});
  const sizing::GridField3 f(g);
  EXPECT_NEAR(f({1, 1, -0.05}), 0.1, 1e-9);  // inside the thin layer
  EXPECT_DOUBLE_EQ(r.smallest, 0.1);
  EXPECT_GT(r.cells_below_hmin, 0u);
  ASSERT_EQ(r.places.size(), 1u);  // the 9.9 m layer bounds at 9.9 > hmin: not listed
  EXPECT_EQ(r.places[0].layer, 0u);
  EXPECT_DOUBLE_EQ(r.places[0].thickness, 0.1);
  // Graded away at 0.5 per metre (up to the grid's cells), never above the input.
  EXPECT_LE(f.lipschitz(), 0.5 * (1 + 1e-9));
  EXPECT_LE(f({1, 1, -9.5}), 5.0);
  EXPECT_GT(f({1, 1, -9.5}), 1.0);
}

TEST(LayerSpacing, PinchedOutTrianglesBoundNothing) {
  const Tin tin = lattice_tin();
  // h1 on the top everywhere: the upper layer has no thickness; the lower one is 8 thick.
  const std::vector<Surface> stack{plane(tin, "top", 0), plane(tin, "h1", 0), plane(tin, "base", -8)};
  sizing::Grid3 g = constant_grid(-8, 0, 5.0);
  const LayerSpacingResult r = bound_by_layer_thickness(g, tin, stack, {.factor = 1.0, .grade = 0.5, .hmin = 1.0});
  for (double v : g.v) EXPECT_DOUBLE_EQ(v, 5.0);  // 1 x 8 m does not lower a 5 m spacing
  EXPECT_TRUE(r.places.empty());
  EXPECT_EQ(r.cells_below_hmin, 0u);
}

TEST(LayerSpacing, LayersThickerThanEverySpacingCellChangeNothing) {
  const Tin tin = lattice_tin();
  // One layer 6 thick over a spacing that varies below 5 (and one cell at exactly 6): the bound
  // never goes under a cell, so the grid comes back bit for bit, limiter or not.
  const std::vector<Surface> stack{plane(tin, "top", 0), plane(tin, "base", -6)};
  sizing::Grid3 g = constant_grid(-6, 0, 1.0);
  for (std::size_t c = 0; c < g.v.size(); ++c) g.v[c] = 1.0 + 4.0 * static_cast<double>(c % 7) / 7.0;
  g.v[g.v.size() / 2] = 6.0;
  const std::vector<double> before = g.v;
  const LayerSpacingResult r = bound_by_layer_thickness(g, tin, stack, {.factor = 1.0, .grade = 0.5, .hmin = 1.0});
  EXPECT_EQ(g.v, before);
  EXPECT_DOUBLE_EQ(r.smallest, 1.0);
  EXPECT_EQ(r.cells_below_hmin, 0u);
  EXPECT_TRUE(r.places.empty());
  // A spacing cell above the layer's thickness is lowered to it.
  g.v[g.v.size() / 2] = 7.0;
  bound_by_layer_thickness(g, tin, stack, {.factor = 1.0, .grade = 0.5, .hmin = 1.0});
  EXPECT_DOUBLE_EQ(g.v[g.v.size() / 2], 6.0);
}

TEST(LayerSpacing, BadOptionsAreUsageErrors) {
  const Tin tin = lattice_tin();
  const std::vector<Surface> stack{plane(tin, "top", 0), plane(tin, "base", -8)};
  sizing::Grid3 g = constant_grid(-8, 0, 5.0);
  EXPECT_THROW(bound_by_layer_thickness(g, tin, stack, {.factor = 0, .grade = 0.5}), Error);
  EXPECT_THROW(bound_by_layer_thickness(g, tin, stack, {.factor = 1, .grade = 0}), Error);
}

}  // namespace
}  // namespace fdr::terrain
