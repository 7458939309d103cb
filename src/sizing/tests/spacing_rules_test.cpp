// sizing::spacing_from_rules, resample_like, size_raster_rule (issue 8: moved from the pipeline).
#include <gtest/gtest.h>
#include <cmath>
#include <limits>
#include "sizing/resample_grid.hpp"
#include "sizing/spacing_rules.hpp"

namespace fdr::sizing {
namespace {

Grid grid(std::size_t nx, std::size_t ny, double d, double v) {
  Grid g;
  g.nx = nx;
  g.ny = ny;
  g.dx = g.dy = d;
  g.v.assign(nx * ny, v);
  return g;
}

TEST(ResampleGrid, SameCellsIsTheSameGridAndBilinearInBetween) {
  Grid g = grid(2, 1, 1.0, 0.0);
  g.v = {0.0, 10.0};
  const Grid same = resample_like(g, g);
  EXPECT_EQ(same.v, g.v);
  Grid fine = grid(4, 1, 0.5, 0.0);  // centres 0.25 0.75 1.25 1.75; g's centres 0.5 and 1.5
  const Grid r = resample_like(g, fine);
  EXPECT_DOUBLE_EQ(r.v[0], 0.0);   // clamped to the hull of the centres
  EXPECT_DOUBLE_EQ(r.v[1], 2.5);
  EXPECT_DOUBLE_EQ(r.v[2], 7.5);
  EXPECT_DOUBLE_EQ(r.v[3], 10.0);
}

TEST(ResampleGrid, SizeRasterNoConstraintCellsBecomeInfinity) {
  Grid like = grid(2, 2, 1.0, 0.0);
  Grid s = like;
  s.v = {5.0, -1.0, std::numeric_limits<double>::quiet_NaN(), 0.0};
  const Grid r = size_raster_rule(s, like);
  EXPECT_EQ(r.v[0], 5.0);
  for (int i = 1; i < 4; ++i) EXPECT_TRUE(std::isinf(r.v[i])) << i;
  const Grid coarse = size_raster_rule(grid(1, 1, 2.0, 7.0), like);  // nearest cell
  for (double v : coarse.v) EXPECT_EQ(v, 7.0);
}

TEST(SpacingRules, NoRuleAndNoShoreIsHmaxAndDistanceRuleIsNamed) {
  const Grid like = grid(8, 8, 10.0, 0.0);
  SpacingRules r;
  r.hmin = 10;
  r.hmax = 200;
  const RuleGrid none = spacing_from_rules(r, {&like, nullptr, nullptr, nullptr});
  EXPECT_TRUE(none.names.empty());
  for (double v : none.h.v) EXPECT_EQ(v, 200.0);
  const std::vector<std::pair<Point2, Point2>> shore = {{{0, 0}, {80, 0}}};
  const RuleGrid dist = spacing_from_rules(r, {&like, &shore, nullptr, nullptr});
  ASSERT_EQ(dist.names.size(), 1u);
  EXPECT_EQ(dist.names[0], "distance (hmin + 0.1 d)");
  EXPECT_DOUBLE_EQ(dist.h.at(0, 0), 10 + 0.1 * 5);  // cell centre 5 m from the shore
  for (double v : dist.h.v) EXPECT_TRUE(v >= 10 && v <= 200);
  EXPECT_EQ(describe_rules(dist, r, 0.15).rfind("grid 8x8: min(distance (hmin + 0.1 d)) clamped to [10, 200] m", 0), 0u);
}

}  // namespace
}  // namespace fdr::sizing
