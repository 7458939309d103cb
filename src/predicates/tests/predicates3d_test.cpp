// orient3d and insphere against CGAL's exact kernel on random, near-degenerate (one ulp off a
// plane or a sphere) and exactly degenerate (integer lattice) inputs.
#include <gtest/gtest.h>
#include <array>
#include <cmath>
#include <random>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include "predicates/predicates3d.hpp"

using namespace fdr;
using namespace fdr::predicates;
using EK = CGAL::Exact_predicates_exact_constructions_kernel;

namespace {
EK::Point_3 ek(Point3 p) { return {p.x, p.y, p.z}; }
int want_orient(Point3 a, Point3 b, Point3 c, Point3 d) {
  return static_cast<int>(CGAL::orientation(ek(a), ek(b), ek(c), ek(d)));
}
int want_insphere(Point3 a, Point3 b, Point3 c, Point3 d, Point3 e) {
  return static_cast<int>(CGAL::side_of_oriented_sphere(ek(a), ek(b), ek(c), ek(d), ek(e)));
}
Point3 nudge(Point3 p, int k) {
  // One ulp up, one ulp down or unchanged, on one coordinate chosen by k.
  const double dir = (k % 3 == 0) ? HUGE_VAL : -HUGE_VAL;
  if (k % 3 == 2) return p;
  switch ((k / 3) % 3) {
    case 0: p.x = std::nextafter(p.x, dir); break;
    case 1: p.y = std::nextafter(p.y, dir); break;
    default: p.z = std::nextafter(p.z, dir); break;
  }
  return p;
}
}  // namespace

TEST(Predicates3d, OrientBasic) {
  EXPECT_EQ(orient3d({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}), 1);
  EXPECT_EQ(orient3d({0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 0, 1}), -1);
  EXPECT_EQ(orient3d({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}), 0);
}

TEST(Predicates3d, InsphereBasic) {
  const Point3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0}, d{0, 0, 1};
  ASSERT_EQ(orient3d(a, b, c, d), 1);
  EXPECT_EQ(insphere(a, b, c, d, {0.25, 0.25, 0.25}), 1);
  EXPECT_EQ(insphere(a, b, c, d, {1, 1, 1}), 0);  // the cube's corner: on the sphere
  EXPECT_EQ(insphere(a, b, c, d, {2, 2, 2}), -1);
  EXPECT_EQ(insphere(b, a, c, d, {0.25, 0.25, 0.25}), -1);  // negative orientation flips the sign
}

TEST(Predicates3d, RandomMatchExactAndAreMostlyFiltered) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1, 1);
  reset_counters();
  for (int i = 0; i < 20000; ++i) {
    std::array<Point3, 5> p;
    for (auto& q : p) q = {u(rng), u(rng), u(rng)};
    ASSERT_EQ(orient3d(p[0], p[1], p[2], p[3]), want_orient(p[0], p[1], p[2], p[3])) << i;
    ASSERT_EQ(insphere(p[0], p[1], p[2], p[3], p[4]), want_insphere(p[0], p[1], p[2], p[3], p[4])) << i;
  }
  EXPECT_EQ(counters().filtered + counters().exact, 40000u);
  EXPECT_LT(counters().exact, 40u);
}

TEST(Predicates3d, NearCoplanarMatchesExact) {
  // d on the plane through a, b, c up to rounding, then moved by one ulp: the naive formula and
  // any missing term of the bound would be caught here.
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> u(-1, 1);
  reset_counters();
  for (int i = 0; i < 30000; ++i) {
    const double off = (i % 2) ? 0.0 : 1e6;
    Point3 a{off + u(rng), off + u(rng), u(rng)}, b{off + u(rng), off + u(rng), u(rng)};
    Point3 c{off + u(rng), off + u(rng), u(rng)};
    const double s = u(rng), t = u(rng);
    Point3 d = a + s * (b - a) + t * (c - a);
    d = nudge(d, i);
    ASSERT_EQ(orient3d(a, b, c, d), want_orient(a, b, c, d)) << i;
    ASSERT_EQ(orient3d(d, c, b, a), want_orient(d, c, b, a)) << i;
  }
  EXPECT_GT(counters().exact, 0u);
}

TEST(Predicates3d, NearCosphericalMatchesExact) {
  // e on the sphere through a..d up to rounding (points on a sphere round a centre), one ulp off.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  reset_counters();
  auto on_sphere = [&](Point3 c, double r) {
    Point3 v;
    do v = {u(rng), u(rng), u(rng)}; while (norm2(v) < 1e-3 || norm2(v) > 1);
    return c + (r / std::sqrt(norm2(v))) * v;
  };
  int tested = 0;
  for (int i = 0; i < 30000; ++i) {
    const Point3 c{(i % 2) ? 0.0 : 1e5 + u(rng), u(rng), u(rng)};
    const double r = 0.5 + u(rng) * 0.25;
    std::array<Point3, 5> p;
    for (auto& q : p) q = on_sphere(c, r);
    p[4] = nudge(p[4], i);
    if (orient3d(p[0], p[1], p[2], p[3]) == 0) continue;
    ++tested;
    ASSERT_EQ(insphere(p[0], p[1], p[2], p[3], p[4]), want_insphere(p[0], p[1], p[2], p[3], p[4])) << i;
  }
  EXPECT_GT(tested, 29000);
  EXPECT_GT(counters().exact, 0u);
}

TEST(Predicates3d, LatticeDegenerateMatchesExact) {
  // Small integer lattices: many exactly coplanar quadruples and cospherical quintuples, where
  // the answer 0 must come out exactly.
  std::mt19937 rng(4);
  std::uniform_int_distribution<int> u(-3, 3);
  int zeros_o = 0, zeros_s = 0;
  for (int i = 0; i < 40000; ++i) {
    std::array<Point3, 5> p;
    for (auto& q : p) q = {u(rng) * 0.1, u(rng) * 0.1, u(rng) * 0.1};
    const int o = orient3d(p[0], p[1], p[2], p[3]);
    ASSERT_EQ(o, want_orient(p[0], p[1], p[2], p[3])) << i;
    zeros_o += o == 0;
    const int s = insphere(p[0], p[1], p[2], p[3], p[4]);
    ASSERT_EQ(s, want_insphere(p[0], p[1], p[2], p[3], p[4])) << i;
    zeros_s += (o != 0 && s == 0);
  }
  EXPECT_GT(zeros_o, 1000);
  EXPECT_GT(zeros_s, 100);
}

TEST(Predicates3d, NonFiniteGoesExact) {
  const double big = 1e300;
  reset_counters();
  // The products overflow: the filter must not certify, the exact answer is still positive.
  EXPECT_EQ(orient3d({0, 0, 0}, {big, 0, 0}, {0, big, 0}, {0, 0, big}), 1);
  EXPECT_EQ(counters().exact, 1u);
}

TEST(Predicates3d, DiametralSideIsTheSignOfTheAngleAtP) {
  const Point3 a{0, 0, 0}, b{2, 0, 0};
  EXPECT_EQ(diametral_side(a, b, {1, 0.5, 0}), 1);
  EXPECT_EQ(diametral_side(a, b, {1, 1, 0}), 0);   // on the sphere: a right angle at p
  EXPECT_EQ(diametral_side(a, b, {1, 0, 1}), 0);
  EXPECT_EQ(diametral_side(a, b, {1, 0.7, 0.8}), -1);
  // Against the exact kernel on random points near the sphere.
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 2000; ++i) {
    const Point3 p{1 + u(rng), u(rng), u(rng)};
    const EK::Point_3 ea(a.x, a.y, a.z), eb(b.x, b.y, b.z), ep(p.x, p.y, p.z);
    const auto d = (ea - ep) * (eb - ep);
    const int want = d < 0 ? 1 : (d == 0 ? 0 : -1);
    ASSERT_EQ(diametral_side(a, b, p), want) << i;
  }
}

TEST(Predicates3d, EquatorialSideUsesTheSmallestSphere) {
  // Triangle in z = 0 with circumcentre (0.5, 0.5, 0) and radius sqrt(0.5).
  const Point3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  EXPECT_EQ(equatorial_side(a, b, c, {0.5, 0.5, 0.7}), 1);
  EXPECT_EQ(equatorial_side(a, b, c, {0.5, 0.5, 0.75}), -1);
  EXPECT_EQ(equatorial_side(a, b, c, {1, 1, 0}), 0);
  EXPECT_EQ(equatorial_side(a, b, c, {0.5, 0.5, -0.7}), 1);
  // Tilted triangle far from the origin, points on the equatorial circle's axis.
  const Point3 o{1e3, 2e3, -5e2};
  const Point3 ta = o + Point3{1, 0, 1}, tb = o + Point3{-1, 0, -1}, tc = o + Point3{0, 1, 0};
  EXPECT_EQ(equatorial_side(ta, tb, tc, o + Point3{0.5, 0, -0.5}), 1);
  EXPECT_EQ(equatorial_side(ta, tb, tc, o + Point3{1.5, 0, -1.5}), -1);
}

TEST(Predicates3d, TriangleCircumcentreExactAndCollinear) {
  const Point3 a{0, 0, 0}, b{2, 0, 0}, c{0, 2, 0};
  EXPECT_EQ(triangle_circumcentre_exact(a, b, c), (Point3{1, 1, 0}));
  const Point3 o{1e3, 2e3, -5e2};
  EXPECT_EQ(triangle_circumcentre_exact(o + Point3{3, 0, 4}, o + Point3{-3, 0, -4}, o + Point3{0, 5, 0}), o);
  EXPECT_FALSE(collinear3d(a, b, c));
  EXPECT_TRUE(collinear3d(a, b, {5, 0, 0}));
  EXPECT_TRUE(collinear3d(a, a, c));
  // A point off the line by one unit in the last place is not collinear.
  EXPECT_FALSE(collinear3d({0, 0, 0}, {1, 1, 1}, {0.5, 0.5, std::nextafter(0.5, 1.0)}));
}
