// Fan insertions of the smoothing: fan_of counts a fixed vertex's triangles and angle; the
// insertions keep every invariant of the refined mesh and only lower the quality deficit.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "cdt/cdt.hpp"
#include "cdt/tests/test_inputs.hpp"
#include "mesh/check.hpp"
#include "refine/refine.hpp"
#include "refine/smooth_fan.hpp"
#include "refine/tests/fn_field.hpp"

using namespace fdr;
using fdr::testing::FnField;

namespace {

mesh::Triangulation refined(const pslg::Pslg& p, const sizing::SizingField& f, double B, double min_angle) {
  auto T = cdt::build_cdt(p, {cdt::CdtOptions::Regions::kSeeds, "test"});
  refine::RefineOptions o;
  o.bound = B;
  o.min_angle_deg = min_angle;
  refine::Refiner r(T, f, o);
  r.init();
  r.run();
  return T;
}

double deficit(const mesh::Triangulation& T) {
  double d = 0;
  for (TriangleId t = 0; t < T.num_slots(); ++t)
    if (!T.dead(t)) d += 1 - geom::mean_ratio_quality(T.point(T.corner(t, 0)), T.point(T.corner(t, 1)), T.point(T.corner(t, 2)));
  return d;
}

// Fixed vertices whose fan has fewer triangles than its angle over 60 degrees, rounded.
std::size_t short_fans(const mesh::Triangulation& T) {
  std::size_t n = 0;
  for (Index v = 0; v < T.num_vertices(); ++v) {
    if (T.kind(v) != mesh::VertexKind::kInput && T.kind(v) != mesh::VertexKind::kSegment) continue;
    const refine::Fan fan = refine::fan_of(T, v);
    n += fan.triangles > 0 && fan.triangles < std::lround(fan.angle_deg / 60.0);
  }
  return n;
}

std::size_t edges_shorter_than(const mesh::Triangulation& T, double l) {
  std::set<std::pair<Index, Index>> e;
  for (TriangleId t = 0; t < T.num_slots(); ++t) {
    if (T.dead(t)) continue;
    for (int k = 0; k < 3; ++k) {
      const Index a = T.corner(t, k), b = T.org(3 * t + (k + 1) % 3);
      if (dist(T.point(a), T.point(b)) < l) e.insert({std::min(a, b), std::max(a, b)});
    }
  }
  return e.size();
}

}  // namespace

// A wedge of 100 degrees without refinement: the CDT of its three corners is one triangle, so
// the corner at the origin has a fan of one triangle and 100 degrees (two would be nearer 60).
TEST(SmoothFan, FanOfCountsTrianglesAndAngle) {
  auto T = cdt::build_cdt(fdr::testing::wedge(100), {cdt::CdtOptions::Regions::kSeeds, "test"});
  const refine::Fan fan = refine::fan_of(T, 0);
  EXPECT_EQ(fan.triangles, 1);
  EXPECT_NEAR(fan.angle_deg, 100.0, 1e-9);
  EXPECT_NE(fan.widest, kNoId);
  EXPECT_EQ(T.org(fan.widest), Index{0});
}

// Random PSLGs refined with an angle bound: the insertions keep the mesh valid and constrained
// Delaunay with its constraints, R/f(c) <= B, the area and no new edge under f/2 (constant f), and
// lower the quality deficit (and, over all the meshes, the number of fans a triangle short).
TEST(SmoothFan, InsertionsKeepEveryInvariantAndLowerTheDeficit) {
  std::size_t added = 0, short_before = 0, short_after = 0;
  for (unsigned seed = 0; seed < 40; ++seed) {
    const auto p = fdr::testing::random_pslg(seed, 5 + seed % 40, static_cast<int>(seed % 12));
    const double h = 0.2 + 0.1 * (seed % 5);
    FnField f([h](Point2) { return h; });
    const double B = (seed % 3 == 0) ? 0.8 : 1.0;
    auto T = refined(p, f, B, 30.0);
    const double area = T.area(), d0 = deficit(T);
    const std::size_t short0 = short_fans(T), edges0 = edges_shorter_than(T, 0.5 * h);
    refine::FanOptions o;
    o.bound = B;
    o.min_angle_deg = 30;
    added += refine::insert_fan_vertices(T, f, o);
    const auto r = mesh::check_all(T);
    ASSERT_TRUE(r.ok()) << "seed " << seed << ": " << (r.problems.empty() ? "" : r.problems[0]);
    EXPECT_LE(fdr::testing::max_r_over_f(T, f), B * (1 + 1e-12)) << seed;
    EXPECT_NEAR(T.area(), area, 1e-9 * area) << seed;
    EXPECT_LE(deficit(T), d0) << seed;
    short_before += short0;
    short_after += short_fans(T);
    EXPECT_LE(edges_shorter_than(T, 0.5 * h), edges0) << seed;
  }
  EXPECT_GT(added, 20u);  // the test exercises the insertions
  // A cavity may take an edge from a neighbouring fixed vertex's fan, so one mesh's count may
  // rise; over all of them the fans a triangle short become fewer.
  EXPECT_LT(short_after, short_before);
}
