// The one-triangle geometry (base/triangle_geometry.hpp) on triangles whose answers are known.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "base/triangle_geometry.hpp"

namespace fdr::geom {
namespace {

const double kInf = std::numeric_limits<double>::infinity();
const double kSqrt3 = std::sqrt(3.0);

TEST(TriangleGeometry, Equilateral) {
  const Point2 a{0, 0}, b{2, 0}, c{1, kSqrt3};
  double r2 = 0;
  const Point2 cc = circumcentre(a, b, c, &r2);
  EXPECT_NEAR(cc.x, 1.0, 1e-15);
  EXPECT_NEAR(cc.y, kSqrt3 / 3, 1e-15);
  EXPECT_NEAR(r2, 4.0 / 3, 1e-15);
  EXPECT_NEAR(circumradius(a, b, c), 2 / kSqrt3, 1e-15);
  EXPECT_NEAR(shortest_edge(a, b, c), 2.0, 1e-15);
  EXPECT_NEAR(min_angle_deg(a, b, c), 60.0, 1e-12);
  EXPECT_NEAR(radius_edge_ratio(a, b, c), 1 / kSqrt3, 1e-15);
  EXPECT_NEAR(mean_ratio_quality(a, b, c), 1.0, 1e-15);
  EXPECT_NEAR(min_angle_sin2(a, b, c), 0.75, 1e-15);
  EXPECT_NEAR(mean_ratio_quality(a, c, b), -1.0, 1e-15);  // clockwise
  EXPECT_DOUBLE_EQ(r_over_f(2.0, 4.0), 0.5);
}

TEST(TriangleGeometry, RightTriangle) {
  const Point2 a{0, 0}, b{4, 0}, c{0, 3};
  double r2 = 0;
  const Point2 cc = circumcentre(a, b, c, &r2);  // the hypotenuse's midpoint
  EXPECT_DOUBLE_EQ(cc.x, 2.0);
  EXPECT_DOUBLE_EQ(cc.y, 1.5);
  EXPECT_DOUBLE_EQ(r2, 6.25);
  EXPECT_DOUBLE_EQ(shortest_edge(a, b, c), 3.0);
  EXPECT_DOUBLE_EQ(radius_edge_ratio(a, b, c), 2.5 / 3.0);
  EXPECT_NEAR(angle_deg(a, b, c), 90.0, 1e-12);
  EXPECT_NEAR(min_angle_deg(a, b, c), std::atan2(3.0, 4.0) * 180 / std::numbers::pi, 1e-12);
  EXPECT_NEAR(min_angle_sin2(a, b, c), 0.36, 1e-15);
  EXPECT_NEAR(mean_ratio_quality(a, b, c), 4 * kSqrt3 * 6 / 50, 1e-15);
}

TEST(TriangleGeometry, Degenerate) {
  const Point2 a{0, 0}, b{1, 1}, c{3, 3};
  EXPECT_EQ(cross2(a, b, c), 0.0);
  EXPECT_EQ(circumradius(a, b, c), kInf);
  EXPECT_EQ(radius_edge_ratio(a, b, c), kInf);
  EXPECT_EQ(min_angle_deg(a, b, c), 0.0);
  EXPECT_EQ(mean_ratio_quality(a, b, c), 0.0);
  EXPECT_EQ(min_angle_sin2(a, b, c), 0.0);
  // Two equal corners: no shortest edge to divide by.
  EXPECT_EQ(radius_edge_ratio(a, a, c), kInf);
  EXPECT_EQ(mean_ratio_quality(a, a, a), 0.0);
}

// Far from the origin the differences lose the leading digits, but the values stay those of the
// triangle at the origin within the relative rounding of its coordinates.
TEST(TriangleGeometry, FarTranslated) {
  const Point2 off{1e6, -2e6};
  const Point2 a{0, 0}, b{2, 0}, c{0.5, 1.5};
  const Point2 fa = a + off, fb = b + off, fc = c + off;
  double r2 = 0, fr2 = 0;
  const Point2 cc = circumcentre(a, b, c, &r2), fcc = circumcentre(fa, fb, fc, &fr2);
  EXPECT_NEAR(fcc.x - off.x, cc.x, 1e-9);
  EXPECT_NEAR(fcc.y - off.y, cc.y, 1e-9);
  EXPECT_NEAR(fr2, r2, 1e-9);
  EXPECT_NEAR(min_angle_deg(fa, fb, fc), min_angle_deg(a, b, c), 1e-8);
  EXPECT_NEAR(mean_ratio_quality(fa, fb, fc), mean_ratio_quality(a, b, c), 1e-9);
  EXPECT_NEAR(radius_edge_ratio(fa, fb, fc), radius_edge_ratio(a, b, c), 1e-9);
}

// The one formula of the smallest angle: the smallest of the three corner angles, also where
// min_angle_deg skips corners that cannot hold it.
TEST(TriangleGeometry, MinAngleIsTheSmallestCornerAngle) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 20000; ++i) {
    const double s = i % 3 == 0 ? 1e-4 : 1.0;  // every third one thin
    const Point2 a{u(rng), u(rng)}, b{u(rng), u(rng)};
    const Point2 c = 0.5 * (a + b) + s * Point2{u(rng), u(rng)};
    const double all = std::min({angle_deg(a, b, c), angle_deg(b, c, a), angle_deg(c, a, b)});
    EXPECT_EQ(min_angle_deg(a, b, c), all) << i;
  }
}

}  // namespace
}  // namespace fdr::geom
