// The sphere of global runs: the stereographic projection against PROJ, lon/lat rings on the
// sphere, great-circle lengths against an independent haversine, spacing on the sphere, the
// mesh measure, and the water of the shared GSHHG land file (skipped when absent).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <random>
#include <iostream>

#include "base/error.hpp"
#include "gis/crs.hpp"
#include "gis/global_domain.hpp"
#include "gis/global_measure.hpp"
#include "gis/global_spacing.hpp"
#include "gis/global_sphere.hpp"

using namespace fdr;
using namespace fdr::gis;

namespace {
constexpr double kPi = std::numbers::pi;
constexpr double kR = kEarthRadius;

// Haversine, written independently of global_sphere.cpp.
double haversine(LonLat a, LonLat b) {
  const double p1 = a.lat_deg * kPi / 180, p2 = b.lat_deg * kPi / 180;
  const double dp = p2 - p1, dl = (b.lon_deg - a.lon_deg) * kPi / 180;
  const double h = std::sin(dp / 2) * std::sin(dp / 2) + std::cos(p1) * std::cos(p2) * std::sin(dl / 2) * std::sin(dl / 2);
  return 2 * kR * std::asin(std::min(1.0, std::sqrt(h)));
}
}  // namespace

TEST(GlobalSphere, StereoMatchesProjAndRoundTrips) {
  for (const LonLat pole : {LonLat{0, -90}, LonLat{30, -80}, LonLat{-120, -75}}) {
    const SphereStereo s(pole);
    const Frame f = Frame::from_crs(s.proj_string(), {0, 0});
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> lon(-180, 180), lat(-60, 89);
    for (int k = 0; k < 200; ++k) {
      const LonLat ll{lon(rng), lat(rng)};
      const Point2 p = s.forward(ll);
      const Point2 q = f.lonlat_to_local(ll);
      EXPECT_NEAR(p.x, q.x, 1e-6 * std::max(1e6, std::hypot(p.x, p.y)));
      EXPECT_NEAR(p.y, q.y, 1e-6 * std::max(1e6, std::hypot(p.x, p.y)));
      const LonLat back = s.inverse(p);
      EXPECT_LT(haversine(back, ll), 1e-3);
      EXPECT_NEAR(s.scale(p), f.scale_factor(p), 1e-6 * s.scale(p));
    }
  }
  const SphereStereo s;
  EXPECT_NEAR(s.scale(s.forward({10, 0})), 2.0, 1e-12);  // 2 / (1 + sin 0) at the equator
  EXPECT_NEAR(s.scale(s.forward({0, 90})), 1.0, 1e-12);
  EXPECT_FALSE(std::isfinite(s.forward({0, -90}).x) && std::hypot(s.forward({0, -90}).x, s.forward({0, -90}).y) < 1e20);
}

TEST(GlobalSphere, GreatCircleAgreesWithHaversine) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> lon(-180, 180), lat(-89, 89), d(-0.5, 0.5);
  for (int k = 0; k < 1000; ++k) {
    const LonLat a{lon(rng), lat(rng)};
    const LonLat b = k % 2 ? LonLat{lon(rng), lat(rng)} : LonLat{a.lon_deg + d(rng), std::clamp(a.lat_deg + d(rng), -90.0, 90.0)};
    EXPECT_NEAR(great_circle(a, b), haversine(a, b), 1e-6 + 1e-9 * haversine(a, b));
  }
  // An octant: area 4 pi R^2 / 8, circumradius = the distance from (1,1,1)/sqrt 3 to a vertex.
  const Point3 x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};
  EXPECT_NEAR(spherical_triangle_area(x, y, z), 0.5 * kPi * kR * kR, 1e-6 * kR * kR);
  EXPECT_NEAR(spherical_triangle_area(x, z, y), -0.5 * kPi * kR * kR, 1e-6 * kR * kR);
  EXPECT_NEAR(spherical_circumradius(x, y, z), kR * std::acos(1 / std::sqrt(3.0)), 1e-6);
}

TEST(GlobalDomain, SphereRingJoinsTheCutAndDropsThePoleClosure) {
  // Antarctica as GSHHG-style files store it: the coast from the cut at +180 round to -180, then
  // down the meridian to the pole, along latitude -90 and back up to the coast.
  std::vector<LonLat> ring = {{180, -78}, {90, -66}, {0, -70}, {-90, -72}, {-180, -78},
                              {-180, -85}, {-180, -90}, {0, -90}, {180, -90}, {180, -85}};
  const std::vector<LonLat> s = sphere_ring(ring);
  ASSERT_EQ(s.size(), 4u);
  for (const LonLat& p : s) EXPECT_GT(p.lat_deg, -80);
  EXPECT_TRUE(ring_holds_pole(ring, {0, -90}));
  EXPECT_FALSE(ring_holds_pole(s, {0, -90}));
  // A spike in the middle and one across the start are both removed.
  const std::vector<LonLat> spiky = {{0, 0}, {1, 0}, {2, 0}, {3, 3}, {2, 0}, {1, 1}, {0, 1}};
  EXPECT_EQ(sphere_ring(spiky).size(), 5u);
  EXPECT_EQ(sphere_ring({{5, 5}, {0, 0}, {1, 0}, {1, 1}, {0, 0}}).size(), 3u);
  EXPECT_TRUE(sphere_ring({{0, 0}, {1, 0}, {0, 0}}).empty());
  EXPECT_TRUE(ring_holds_pole({{0, 0}, {10, 0}, {10, 10}, {0, 10}}, {5, 5}));
  EXPECT_FALSE(ring_holds_pole({{0, 0}, {10, 0}, {10, 10}, {0, 10}}, {15, 5}));
  std::vector<LonLat> d = {{0, 0}, {1, 0}, {1, 1}};
  EXPECT_EQ(densify_lonlat(d, 0.25), 3u + 3u + 3u);
  std::vector<LonLat> cut = {{179.5, 0}, {-179.5, 0}, {-179.5, 1}};  // across the antimeridian
  EXPECT_EQ(densify_lonlat(cut, 0.25), 3u + 3u + 3u);
  EXPECT_EQ(cut[1].lon_deg, 179.75);
  EXPECT_EQ(cut[2].lon_deg, 180.0);
  EXPECT_EQ(cut[3].lon_deg, -179.75);
}

TEST(GlobalSpacing, DistanceAndLimiterOnTheSphere) {
  LonLatGrid g = lonlat_grid(2.0, -90, 90, 0);
  std::vector<Point3> shore;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> lon(-180, 180), lat(-80, 80);
  for (int k = 0; k < 40; ++k) shore.push_back(unit_vector({lon(rng), lat(rng)}));
  distance_to_shore_sphere(g, shore);
  double worst = 0;
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i) {
      double best = 1e300;
      for (const Point3& s : shore) best = std::min(best, great_circle(unit_vector(g.centre(i, j)), s));
      const double got = g.v[j * g.nx + i];
      EXPECT_GE(got, best * (1 - 1e-12));
      worst = std::max(worst, got - best);
    }
  EXPECT_LT(worst, 3 * 2.0 * kPi / 180 * kR);  // within a few cells of the exact distance
  // The limiter: never above the input, alpha-Lipschitz (chord) between neighbouring cells.
  LonLatGrid h = lonlat_grid(3.0, -90, 90, 5e6);
  h.v[h.nx * 20 + 7] = 1e4;
  h.v[h.nx * 40 + 100] = 2e4;
  const std::vector<double> before = h.v;
  limit_gradient_sphere(h, 0.2);
  for (std::size_t j = 0; j < h.ny; ++j)
    for (std::size_t i = 0; i < h.nx; ++i) {
      const std::size_t c = j * h.nx + i;
      EXPECT_LE(h.v[c], before[c]);
      for (const auto& [di, dj] : {std::pair{1, 0}, std::pair{0, 1}, std::pair{1, 1}}) {
        const std::size_t i2 = (i + di) % h.nx, j2 = j + dj;
        if (j2 >= h.ny) continue;
        const double d = kR * dist(unit_vector(h.centre(i, j)), unit_vector(h.centre(i2, j2)));
        EXPECT_LE(std::fabs(h.v[c] - h.v[j2 * h.nx + i2]), 0.2 * d * (1 + 1e-9) + 1e-6);
      }
    }
}

TEST(GlobalSpacing, PlaneCircleOfRadiusBfIsASphereCircleOfRadiusBg) {
  for (const double g : {1e4, 1e5, 1e6}) {
    auto grid = std::make_shared<LonLatGrid>(lonlat_grid(1.0, -90, 90, g));
    const SphereStereo proj;
    for (const double bound : {1.0, 0.7}) {
      const StereoSpacing f(grid, proj, 0.15, 2e8, bound, "test");
      for (const double lat : {80.0, 30.0, 0.0, -40.0, -60.0, -75.0}) {
        const Point2 c = proj.forward({25, lat});
        const double r = bound * f(c), a = std::hypot(c.x, c.y);
        // The plane circle's nearest and farthest points from the centre of projection are the
        // ends of a diameter of its image on the sphere.
        const Point2 u{c.x / a, c.y / a};
        const LonLat p1 = proj.inverse({(a - r) * u.x, (a - r) * u.y}), p2 = proj.inverse({(a + r) * u.x, (a + r) * u.y});
        // Its radius is B g, less alpha times the offset of its centre (zero at the centre).
        EXPECT_LE(haversine(p1, p2), 2 * bound * g * (1 + 1e-9)) << "g " << g << " lat " << lat;
        EXPECT_GE(haversine(p1, p2), 2 * bound * g * (1 - 0.15 * 1.05 * 0.5 * g / kR * 40)) << "g " << g << " lat " << lat;
        EXPECT_NEAR(f(c) / (proj.scale(c) * g), 1.0, g / kR * 2);  // k g for g << R
      }
    }
  }
}

TEST(GlobalMeasure, OctahedronClosesAndMatchesHaversine) {
  // The octahedron's 6 vertices on the sphere, projected from the south pole's antipode plane.
  const SphereStereo proj({0, -89});  // pole beside a vertex: every vertex projects finitely
  const std::vector<LonLat> ll = {{0, 0}, {90, 0}, {180, 0}, {-90, 0}, {0, 90}, {0, -90}};
  std::vector<Point2> v;
  for (const LonLat& p : ll) v.push_back(proj.forward(p));
  // Counter-clockwise seen from outside: north faces (a, b, N), south faces (b, a, S).
  std::vector<std::array<Index, 3>> t;
  for (Index k = 0; k < 4; ++k) {
    t.push_back({k, static_cast<Index>((k + 1) % 4), 4});
    t.push_back({static_cast<Index>((k + 1) % 4), k, 5});
  }
  SphereMeshInput in;
  in.vertices = &v;
  in.triangles = &t;
  in.proj = &proj;
  in.hmin = 1e6;
  const SphereMeasure s = measure_on_sphere(in);
  EXPECT_TRUE(s.closed());
  EXPECT_EQ(s.boundary_edges, 0u);
  EXPECT_EQ(s.edges, 12u);
  EXPECT_EQ(s.negative_triangles, 0u);
  EXPECT_NEAR(s.area_m2, 4 * kPi * kR * kR, 1e-6 * kR * kR);
  EXPECT_NEAR(s.shortest_edge_m, haversine(ll[0], ll[1]), 1e-3);
  EXPECT_NEAR(s.longest_edge_m, haversine(ll[0], ll[4]), 1e-3);
  EXPECT_NEAR(s.min_angle_deg, 60, 1e-9);
  // One triangle less: its three edges are boundary edges that are no coast.
  t.pop_back();
  EXPECT_EQ(measure_on_sphere(in).boundary_edges_not_coast, 3u);
}

TEST(GlobalDomain, SharedGshhgLowIsOneOceanBoundedByAntarctica) {
  const std::string path = std::string(FDR_SHARED_DATA_DIR) + "/global/gshhg_land_l.gpkg";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "shared data not present: " << path;
  const SphereStereo proj;
  const auto t0 = std::chrono::steady_clock::now();
  const GlobalWater w = global_water({path, "", ""}, "", proj, 0.1);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(w.land_polygons, 5745u);
  EXPECT_EQ(w.land_holes_filled, 1u);
  EXPECT_GE(w.antimeridian_rings, 8u);
  ASSERT_GE(w.polygons.size(), 1u);

  // Antarctica's coast bounds the largest water polygon; every other land polygon is a hole
  // (those joined across the antimeridian once).
  std::size_t holes = 0;
  for (const auto& p : w.polygons) holes += p.size() - 1;
  EXPECT_GT(holes, 5700u);
  EXPECT_LT(holes, 5745u);
  // Ocean = sphere minus land (148.69 M km^2 geodesic on WGS 84; the sphere differs slightly).
  const double ocean = w.water_area_m2 / 1e6, sphere = 4 * kPi * kR * kR / 1e6;
  EXPECT_NEAR(sphere - ocean, 148.69e6, 0.01 * 148.69e6);
  RecordProperty("seconds", std::to_string(s));
}
