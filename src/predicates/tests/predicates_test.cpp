// Predicates against CGAL's exact kernel on random, near-degenerate and exactly degenerate inputs.
#include <gtest/gtest.h>
#include <numbers>
#include <random>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include "predicates/predicates.hpp"
#include "base/triangle_geometry.hpp"

using namespace fdr;
using namespace fdr::predicates;
using EK = CGAL::Exact_predicates_exact_constructions_kernel;

static EK::Point_2 ek(Point2 p) { return {p.x, p.y}; }

TEST(Predicates, Orient2dBasic) {
  EXPECT_EQ(orient2d({0, 0}, {1, 0}, {0, 1}), 1);
  EXPECT_EQ(orient2d({0, 0}, {0, 1}, {1, 0}), -1);
  EXPECT_EQ(orient2d({0, 0}, {1, 1}, {2, 2}), 0);
}

TEST(Predicates, NearCollinearMatchesExact) {
  // Points on the line y = x perturbed by one ulp: the naive formula gets many of these wrong.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  int disagreements_naive = 0;
  for (int i = 0; i < 20000; ++i) {
    double t = u(rng);
    Point2 a{0.5, 0.5}, b{12.0, 12.0};
    Point2 c{0.5 + t * 11.5, 0.5 + t * 11.5};
    c.y = std::nextafter(c.y, (i % 3 == 0) ? 100.0 : ((i % 3 == 1) ? -100.0 : c.y));
    int got = orient2d(a, b, c);
    int want = static_cast<int>(CGAL::orientation(ek(a), ek(b), ek(c)));
    ASSERT_EQ(got, want) << i;
    double naive = (a.x - c.x) * (b.y - c.y) - (a.y - c.y) * (b.x - c.x);
    if ((naive > 0) - (naive < 0) != want) ++disagreements_naive;
  }
  EXPECT_GT(counters().exact, 0u);
}

TEST(Predicates, IncircleMatchesExactOnCocircularLattice) {
  // Lattice points: many exactly cocircular quadruples.
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> u(-4, 4);
  for (int i = 0; i < 20000; ++i) {
    Point2 p[4];
    for (auto& q : p) q = {u(rng) * 0.1, u(rng) * 0.1};
    if (orient2d(p[0], p[1], p[2]) <= 0) continue;
    int got = incircle(p[0], p[1], p[2], p[3]);
    int want = static_cast<int>(CGAL::side_of_oriented_circle(ek(p[0]), ek(p[1]), ek(p[2]), ek(p[3])));
    ASSERT_EQ(got, want) << i;
  }
}

TEST(Predicates, IncircleTranslatedFarAway) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 20000; ++i) {
    const double off = 1e7;
    Point2 p[4];
    for (auto& q : p) q = {off + u(rng), off + u(rng)};
    p[3] = {p[0].x + p[1].x - p[2].x, p[0].y + p[1].y - p[2].y};  // near-degenerate parallelogram
    int got = incircle(p[0], p[1], p[2], p[3]);
    int want = static_cast<int>(CGAL::side_of_oriented_circle(ek(p[0]), ek(p[1]), ek(p[2]), ek(p[3])));
    ASSERT_EQ(got, want) << i;
  }
}

TEST(Predicates, DiametralMatchesExact) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 20000; ++i) {
    Point2 a{u(rng), u(rng)}, b{u(rng), u(rng)};
    // A point near the circle with diameter ab.
    Point2 c = 0.5 * (a + b);
    double r = dist(a, b) / 2, th = u(rng) * std::numbers::pi;
    Point2 p{c.x + r * std::cos(th), c.y + r * std::sin(th)};
    int got = diametral(a, b, p);
    auto ang = CGAL::angle(ek(a), ek(p), ek(b));
    int want = ang == CGAL::OBTUSE ? 1 : (ang == CGAL::RIGHT ? 0 : -1);
    ASSERT_EQ(got, want) << i;
  }
  EXPECT_EQ(diametral({0, 0}, {2, 0}, {1, 1}), 0);   // exactly on the circle
  EXPECT_TRUE(encroaches({0, 0}, {2, 0}, {1, 0.5}));
  EXPECT_FALSE(encroaches({0, 0}, {2, 0}, {1, 1.5}));
}

TEST(Predicates, CircumcenterIsEquidistant) {
  double r2;
  Point2 c = geom::circumcentre({0, 0}, {2, 0}, {0, 2}, &r2);
  EXPECT_DOUBLE_EQ(c.x, 1);
  EXPECT_DOUBLE_EQ(c.y, 1);
  EXPECT_DOUBLE_EQ(r2, 2);
}
