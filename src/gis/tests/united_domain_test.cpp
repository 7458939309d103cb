// The united input domain the report measures the coast against (gis/united_domain.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "gis/united_domain.hpp"

using namespace fdr;

namespace {

coast::Rings box(double x0, double y0, double x1, double y1) { return {{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}}; }

double ring_area(const std::vector<Point2>& r) {
  double a = 0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Point2 p = r[i], q = r[(i + 1) % r.size()];
    a += p.x * q.y - q.x * p.y;
  }
  return 0.5 * a;
}

// Distance of p to the ring's boundary.
double to_ring(Point2 p, const std::vector<Point2>& r) {
  double best = INFINITY;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Point2 a = r[i], b = r[(i + 1) % r.size()], d = b - a;
    const double t = std::clamp(dot(p - a, d) / norm2(d), 0.0, 1.0);
    best = std::min(best, dist(p, a + t * d));
  }
  return best;
}

}  // namespace

// Two districts sharing a border (exactly the same vertices along it) become one polygon whose
// boundary does not run along the shared border.
TEST(UnitedDomain, AdjacentPolygonsLoseTheirSharedBorder) {
  coast::Rings left = {{{0, 0}, {10, 0}, {10, 5}, {10, 10}, {0, 10}}};
  coast::Rings right = {{{10, 0}, {20, 0}, {20, 10}, {10, 10}, {10, 5}}};
  const coast::Polygons out = gis::united_domain({left, right}, false).value();
  ASSERT_EQ(out.size(), 1u);
  ASSERT_EQ(out[0].size(), 1u);  // no hole
  EXPECT_NEAR(ring_area(out[0][0]), 200.0, 1e-9);  // counter-clockwise
  EXPECT_GT(to_ring({10, 5}, out[0][0]), 4.9);      // the border's midpoint is inside
  EXPECT_NEAR(to_ring({10, 0}, out[0][0]), 0.0, 1e-12);
}

// Overlapping polygons (reported so by the generalisation) are united even without a common
// vertex; a hole of one covered by the other disappears.
TEST(UnitedDomain, OverlapsUnitedAndCoveredHolesGone) {
  coast::Rings a = box(0, 0, 10, 10);
  a.push_back({{6, 4}, {6, 6}, {8, 6}, {8, 4}});  // a clockwise hole under b
  const coast::Rings b = box(5, 2, 15, 8);
  const coast::Polygons out = gis::united_domain({a, b}, true).value();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].size(), 1u);
  EXPECT_NEAR(ring_area(out[0][0]), 100.0 + 60.0 - 30.0, 1e-9);  // the 5 x 6 overlap once
}

// Disjoint polygons, and a single one, need no union (no GEOS work).
TEST(UnitedDomain, DisjointAndSingleNeedNone) {
  EXPECT_FALSE(gis::united_domain({box(0, 0, 1, 1), box(3, 0, 4, 1)}, false));
  EXPECT_FALSE(gis::united_domain({box(0, 0, 1, 1)}, true));
  // Touching at one corner: a shared vertex, so united (GEOS keeps two polygons meeting at a point).
  const auto corner = gis::united_domain({box(0, 0, 1, 1), box(1, 1, 2, 2)}, false);
  ASSERT_TRUE(corner);
  EXPECT_EQ(corner->size(), 2u);
}
