// Coast deviation on the sphere: the distance to an arc against dense sampling, the index against
// brute force, and the deviation between rings a known angle apart.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "gis/global_coast.hpp"

using namespace fdr;
using namespace fdr::gis;

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

Point3 unit(double lon, double lat) { return unit_vector({lon, lat}); }

double angle(Point3 u, Point3 v) { return std::atan2(std::sqrt(norm2(cross(u, v))), dot(u, v)); }

Point3 random_unit(std::mt19937& rng) {
  std::normal_distribution<double> g;
  const Point3 p{g(rng), g(rng), g(rng)};
  return (1.0 / std::sqrt(norm2(p))) * p;
}

// An arc from a random point, of a random length up to `max_deg`, in a random direction.
SphereArc random_arc(std::mt19937& rng, double max_deg) {
  const Point3 a = random_unit(rng);
  Point3 t = cross(a, random_unit(rng));
  t = (1.0 / std::sqrt(norm2(t))) * t;
  const double th = std::uniform_real_distribution<double>(0.0, max_deg * kDeg)(rng);
  return {a, std::cos(th) * a + std::sin(th) * t};
}

// The angle to the arc by its points at `n` equal steps (an upper bound, within half a step).
double sampled_distance(Point3 p, const SphereArc& s, int n) {
  double best = std::numeric_limits<double>::infinity();
  for (const Point3& q : sample_arcs({s}, angle(s.a, s.b) / n)) best = std::min(best, angle(p, q));
  return std::min(best, angle(p, s.b));
}

TEST(GlobalCoast, ArcDistanceKnownCases) {
  const Point3 a = unit(0, 0), b = unit(90, 0);
  EXPECT_NEAR(arc_distance(unit(45, 0), a, b), 0.0, 1e-15);
  EXPECT_NEAR(arc_distance(unit(30, 20), a, b), 20 * kDeg, 1e-14);   // foot on the arc: the latitude
  EXPECT_NEAR(arc_distance(unit(0, 90), a, b), 90 * kDeg, 1e-14);    // the pole of the great circle
  EXPECT_NEAR(arc_distance(unit(120, 0), a, b), 30 * kDeg, 1e-14);   // beyond b: the distance to b
  EXPECT_NEAR(arc_distance(unit(-10, 10), a, b), angle(unit(-10, 10), a), 1e-15);
  EXPECT_NEAR(arc_distance(unit(10, 5), a, a), angle(unit(10, 5), a), 1e-15);  // a degenerate arc
}

TEST(GlobalCoast, ArcDistanceAgainstDenseSampling) {
  std::mt19937 rng(7);
  for (int i = 0; i < 300; ++i) {
    const SphereArc s = random_arc(rng, i % 2 ? 60.0 : 0.5);
    const Point3 p = random_unit(rng);
    const double exact = arc_distance(p, s.a, s.b), sampled = sampled_distance(p, s, 4000);
    EXPECT_LE(exact, sampled + 1e-12);
    EXPECT_LE(sampled - exact, angle(s.a, s.b) / 4000 + 1e-12) << i;
  }
}

TEST(GlobalCoast, IndexEqualsBruteForce) {
  std::mt19937 rng(11);
  std::vector<SphereArc> arcs;
  for (int i = 0; i < 3000; ++i) arcs.push_back(random_arc(rng, i % 100 == 0 ? 120.0 : 0.3));
  const ArcIndex index(arcs);
  for (int i = 0; i < 500; ++i) {
    // Points near an arc and anywhere.
    const Point3 p = i % 2 ? random_unit(rng) : arcs[static_cast<std::size_t>(i) % arcs.size()].a;
    double brute = std::numeric_limits<double>::infinity();
    for (const SphereArc& s : arcs) brute = std::min(brute, arc_distance(p, s.a, s.b));
    EXPECT_EQ(index.nearest(p), brute) << i;
  }
  EXPECT_EQ(ArcIndex({}).nearest(unit(0, 0)), std::numeric_limits<double>::infinity());
}

// A ring of n arcs along the parallel `lat`, lon from lon0 to lon0 + 360.
std::vector<SphereArc> parallel_ring(double lat, int n, double lon0 = 0) {
  std::vector<SphereArc> out;
  for (int i = 0; i < n; ++i)
    out.push_back({unit(lon0 + 360.0 * i / n, lat), unit(lon0 + 360.0 * (i + 1) / n, lat)});
  return out;
}

TEST(GlobalCoast, DeviationBetweenParallels) {
  // Rings along 40 N and 40.5 N, 2000 arcs each (the arcs bulge poleward of the parallel by under
  // 20 m): every point of one is half a degree of latitude from the other.
  const auto a = parallel_ring(40, 2000), b = parallel_ring(40.5, 2000, 0.07);
  const double half_deg = 0.5 * kDeg * kEarthRadius;
  const SphereDeviation d = sphere_deviation(a, b, 5000);
  EXPECT_GT(d.samples, 2000u);
  EXPECT_NEAR(d.max_m, half_deg, 40.0);
  EXPECT_NEAR(d.p99_m, half_deg, 40.0);
  EXPECT_NEAR(d.max_at.lat_deg, 40, 0.01);
  const SphereDeviation same = sphere_deviation(a, a, 5000);
  EXPECT_LT(same.max_m, 1e-6);
}

TEST(GlobalCoast, P99IgnoresOnePercentOfOutliers) {
  // 1000 arcs on the equator, the other side along it except for 5 arcs bent 1 degree north: the
  // samples on those (about 0.5 %) are the maximum, not the p99.
  std::vector<SphereArc> to = parallel_ring(0, 1000), from = to;
  for (int i = 0; i < 5; ++i) from[static_cast<std::size_t>(i)] = {unit(360.0 * i / 1000, 1), unit(360.0 * i / 1000, 1)};
  const SphereDeviation d = sphere_deviation(from, to, 0);
  EXPECT_EQ(d.samples, 1000u);
  EXPECT_NEAR(d.max_m, kDeg * kEarthRadius, 1e-6);
  EXPECT_LT(d.p99_m, 1e-6);
}

// Input rings along 40 N (a counterpart half a degree away) and 10 N and 70 N (none within 2
// degrees): the two far rings are left out and counted, the deviation is that of the ring at 40 N
// alone; with everything kept, the far rings decide the maximum.
TEST(GlobalCoast, KeptRingsLeaveOutRingsWithoutCounterpart) {
  auto closed = [](std::vector<SphereArc> r) {  // the last arc ends exactly where the first starts
    r.back().b = r.front().a;
    return r;
  };
  const auto near = closed(parallel_ring(40, 500)), mesh = parallel_ring(40.5, 500, 0.07);
  std::vector<SphereArc> input = closed(parallel_ring(10, 300));
  input.insert(input.end(), near.begin(), near.end());
  const auto polar = closed(parallel_ring(70, 200));
  input.insert(input.end(), polar.begin(), polar.end());
  const double half_deg = 0.5 * kDeg * kEarthRadius, keep = 2 * kDeg * kEarthRadius;
  std::size_t lost = 99;
  const SphereDeviation kept = sphere_deviation_kept(input, mesh, 5000, keep, &lost);
  EXPECT_EQ(lost, 2u);
  const SphereDeviation alone = sphere_deviation(near, mesh, 5000);
  EXPECT_EQ(kept.samples, alone.samples);
  EXPECT_EQ(kept.max_m, alone.max_m);
  EXPECT_EQ(kept.p99_m, alone.p99_m);
  EXPECT_NEAR(kept.max_m, half_deg, 100.0);
  EXPECT_GT(sphere_deviation(input, mesh, 5000).max_m, 29 * kDeg * kEarthRadius);
  // A far ring with one vertex within keep_m is kept whole.
  input.push_back({unit(0, 40.6), unit(10, 70)});
  input.push_back({unit(10, 70), unit(0, 70)});
  input.push_back({unit(0, 70), unit(0, 40.6)});
  EXPECT_GT(sphere_deviation_kept(input, mesh, 5000, keep, &lost).max_m, 20 * kDeg * kEarthRadius);
  EXPECT_EQ(lost, 2u);
}

}  // namespace
