// Quality smoothing keeps every invariant of the refined mesh: valid, constrained Delaunay,
// constraints present, R/f(c) <= B, the area; it raises the summed quality; it is deterministic.
#include <gtest/gtest.h>

#include <cmath>

#include "cdt/cdt.hpp"
#include "cdt/tests/test_inputs.hpp"
#include "mesh/check.hpp"
#include "predicates/predicates.hpp"
#include "refine/refine.hpp"
#include "refine/smooth.hpp"
#include "refine/tests/fn_field.hpp"

using namespace fdr;
using fdr::testing::FnField;

namespace {
using fdr::testing::max_r_over_f;

double quality_sum(const mesh::Triangulation& T) {
  double s = 0;
  for (TriangleId t = 0; t < T.num_slots(); ++t) {
    if (T.dead(t)) continue;
    const Point2 a = T.pts[T.tv[3 * t]], b = T.pts[T.tv[3 * t + 1]], c = T.pts[T.tv[3 * t + 2]];
    const double ar = 0.5 * ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
    s += 6.928203230275509 * ar / (norm2(b - a) + norm2(c - b) + norm2(a - c));
  }
  return s;
}

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

}  // namespace

// Random PSLGs (holes, interior segments, graded f): many moves are tried, many undone after
// chains of flips; every one must leave the constrained Delaunay triangulation intact.
TEST(Smooth, RandomPslgsKeepEveryInvariant) {
  std::size_t moves = 0;
  for (unsigned seed = 0; seed < 60; ++seed) {
    const auto p = fdr::testing::random_pslg(seed, 5 + seed % 40, static_cast<int>(seed % 12));
    const double h = 0.2 + 0.1 * (seed % 5);
    FnField f([h](Point2 q) { return h * (1 + 0.08 * q.x + 0.03 * std::sin(3 * q.y)); });
    const double B = (seed % 3 == 0) ? 0.8 : 1.0;
    auto T = refined(p, f, B, seed % 2 ? 25.0 : 0.0);
    const double area = T.area(), q0 = quality_sum(T);
    refine::SmoothOptions so;
    so.passes = 4;
    so.bound = B;
    so.min_angle_deg = 25;
    const auto st = refine::smooth(T, f, so);
    moves += st.moves;
    const auto r = mesh::check_all(T);
    ASSERT_TRUE(r.ok()) << "seed " << seed << ": " << (r.problems.empty() ? "" : r.problems[0]);
    EXPECT_LE(max_r_over_f(T, f), B * (1 + 1e-12)) << seed;
    EXPECT_NEAR(T.area(), area, 1e-9 * area) << seed;
    EXPECT_GE(quality_sum(T), q0) << seed;
  }
  EXPECT_GT(moves, 1000u);  // the test exercises the smoother
}

TEST(Smooth, Deterministic) {
  const auto p = fdr::testing::random_pslg(11, 40, 6);
  FnField f([](Point2 q) { return 0.25 * (1 + 0.1 * q.x); });
  auto run = [&] {
    auto T = refined(p, f, 1.0, 30.0);
    refine::SmoothOptions so;
    so.min_angle_deg = 30;
    refine::smooth(T, f, so);
    return T.to_view();
  };
  const auto a = run(), b = run();
  ASSERT_EQ(a.triangles, b.triangles);
  ASSERT_EQ(a.vertices.size(), b.vertices.size());
  for (std::size_t i = 0; i < a.vertices.size(); ++i) ASSERT_EQ(a.vertices[i], b.vertices[i]);
}
