// Channel rule: a straight channel of known width gets h = width / N on its axis; land and open
// water far from both banks are not constrained by it; the even-odd mask.
#include <gtest/gtest.h>

#include <cmath>

#include "base/error.hpp"
#include "sizing/channel_rule.hpp"
#include "sizing/raster_rules.hpp"

namespace fdr::sizing {
namespace {

Grid grid(double x0, double y0, std::size_t nx, std::size_t ny, double cell) {
  Grid g;
  g.nx = nx;
  g.ny = ny;
  g.x0 = x0;
  g.y0 = y0;
  g.dx = g.dy = cell;
  g.v.assign(nx * ny, 0.0);
  return g;
}

std::vector<std::pair<Point2, Point2>> rect(double x0, double y0, double x1, double y1) {
  return {{{x0, y0}, {x1, y0}}, {{x1, y0}, {x1, y1}}, {{x1, y1}, {x0, y1}}, {{x0, y1}, {x0, y0}}};
}

TEST(ChannelRule, MaskIsEvenOdd) {
  const Grid g = grid(0, 0, 10, 10, 1);
  auto b = rect(2, 2, 8, 8);
  auto hole = rect(4, 4, 6, 6);
  b.insert(b.end(), hole.begin(), hole.end());
  const auto m = inside_mask(g, b);
  EXPECT_EQ(m[2 * 10 + 2], 1);  // (2.5, 2.5) inside
  EXPECT_EQ(m[4 * 10 + 4], 0);  // (4.5, 4.5) in the hole
  EXPECT_EQ(m[0], 0);
  EXPECT_EQ(m[9 * 10 + 9], 0);
  std::size_t n = 0;
  for (char c : m) n += c;
  EXPECT_EQ(n, 36u - 4u);
}

TEST(ChannelRule, StraightChannelGetsWidthOverN) {
  // A channel 400 m wide (y in [0, 400]) and 4 km long, cells of 10 m.
  const Grid like = grid(-100, -100, 420, 60, 10);
  const auto shore = std::vector<std::pair<Point2, Point2>>{{{0, 0}, {4000, 0}}, {{0, 400}, {4000, 400}}};
  auto boundary = rect(0, 0, 4000, 400);
  const Grid d = distance_to_shore(like, shore);
  const Grid h = rule_channel(d, inside_mask(like, boundary), 4.0);
  // On the axis (y = 200): h = 400 / 4 = 100 m.
  double hmin_axis = 1e300;
  for (std::size_t i = 50; i < 350; ++i) hmin_axis = std::min(hmin_axis, h.at(i, 29));  // row centre y = 195
  EXPECT_NEAR(hmin_axis, 97.5, 1e-9);  // the ridge cells sit 5 m off the axis: 2 * 195 / 4
  // Near the banks and outside the channel, no constraint.
  EXPECT_TRUE(std::isinf(h.at(200, 12)));  // y = 25
  EXPECT_TRUE(std::isinf(h.at(5, 5)));     // outside (x < 0)
  // min over the grid is on the axis.
  double hmin = 1e300;
  for (double v : h.v) hmin = std::min(hmin, v);
  EXPECT_NEAR(hmin, 97.5, 1e-9);
}

TEST(ChannelRule, BadN) {
  const Grid g = grid(0, 0, 2, 2, 1);
  EXPECT_THROW(rule_channel(g, std::vector<char>(4, 1), 0.5), Error);
}

}  // namespace
}  // namespace fdr::sizing
