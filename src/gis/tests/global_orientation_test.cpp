// The stereographic plane of global runs keeps orientation: a triangle counter-clockwise in the
// plane is counter-clockwise seen from outside the sphere (its normal points away from the centre),
// which is what the VTU and msh outputs on the sphere rely on, for the default and oblique poles.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "gis/global_sphere.hpp"

using namespace fdr;
using namespace fdr::gis;

namespace {

double min_angle_deg(Point2 a, Point2 b, Point2 c) {
  auto at = [](Point2 p, Point2 q, Point2 r) {
    const double ux = q.x - p.x, uy = q.y - p.y, vx = r.x - p.x, vy = r.y - p.y;
    return std::atan2(std::abs(ux * vy - uy * vx), ux * vx + uy * vy) * 180 / std::numbers::pi;
  };
  return std::min({at(a, b, c), at(b, c, a), at(c, a, b)});
}

TEST(GlobalOrientation, CounterClockwiseInThePlaneIsOutwardOnTheSphere) {
  std::mt19937 rng(3);
  for (const LonLat pole : {LonLat{0, -90}, LonLat{10, -80}, LonLat{-150, -45}, LonLat{100, 30}}) {
    const SphereStereo proj(pole);
    std::uniform_real_distribution<double> coord(-3e7, 3e7), step(-2e5, 2e5);
    int tried = 0, outward = 0;
    for (int i = 0; i < 2000; ++i) {
      const Point2 a{coord(rng), coord(rng)};
      Point2 b{a.x + step(rng), a.y + step(rng)}, c{a.x + step(rng), a.y + step(rng)};
      const double plane = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
      // Nearly flat triangles are left out: the plane's straight edges are not the images of great
      // circles, so a vertex close to the opposite side can fall on its other side on the sphere
      // (the report counts such triangles: sphere_negative_triangles). Kept: every angle >= 5 deg.
      if (min_angle_deg(a, b, c) < 5) continue;
      if (plane < 0) std::swap(b, c);
      const Point3 pa = sphere_xyz(proj.inverse(a)), pb = sphere_xyz(proj.inverse(b)), pc = sphere_xyz(proj.inverse(c));
      ++tried;
      outward += dot(cross(pb - pa, pc - pa), pa + pb + pc) > 0;
    }
    EXPECT_GT(tried, 1000);
    EXPECT_EQ(outward, tried) << "pole " << pole.lon_deg << ", " << pole.lat_deg;
  }
}

}  // namespace
