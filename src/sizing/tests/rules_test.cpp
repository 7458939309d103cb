// Tests of the raster rules: distance to shore against brute force, slope/wavelength/
// curvature on analytic surfaces, combine_min and clamp conventions.
#include "sizing/tests/brute_distance.hpp"
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "base/error.hpp"
#include "sizing/raster_rules.hpp"

namespace fdr::sizing {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

Grid make_grid(std::size_t nx, std::size_t ny, double x0, double y0, double dx, double dy) {
  Grid g;
  g.nx = nx; g.ny = ny; g.x0 = x0; g.y0 = y0; g.dx = dx; g.dy = dy;
  g.v.assign(nx * ny, 0.0);
  return g;
}

template <class F>
Grid sample(Grid g, F f) {
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i) g.at(i, j) = f(g.center(i, j));
  return g;
}

using fdr::sizing::testing::brute_dist;

TEST(DistanceToShore, EqualsBruteForce) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 3; ++trial) {
    std::uniform_real_distribution<double> u(-50, 150), len(-8, 8);
    std::vector<std::pair<Point2, Point2>> segs;
    const int n = trial == 0 ? 1 : trial == 1 ? 17 : 400;
    for (int k = 0; k < n; ++k) {
      const Point2 a{u(rng), u(rng)};
      segs.push_back({a, trial == 1 && k == 0 ? a : a + Point2{len(rng), len(rng)}});  // one degenerate
    }
    const Grid like = make_grid(83, 61, -20, -10, 1.5, 2.0);
    const Grid d = distance_to_shore(like, segs);
    ASSERT_EQ(d.nx, like.nx);
    for (std::size_t j = 0; j < d.ny; ++j)
      for (std::size_t i = 0; i < d.nx; ++i) ASSERT_EQ(d.at(i, j), brute_dist(d.center(i, j), segs)) << i << " " << j;
  }
}

TEST(DistanceToShore, EmptyAndBadSegments) {
  const Grid like = make_grid(4, 3, 0, 0, 1, 1);
  for (double v : distance_to_shore(like, {}).v) EXPECT_EQ(v, kInf);
  try {
    distance_to_shore(like, {{{0, 0}, {1, 1}}, {{0, std::nan("")}, {1, 1}}});
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidGeometry);
    EXPECT_NE(std::string(e.what()).find("shore segment 1"), std::string::npos);
  }
}

TEST(Rules, Distance) {
  Grid d = make_grid(3, 1, 0, 0, 1, 1);
  d.v = {0, 10, kInf};
  const Grid h = rule_distance(d, 50, 0.2);
  EXPECT_EQ(h.v[0], 50);
  EXPECT_EQ(h.v[1], 52);
  EXPECT_EQ(h.v[2], kInf);
  EXPECT_EQ(rule_distance(d, 50, 0).v[2], 50);
  EXPECT_THROW(rule_distance(d, 0, 0.2), Error);
  EXPECT_THROW(rule_distance(d, 1, -1), Error);
}

TEST(Rules, SlopeOnLinearBathymetry) {
  const double gx = 0.01, gy = -0.02;
  // Depth positive down; the left part is land (negative depth).
  Grid depth = sample(make_grid(40, 30, 0, 0, 10, 20), [&](Point2 p) { return gx * p.x + gy * p.y + 2; });
  depth.at(20, 15) = std::nan("");
  const double slp = 10;
  const Grid h = rule_slope(depth, slp);
  int water = 0;
  for (std::size_t j = 0; j < h.ny; ++j)
    for (std::size_t i = 0; i < h.nx; ++i) {
      const double d = depth.at(i, j);
      if (std::isnan(d)) {
        EXPECT_TRUE(std::isnan(h.at(i, j)));
      } else if (d <= 0) {
        EXPECT_EQ(h.at(i, j), kInf);
      } else {
        ++water;
        EXPECT_NEAR(h.at(i, j), 2 * std::numbers::pi / slp * d / std::hypot(gx, gy), 1e-9 * h.at(i, j)) << i << " " << j;
      }
    }
  EXPECT_GT(water, 100);
  const Grid flat = sample(make_grid(5, 5, 0, 0, 1, 1), [](Point2) { return 30.0; });
  for (double v : rule_slope(flat, 10).v) EXPECT_EQ(v, kInf);
  EXPECT_THROW(rule_slope(flat, 0), Error);
}

TEST(Rules, Wavelength) {
  Grid depth = make_grid(4, 1, 0, 0, 1, 1);
  depth.v = {100, 4, -3, std::nan("")};
  const Grid h = rule_wavelength(depth, 12.42 * 3600, 30);
  EXPECT_DOUBLE_EQ(h.v[0], 12.42 * 3600 * std::sqrt(981.0) / 30);
  EXPECT_DOUBLE_EQ(h.v[1], 12.42 * 3600 * std::sqrt(9.81 * 4) / 30);
  EXPECT_EQ(h.v[2], kInf);
  EXPECT_TRUE(std::isnan(h.v[3]));
  EXPECT_THROW(rule_wavelength(depth, 0, 30), Error);
}

TEST(Rules, CurvatureOnQuadraticSurfaces) {
  const double tol = 0.1;
  struct Case {
    double a, b, c;  // z = a x^2 / 2 + b x y + c y^2 / 2, Hessian [[a, b], [b, c]]
  } cases[] = {{0.02, 0, -0.05}, {0, 0.03, 0}, {0.02, 0.03, 0}, {-0.01, 0.004, -0.01}};
  for (const auto& k : cases) {
    const Grid dem = sample(make_grid(25, 18, -100, 40, 4, 6), [&](Point2 p) {
      return 100 + 0.3 * p.x + k.a * p.x * p.x / 2 + k.b * p.x * p.y + k.c * p.y * p.y / 2;
    });
    const double m = (k.a + k.c) / 2, r = std::hypot((k.a - k.c) / 2, k.b);
    const double kappa = std::max(std::abs(m + r), std::abs(m - r));
    const Grid h = rule_curvature(dem, tol);
    for (std::size_t j = 0; j < h.ny; ++j)
      for (std::size_t i = 0; i < h.nx; ++i)
        EXPECT_NEAR(h.at(i, j), std::sqrt(8 * tol / kappa), 1e-6 * h.at(i, j)) << k.a << " " << i << " " << j;
  }
  // Paraboloid of radius R at the apex: z = (x^2 + y^2) / (2R), kappa = 1/R.
  const double R = 500;
  const Grid para = sample(make_grid(31, 31, -150, -150, 10, 10), [&](Point2 p) { return (p.x * p.x + p.y * p.y) / (2 * R); });
  EXPECT_NEAR(rule_curvature(para, tol).at(15, 15), std::sqrt(8 * tol * R), 1e-6);
  const Grid plane = sample(make_grid(6, 6, 0, 0, 1, 1), [](Point2 p) { return 2 * p.x - p.y; });
  for (double v : rule_curvature(plane, tol).v) EXPECT_EQ(v, kInf);
  EXPECT_THROW(rule_curvature(plane, 0), Error);
}

TEST(Rules, CombineMinAndClamp) {
  Grid a = make_grid(4, 1, 0, 0, 1, 1), b = a;
  a.v = {1, kInf, std::nan(""), std::nan("")};
  b.v = {2, 3, 4, std::nan("")};
  const Grid m = combine_min({a, b});
  EXPECT_EQ(m.v[0], 1);
  EXPECT_EQ(m.v[1], 3);
  EXPECT_EQ(m.v[2], 4);
  EXPECT_TRUE(std::isnan(m.v[3]));
  Grid c = make_grid(4, 1, 0, 0, 2, 1);
  EXPECT_THROW(combine_min({a, c}), Error);
  EXPECT_THROW(combine_min({}), Error);
  const Grid cl = clamp(a, 0.5, 0.8);
  EXPECT_EQ(cl.v[0], 0.8);
  EXPECT_EQ(cl.v[1], 0.8);  // +inf (no constraint) becomes hmax
  EXPECT_TRUE(std::isnan(cl.v[2]));
  EXPECT_EQ(clamp(a, 2, 5).v[0], 2);
  EXPECT_THROW(clamp(a, 2, 1), Error);
  const Grid f = fill_nan(a, 7);
  EXPECT_EQ(f.v[0], 1);
  EXPECT_EQ(f.v[1], kInf);
  EXPECT_EQ(f.v[2], 7);
  EXPECT_EQ(f.v[3], 7);
}

}  // namespace
}  // namespace fdr::sizing
