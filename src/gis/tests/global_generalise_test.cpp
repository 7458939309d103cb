// The coast generalisation of global runs in ground metres: land groups by reach on the sphere,
// and the same synthetic land near the equator and near the projection's pole (where the global
// plane's scale factor is 15) generalised alike; lon/lat clipping for the tiles.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "gis/global_generalise.hpp"
#include "gis/global_land.hpp"
#include "gis/global_sphere.hpp"

using namespace fdr;
using namespace fdr::gis;

namespace {

// A ring given in metres in a plane tangent at `at` (scale 1 there), on the sphere.
std::vector<LonLat> ring_at(LonLat at, const std::vector<Point2>& metres) {
  const SphereStereo local({at.lon_deg > 0 ? at.lon_deg - 180 : at.lon_deg + 180, -at.lat_deg});
  std::vector<LonLat> out;
  for (const Point2& p : metres) out.push_back(local.inverse(p));
  return out;
}

std::vector<Point2> square(double x0, double y0, double side) {
  return {{x0, y0}, {x0 + side, y0}, {x0 + side, y0 + side}, {x0, y0 + side}};
}

double sphere_area(const std::vector<LonLat>& ring) {
  const Point3 c = unit_vector(ring[0]);
  double a = 0;
  for (std::size_t i = 1; i + 1 < ring.size(); ++i)
    a += spherical_triangle_area(c, unit_vector(ring[i]), unit_vector(ring[i + 1]));
  return std::fabs(a);
}

// Options as a global run sets them, in ground metres.
coast::Options ground_options(double h) { return coast::resolution_options(h); }

// Antarctica as a circle of latitude -75 (the ring holding the south pole).
std::vector<LonLat> polar_land() {
  std::vector<LonLat> r;
  for (int i = 0; i < 360; ++i) r.push_back({-180.0 + i, -75.0});
  return r;
}

// Two islands 20 km square with a channel of 1 km between them (narrower than the close width
// of 1.5 km) and a bay of 600 m by 6 km cut into one; an islet of 1 km^2 (below 0.3 hmin^2) 60 km
// away; all in metres around `at`.
std::vector<std::vector<LonLat>> archipelago(LonLat at) {
  std::vector<Point2> west = square(-21000, -10000, 20000);
  west.insert(west.begin() + 1, {{-11300, -10000}, {-11300, -4000}, {-10700, -4000}, {-10700, -10000}});
  return {ring_at(at, west), ring_at(at, square(0, -10000, 20000)), ring_at(at, square(80000, 0, 1000))};
}

}  // namespace

TEST(GlobalGeneralise, GroupsByReachOnTheSphere) {
  const LonLat at{30, 10};
  // reach 10 km: islands 5 km apart are one group, 30 km apart are not (and the sphere's far side
  // never joins them).
  const std::vector<std::vector<LonLat>> rings{ring_at(at, square(0, 0, 1000)), ring_at(at, square(6000, 0, 1000)),
                                               ring_at(at, square(37000, 0, 1000)),
                                               ring_at({-150, -10}, square(0, 0, 1000))};
  const auto g = land_groups(rings, 10000);
  ASSERT_EQ(g.size(), 3u);
  EXPECT_EQ(g[0], (std::vector<std::size_t>{0, 1}));
  EXPECT_EQ(g[1], (std::vector<std::size_t>{2}));
  EXPECT_EQ(g[2], (std::vector<std::size_t>{3}));
  EXPECT_EQ(land_groups(rings, 40000).size(), 2u);
}

// Coasts whose samples come within reach + gap (1.5 reach) but whose edges stay farther apart than
// the reach are two groups: two continents across a strait wider than the reach are generalised
// apart. Edges within reach join, whether their nearest points are vertices or inside edges.
TEST(GlobalGeneralise, GroupsByTheDistanceOfTheEdges) {
  const LonLat at{-20, 40};
  const double reach = 10000;
  // 12 km apart, face to face: samples within 15 km, edges not within 10 km.
  EXPECT_EQ(land_groups({ring_at(at, square(0, 0, 50000)), ring_at(at, square(62000, 0, 50000))}, reach).size(), 2u);
  // 9.5 km apart, the nearest points inside both edges (the second square shifted along the first).
  const auto g = land_groups({ring_at(at, square(0, 0, 50000)), ring_at(at, square(59500, 17000, 50000))}, reach);
  EXPECT_EQ(g.size(), 1u);
  // A corner 9.5 km from the middle of an edge, and 10.5 km.
  const std::vector<Point2> diamond{{0, 0}, {20000, -20000}, {40000, 0}, {20000, 20000}};
  auto shifted = [](std::vector<Point2> r, double dx, double dy) {
    for (Point2& p : r) p = {p.x + dx, p.y + dy};
    return r;
  };
  EXPECT_EQ(land_groups({ring_at(at, square(0, 0, 50000)), ring_at(at, shifted(diamond, 59500, 23000))}, reach).size(), 1u);
  EXPECT_EQ(land_groups({ring_at(at, square(0, 0, 50000)), ring_at(at, shifted(diamond, 60500, 23000))}, reach).size(), 2u);
}

TEST(GlobalGeneralise, SameLandIsGeneralisedAlikeNearTheEquatorAndNearThePole) {
  const double h = 10000;
  const coast::Options o = ground_options(h);
  // The global plane's scale factor 2 / (1 + sin(lat)) is 1.7 at 10 N and 14.9 at 60 S.
  const LonLat near_equator{30, 10}, near_pole{-60, -60};
  std::vector<std::vector<LonLat>> rings{polar_land()};
  for (const auto& r : archipelago(near_equator)) rings.push_back(r);
  for (const auto& r : archipelago(near_pole)) rings.push_back(r);
  const GeneralisedLand g = generalise_land(rings, {0, -90}, o, 0.1);
  EXPECT_EQ(g.groups, 5u);  // Antarctica; at each place the two islands and the islet
  // Rings by where they lie: the two islands joined across the channel and the islet a triangle
  // of side 0.7 hmin, at both places.
  std::vector<double> eq, po;
  std::size_t pole_rings = 0;
  for (std::size_t k = 0; k < g.rings.size(); ++k) {
    if (g.holds_pole[k]) {
      ++pole_rings;
      continue;
    }
    const double a = sphere_area(g.rings[k]);
    (g.rings[k][0].lat_deg > -30 ? eq : po).push_back(a);
  }
  EXPECT_EQ(pole_rings, 1u);
  ASSERT_EQ(eq.size(), 2u);
  ASSERT_EQ(po.size(), 2u);
  std::sort(eq.begin(), eq.end());
  std::sort(po.begin(), po.end());
  const double islet = std::sqrt(3.0) / 4 * 0.49 * h * h;  // the triangle, its corners rounded a little
  EXPECT_NEAR(eq[0], islet, 0.1 * islet);
  EXPECT_NEAR(po[0], eq[0], 0.001 * eq[0]);
  // The islands joined (one ring): 800 km^2 and the channel of 20 km^2, less rounded corners.
  EXPECT_GT(eq[1], 810e6);
  EXPECT_NEAR(po[1], eq[1], 0.001 * eq[1]);
  EXPECT_LT(g.max_scale, 1.1);
  EXPECT_GE(g.result.islets_replaced, 2u);
  // Every repair in lon/lat, at one of the two places (within 100 km of it).
  ASSERT_FALSE(g.result.repairs.empty());
  for (const auto& rep : g.result.repairs) {
    const Point3 u = unit_vector({rep.where.x, rep.where.y});
    const double d = std::min(great_circle(u, unit_vector(near_equator)), great_circle(u, unit_vector(near_pole)));
    EXPECT_LT(d, 100e3) << rep.kind << " at (" << rep.where.x << ", " << rep.where.y << ")";
  }
}

TEST(GlobalGeneralise, PoleWinding) {
  EXPECT_TRUE(winds_round_pole(polar_land()));
  const std::vector<LonLat> sq{{-10, 0}, {10, 0}, {10, 10}, {-10, 10}};
  EXPECT_FALSE(winds_round_pole(sq));
}
