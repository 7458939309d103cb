// StaticFilter3 against CGAL's exact kernel: random, nearly degenerate (one ulp off a plane or a
// sphere), exactly degenerate and GIS-sized inputs (metre coordinates offset by 6e5 / 5.5e6), and
// its bounds against the dynamic filter's at the box's worst corners.
#include <gtest/gtest.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <tuple>
#include <utility>
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

// A box [o, o + size] and a filter covering it (its two corners).
StaticFilter3 filter_for(Point3 o, Point3 size) {
  StaticFilter3 f;
  f.cover(o);
  f.cover(o + size);
  return f;
}

// A point of the box [o, o + size], coordinates uniform.
struct BoxPoints {
  Point3 o, size;
  std::mt19937_64 rng;
  std::uniform_real_distribution<double> u{0, 1};
  Point3 operator()() { return {o.x + size.x * u(rng), o.y + size.y * u(rng), o.z + size.z * u(rng)}; }
};

// The dynamic filters' bounds (predicates3d.hpp), computed the way they compute them.
double dynamic_orient_bound(Point3 a, Point3 b, Point3 c, Point3 d) {
  const double bx = b.x - a.x, by = b.y - a.y, bz = b.z - a.z;
  const double cx = c.x - a.x, cy = c.y - a.y, cz = c.z - a.z;
  const double dx = d.x - a.x, dy = d.y - a.y, dz = d.z - a.z;
  const double perm = (std::fabs(cx * dy) + std::fabs(dx * cy)) * std::fabs(bz) +
                      (std::fabs(dx * by) + std::fabs(bx * dy)) * std::fabs(cz) +
                      (std::fabs(bx * cy) + std::fabs(cx * by)) * std::fabs(dz);
  return detail::kO3dBound * perm;
}
double dynamic_insphere_bound(Point3 a, Point3 b, Point3 c, Point3 d, Point3 e) {
  const Point3 p[4] = {a - e, b - e, c - e, d - e};
  auto pxy = [&](int i, int j) { return std::fabs(p[i].x * p[j].y) + std::fabs(p[j].x * p[i].y); };
  auto lift = [&](int i) { return p[i].x * p[i].x + p[i].y * p[i].y + p[i].z * p[i].z; };
  const double az = std::fabs(p[0].z), bz = std::fabs(p[1].z), cz = std::fabs(p[2].z), dz = std::fabs(p[3].z);
  const double perm = (pxy(2, 3) * bz + pxy(1, 3) * cz + pxy(1, 2) * dz) * lift(0) +
                      (pxy(3, 0) * cz + pxy(0, 2) * dz + pxy(2, 3) * az) * lift(1) +
                      (pxy(0, 1) * dz + pxy(1, 3) * az + pxy(3, 0) * bz) * lift(2) +
                      (pxy(1, 2) * az + pxy(0, 2) * bz + pxy(0, 1) * cz) * lift(3);
  return detail::kIspBound * perm;
}
}  // namespace

TEST(StaticFilter3, EmptyCertifiesNothingAndStillAnswers) {
  const StaticFilter3 f;
  EXPECT_FALSE(f.covers({0, 0, 0}));
  EXPECT_EQ(f.orient_bound(), HUGE_VAL);
  EXPECT_EQ(f.insphere_bound(), HUGE_VAL);
  const StaticFilter3 g = f.covering({1, 2, 3});
  EXPECT_TRUE(g.covers({1, 2, 3}));
  EXPECT_FALSE(g.covers({1, 2, 3.5}));
  // A box of one point: every difference is 0 and so is every determinant, exactly.
  EXPECT_EQ(g.orient_bound(), 0.0);
}

TEST(StaticFilter3, CoveringGrowsTheBoxAndTheBounds) {
  const StaticFilter3 f = filter_for({0, 0, 0}, {1, 1, 1});
  EXPECT_TRUE(f.covers({0.5, 1, 0}));
  EXPECT_FALSE(f.covers({0.5, 1.5, 0}));
  const StaticFilter3 g = f.covering({0.5, 1.5, 0});
  EXPECT_TRUE(g.covers({0.5, 1.5, 0}));
  EXPECT_TRUE(g.covers({0, 0, 0}));
  EXPECT_GT(g.orient_bound(), f.orient_bound());
  EXPECT_GT(g.insphere_bound(), f.insphere_bound());
  // A covered point leaves it as it is.
  EXPECT_EQ(f.covering({0.25, 0.25, 0.25}).insphere_bound(), f.insphere_bound());
  // Tight enough to certify well-shaped unit tetrahedra.
  EXPECT_LT(f.orient_bound(), 1e-14);
  EXPECT_LT(f.insphere_bound(), 1e-12);
}

TEST(StaticFilter3, BoundsAreAtLeastTheDynamicOnesAtTheCorners) {
  // The permanents are largest with every difference at a full extent: points on the box's
  // corners. Every choice of corners (with repeats) is tried, for a cube, a flat slab and a box
  // offset like GIS coordinates.
  for (const auto& [o, size] : {std::pair<Point3, Point3>{{0, 0, 0}, {1, 1, 1}},
                                {{-3, 2, 7}, {1e4, 3e3, 0.5}},
                                {{6e5, 5.5e6, -500}, {8e4, 6e4, 1100}}}) {
    const StaticFilter3 f = filter_for(o, size);
    std::array<Point3, 8> corner;
    for (int k = 0; k < 8; ++k)
      corner[k] = {(k & 1) ? o.x + size.x : o.x, (k & 2) ? o.y + size.y : o.y, (k & 4) ? o.z + size.z : o.z};
    for (int m = 0; m < 8 * 8 * 8 * 8 * 8; ++m) {
      const Point3 a = corner[m & 7], b = corner[(m >> 3) & 7], c = corner[(m >> 6) & 7], d = corner[(m >> 9) & 7],
                   e = corner[(m >> 12) & 7];
      ASSERT_GE(f.orient_bound(), dynamic_orient_bound(a, b, c, d)) << m;
      ASSERT_GE(f.insphere_bound(), dynamic_insphere_bound(a, b, c, d, e)) << m;
    }
  }
}

TEST(StaticFilter3, RandomMatchExact) {
  for (const auto& [o, size] : {std::pair<Point3, Point3>{{-1, -1, -1}, {2, 2, 2}},
                                {{6e5, 5.5e6, -500}, {8e4, 6e4, 1100}}}) {
    const StaticFilter3 f = filter_for(o, size);
    BoxPoints pt{o, size, std::mt19937_64(1)};
    for (int i = 0; i < 20000; ++i) {
      std::array<Point3, 5> p;
      for (auto& q : p) q = pt();
      ASSERT_EQ(f.orient3d(p[0], p[1], p[2], p[3]), want_orient(p[0], p[1], p[2], p[3])) << i;
      ASSERT_EQ(f.insphere(p[0], p[1], p[2], p[3], p[4]), want_insphere(p[0], p[1], p[2], p[3], p[4])) << i;
    }
  }
}

TEST(StaticFilter3, SmallTetrahedraInAGisBoxMatchExact) {
  // Tetrahedra of about 100 m inside an 80 km x 60 km x 1.1 km box at UTM-like offsets: the
  // bound is loose for them, so many calls go on to the dynamic filter; the signs must not care.
  const Point3 o{6e5, 5.5e6, -500}, size{8e4, 6e4, 1100};
  const StaticFilter3 f = filter_for(o, size);
  BoxPoints centre{o, size, std::mt19937_64(2)};
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-50, 50);
  for (int i = 0; i < 20000; ++i) {
    Point3 c = centre();
    c.z = std::clamp(c.z, o.z + 60, o.z + size.z - 60);
    c.x = std::clamp(c.x, o.x + 60, o.x + size.x - 60);
    c.y = std::clamp(c.y, o.y + 60, o.y + size.y - 60);
    std::array<Point3, 5> p;
    for (auto& q : p) q = c + Point3{u(rng), u(rng), u(rng)};
    ASSERT_EQ(f.orient3d(p[0], p[1], p[2], p[3]), want_orient(p[0], p[1], p[2], p[3])) << i;
    ASSERT_EQ(f.insphere(p[0], p[1], p[2], p[3], p[4]), want_insphere(p[0], p[1], p[2], p[3], p[4])) << i;
  }
}

TEST(StaticFilter3, NearCoplanarMatchesExact) {
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(0, 1);
  for (const auto& [o, size] : {std::pair<Point3, Point3>{{0, 0, 0}, {1, 1, 1}},
                                {{6e5, 5.5e6, -500}, {8e4, 6e4, 1100}}}) {
    const StaticFilter3 f = filter_for(o, size);
    reset_counters();
    for (int i = 0; i < 30000; ++i) {
      auto at = [&](double s, double t, double w) { return Point3{o.x + s * size.x, o.y + t * size.y, o.z + w * size.z}; };
      const Point3 a = at(u(rng), u(rng), u(rng)), b = at(u(rng), u(rng), u(rng)), c = at(u(rng), u(rng), u(rng));
      // d on the plane abc up to rounding, inside the box (a convex combination), then one ulp off.
      double s = u(rng), t = u(rng) * (1 - s);
      Point3 d = a + s * (b - a) + t * (c - a);
      d = nudge(d, i);
      if (!f.covers(d)) continue;
      ASSERT_EQ(f.orient3d(a, b, c, d), want_orient(a, b, c, d)) << i;
      ASSERT_EQ(f.orient3d(d, c, b, a), want_orient(d, c, b, a)) << i;
    }
    EXPECT_GT(counters().exact, 0u);
  }
}

TEST(StaticFilter3, NearCosphericalMatchesExact) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (const auto& [o, size, r] : {std::tuple<Point3, Point3, double>{{-1, -1, -1}, {2, 2, 2}, 0.6},
                                   {{6e5, 5.5e6, -500}, {8e4, 6e4, 1100}, 150.0}}) {
    const StaticFilter3 f = filter_for(o, size);
    reset_counters();
    int tested = 0;
    for (int i = 0; i < 30000; ++i) {
      const Point3 c = o + 0.5 * size + Point3{u(rng) * 0.2 * size.x, u(rng) * 0.2 * size.y, u(rng) * 0.2 * size.z};
      std::array<Point3, 5> p;
      for (auto& q : p) {
        Point3 v;
        do v = {u(rng), u(rng), u(rng)}; while (norm2(v) < 1e-3 || norm2(v) > 1);
        q = c + (r / std::sqrt(norm2(v))) * v;
      }
      p[4] = nudge(p[4], i);
      if (want_orient(p[0], p[1], p[2], p[3]) == 0) continue;
      ++tested;
      ASSERT_EQ(f.insphere(p[0], p[1], p[2], p[3], p[4]), want_insphere(p[0], p[1], p[2], p[3], p[4])) << i;
    }
    EXPECT_GT(tested, 29000);
    EXPECT_GT(counters().exact, 0u);
  }
}

TEST(StaticFilter3, LatticeDegenerateMatchesExact) {
  // Integer lattices, also offset like GIS coordinates: many exactly coplanar quadruples and
  // cospherical quintuples, where the answer 0 must come out exactly.
  for (const Point3 o : {Point3{0, 0, 0}, Point3{6e5, 5.5e6, 0}}) {
    const StaticFilter3 f = filter_for(o + Point3{-3, -3, -3}, {6, 6, 6});
    std::mt19937 rng(6);
    std::uniform_int_distribution<int> u(-3, 3);
    int zeros_o = 0, zeros_s = 0;
    for (int i = 0; i < 40000; ++i) {
      std::array<Point3, 5> p;
      for (auto& q : p) q = o + Point3{double(u(rng)), double(u(rng)), double(u(rng))};
      const int want_o = want_orient(p[0], p[1], p[2], p[3]);
      ASSERT_EQ(f.orient3d(p[0], p[1], p[2], p[3]), want_o) << i;
      zeros_o += want_o == 0;
      const int s = f.insphere(p[0], p[1], p[2], p[3], p[4]);
      ASSERT_EQ(s, want_insphere(p[0], p[1], p[2], p[3], p[4])) << i;
      zeros_s += (want_o != 0 && s == 0);
    }
    EXPECT_GT(zeros_o, 1000);
    EXPECT_GT(zeros_s, 100);
  }
}

TEST(StaticFilter3, OverflowingBoxGoesOnToTheExactFallback) {
  const double big = 1e300;
  const StaticFilter3 f = filter_for({0, 0, 0}, {big, big, big});
  EXPECT_EQ(f.orient_bound(), HUGE_VAL);
  reset_counters();
  EXPECT_EQ(f.orient3d({0, 0, 0}, {big, 0, 0}, {0, big, 0}, {0, 0, big}), 1);
  EXPECT_EQ(counters().exact, 1u);
}
