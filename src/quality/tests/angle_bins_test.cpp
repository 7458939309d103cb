// Issue 7: the report's angle figures (min/max angle, both histograms) measured without atan2 for
// most triangles must equal the atan2 measurement of every triangle (the previous implementation,
// written out here), also on angles exactly at bin edges, right angles, slivers and flat triangles.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "quality/report.hpp"

namespace fdr::quality {
namespace {

constexpr double kDeg = 180.0 / std::numbers::pi;

double angle_at(Point2 apex, Point2 p, Point2 q) {  // as report.cpp
  const Point2 u = p - apex, v = q - apex;
  return std::atan2(std::fabs(u.x * v.y - u.y * v.x), dot(u, v)) * kDeg;
}

struct Reference {
  double min_deg = 1e300, max_deg = -1e300;
  Histogram lo{0.0, 5.0, std::vector<std::uint64_t>(12, 0)}, hi{60.0, 5.0, std::vector<std::uint64_t>(24, 0)};
};

Reference reference(const mesh::MeshView& m) {
  Reference r;
  for (const auto& t : m.triangles) {
    const Point2 a = m.vertices[t[0]], b = m.vertices[t[1]], c = m.vertices[t[2]];
    const double ang[3] = {angle_at(a, b, c), angle_at(b, c, a), angle_at(c, a, b)};
    const double amin = std::min({ang[0], ang[1], ang[2]}), amax = std::max({ang[0], ang[1], ang[2]});
    r.min_deg = std::min(r.min_deg, amin);
    r.max_deg = std::max(r.max_deg, amax);
    r.lo.add(amin);
    r.hi.add(amax);
  }
  return r;
}

void expect_same(const mesh::MeshView& m) {
  const Reference ref = reference(m);
  const QualityReport r = compute_quality(m, nullptr, 1.0, -1, RunInfo{});
  ASSERT_TRUE(r.min_angle_deg && r.max_angle_deg);
  EXPECT_EQ(*r.min_angle_deg, ref.min_deg);  // bit for bit
  EXPECT_EQ(*r.max_angle_deg, ref.max_deg);
  EXPECT_EQ(r.min_angle_histogram.counts, ref.lo.counts);
  EXPECT_EQ(r.max_angle_histogram.counts, ref.hi.counts);
  // With per-triangle values (the writers'): the same figures, and each triangle's smallest angle
  // equal to the smallest of its three atan2 angles (atan2 only where the smallest may be).
  TriangleValues tv;
  const QualityReport rt = compute_quality(m, nullptr, 1.0, -1, RunInfo{}, &tv);
  EXPECT_EQ(*rt.min_angle_deg, ref.min_deg);
  EXPECT_EQ(*rt.max_angle_deg, ref.max_deg);
  EXPECT_EQ(rt.min_angle_histogram.counts, ref.lo.counts);
  EXPECT_EQ(rt.max_angle_histogram.counts, ref.hi.counts);
  ASSERT_EQ(tv.min_angle_deg.size(), m.triangles.size());
  std::size_t wrong = 0;
  for (std::size_t i = 0; i < m.triangles.size(); ++i) {
    const auto& t = m.triangles[i];
    const Point2 a = m.vertices[t[0]], b = m.vertices[t[1]], c = m.vertices[t[2]];
    const double amin = std::min({angle_at(a, b, c), angle_at(b, c, a), angle_at(c, a, b)});
    wrong += !(tv.min_angle_deg[i] == amin || (std::isnan(amin) && std::isnan(tv.min_angle_deg[i])));
  }
  EXPECT_EQ(wrong, 0u);
}

// One triangle per entry: apex at the origin, base along x, the angle at the origin `deg`.
mesh::MeshView fan(const std::vector<double>& degs, double scale) {
  mesh::MeshView m;
  for (double d : degs) {
    const Index o = static_cast<Index>(m.vertices.size());
    const double r = d / kDeg;
    m.vertices.push_back({0, 0});
    m.vertices.push_back({scale, 0});
    m.vertices.push_back({scale * 0.8 * std::cos(r), scale * 0.8 * std::sin(r)});
    m.triangles.push_back({o, o + 1, o + 2});
  }
  return m;
}

TEST(AngleBins, AnglesAtEveryBinEdgeAndBetween) {
  std::vector<double> degs;
  for (int k = 1; k < 180; ++k) {
    const double d = k;
    degs.push_back(d);
    degs.push_back(std::nextafter(d, 0.0));
    degs.push_back(std::nextafter(d, 200.0));
    degs.push_back(d + 1e-12);
    degs.push_back(d - 1e-10);
  }
  for (double s : {1.0, 1e-6, 3e5}) expect_same(fan(degs, s));
}

TEST(AngleBins, EquilateralRightAndGridTriangles) {
  mesh::MeshView m;
  const double h = std::sqrt(3.0) / 2;
  m.vertices = {{0, 0}, {1, 0}, {0.5, h}, {0, 1}, {1, 1}, {2, 0}, {2, 1}};
  m.triangles = {{0, 1, 2}, {0, 1, 4}, {0, 4, 3}, {1, 5, 6}, {1, 6, 4}};
  expect_same(m);
}

TEST(AngleBins, SliversAndFlatTriangles) {
  mesh::MeshView m;
  m.vertices = {{0, 0}, {1, 0}, {0.5, 1e-9}, {0.5, 0}, {2, 1e-300}, {1e-200, 5e-201}};
  m.triangles = {{0, 1, 2}, {0, 1, 3}, {0, 4, 1}, {0, 1, 5}};
  expect_same(m);
}

TEST(AngleBins, RandomTrianglesOfEveryShape) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  mesh::MeshView m;
  for (int i = 0; i < 200000; ++i) {
    const double s = std::pow(10.0, 6 * u(rng));
    const Point2 a{u(rng) * s + 1e4, u(rng) * s}, b{u(rng) * s + 1e4, u(rng) * s}, c{u(rng) * s + 1e4, u(rng) * s};
    const Index o = static_cast<Index>(m.vertices.size());
    m.vertices.insert(m.vertices.end(), {a, b, c});
    m.triangles.push_back({o, o + 1, o + 2});
  }
  expect_same(m);
}

// Two (or three) corners with the same smallest angle up to rounding or a tiny perturbation:
// isosceles triangles with an apex above the base's midpoint moved by 0 to 1e-6, nearly
// equilateral ones, at several scales and offsets (the per-triangle smallest angle takes atan2
// at every corner that may hold it).
TEST(AngleBins, NearTiesForTheSmallestAngle) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  mesh::MeshView m;
  const double eps[] = {0.0, 1e-16, 1e-15, 1e-13, 1e-11, 1e-9, 1e-8, 1e-7, 1e-6};
  for (int i = 0; i < 20000; ++i) {
    const double s = std::pow(10.0, 3 * u(rng)), off = 1e5 * u(rng);
    const double height = i % 3 == 0 ? std::sqrt(3.0) / 2 : 0.2 + 1.5 * (u(rng) + 1);
    const double e = eps[i % 9] * (u(rng) > 0 ? 1 : -1);
    const Index o = static_cast<Index>(m.vertices.size());
    m.vertices.push_back({off, off});
    m.vertices.push_back({off + s, off});
    m.vertices.push_back({off + s * (0.5 + e), off + s * height});
    m.triangles.push_back({o, o + 1, o + 2});
  }
  expect_same(m);
}

// Grid-snapped points: many exactly right, 45 and bin-edge-free angles, and repeated extremes.
TEST(AngleBins, SnappedPoints) {
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<int> u(0, 20);
  mesh::MeshView m;
  for (int i = 0; i < 50000; ++i) {
    const Index o = static_cast<Index>(m.vertices.size());
    for (int k = 0; k < 3; ++k) m.vertices.push_back({static_cast<double>(u(rng)), static_cast<double>(u(rng))});
    m.triangles.push_back({o, o + 1, o + 2});
  }
  expect_same(m);
}

}  // namespace
}  // namespace fdr::quality
