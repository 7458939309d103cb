// Quality smoothing keeps every invariant of the refined mesh: valid, constrained Delaunay,
// constraints present, R/f(c) <= B, the area; it raises the summed quality; it is deterministic.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <map>
#include <set>
#include <string>

#include "cdt/cdt.hpp"
#include "cdt/tests/test_inputs.hpp"
#include "mesh/check.hpp"
#include "predicates/predicates.hpp"
#include "refine/refine.hpp"
#include "refine/smooth.hpp"
#include "refine/tests/fn_field.hpp"
#include "base/tests/scoped_env.hpp"

using namespace fdr;
using fdr::testing::FnField;

namespace {
using fdr::testing::max_r_over_f;

double quality_sum(const mesh::Triangulation& T) {
  double s = 0;
  for (TriangleId t = 0; t < T.num_slots(); ++t) {
    if (T.dead(t)) continue;
    const Point2 a = T.point(T.corner(t, 0)), b = T.point(T.corner(t, 1)), c = T.point(T.corner(t, 2));
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

using fdr::ThreadsEnv;

}  // namespace

// Random PSLGs (holes, interior segments, graded f): many moves are tried, many undone after
// chains of flips; every one must leave the constrained Delaunay triangulation intact.
TEST(Smooth, RandomPslgsKeepEveryInvariant) {
  std::size_t moves = 0, deferred = 0;
  for (unsigned seed = 0; seed < 60; ++seed) {
    const auto p = fdr::testing::random_pslg(seed, 5 + seed % 40, static_cast<int>(seed % 12));
    const double h = 0.2 + 0.1 * (seed % 5);
    // Half the seeds tell the smoother f's Lipschitz constant (|grad f| <= h sqrt(0.08^2 + 0.09^2)):
    // then R/f(c) <= B is mostly decided from f at the moved vertex.
    FnField f([h](Point2 q) { return h * (1 + 0.08 * q.x + 0.03 * std::sin(3 * q.y)); }, seed % 2 ? 0.121 * h : -1.0);
    const double B = (seed % 3 == 0) ? 0.8 : 1.0;
    auto T = refined(p, f, B, seed % 2 ? 25.0 : 0.0);
    const double area = T.area(), q0 = quality_sum(T);
    refine::SmoothOptions so;
    so.passes = 4;
    so.bound = B;
    so.min_angle_deg = 25;
    so.block_vertices = 16 + 8 * (seed % 7);  // many blocks: the concurrent sweeps and the deferrals run
    ThreadsEnv threads(2);
    const auto st = refine::smooth(T, f, so);
    deferred += st.deferred;
    moves += st.moves;
    const auto r = mesh::check_all(T);
    ASSERT_TRUE(r.ok()) << "seed " << seed << ": " << (r.problems.empty() ? "" : r.problems[0]);
    EXPECT_LE(max_r_over_f(T, f), B * (1 + 1e-12)) << seed;
    EXPECT_NEAR(T.area(), area, 1e-9 * area) << seed;
    EXPECT_GE(quality_sum(T), q0) << seed;
  }
  EXPECT_GT(moves, 1000u);  // the test exercises the smoother
  EXPECT_GT(deferred, 100u);  // and vertices whose star or flips cross blocks
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

// A short edge sets a model's time step: smoothing never adds an edge shorter than f/2 (constant
// f here, so the count over the mesh can only fall), also beside one that already was.
TEST(Smooth, NoNewEdgesUnderHalfF) {
  std::size_t before_total = 0;
  for (unsigned seed = 0; seed < 40; ++seed) {
    const auto p = fdr::testing::random_pslg(seed, 5 + seed % 40, static_cast<int>(seed % 12));
    const double h = 0.2 + 0.1 * (seed % 5);
    FnField f([h](Point2) { return h; });
    auto T = refined(p, f, 1.0, 30.0);
    const std::size_t before = edges_shorter_than(T, 0.5 * h);
    before_total += before;
    refine::SmoothOptions so;
    so.passes = 4;
    so.min_angle_deg = 30;
    refine::smooth(T, f, so);
    EXPECT_LE(edges_shorter_than(T, 0.5 * h), before) << seed;
  }
  EXPECT_GT(before_total, 100u);  // the inputs' small features make short edges to begin with
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

// The blocks are swept concurrently, the vertices across blocks in a second, shifted blocking
// (concurrently too), those across blocks of both afterwards on one thread: the
// mesh is the same bit for bit for every thread count (FDR_THREADS) and block size is what
// decides it, on a mesh of many blocks (about 20 000 vertices, blocks of 512, 4096 and the default).
TEST(Smooth, SameMeshForEveryThreadCount) {
  const auto p = fdr::testing::random_pslg(5, 60, 8);
  FnField f([](Point2 q) { return 0.03 * (1 + 0.15 * q.x + 0.05 * std::sin(2 * q.y)); });
  const auto base = refined(p, f, 1.0, 30.0);
  ASSERT_GT(base.num_vertices(), 10000u);
  for (std::size_t block : {std::size_t{512}, std::size_t{4096}, refine::SmoothOptions{}.block_vertices}) {
    std::vector<mesh::MeshView> views;
    std::vector<std::size_t> moves, calls;
    for (int threads : {1, 2, 3, 4}) {
      ThreadsEnv env(threads);
      auto T = base;
      refine::SmoothOptions so;
      so.min_angle_deg = 30;
      so.block_vertices = block;
      predicates::reset_counters();
      const auto st = refine::smooth(T, f, so);
      calls.push_back(predicates::counters().filtered + predicates::counters().exact);  // all threads'
      EXPECT_GT(st.moves, 1000u);
      EXPECT_GT(st.shifted, st.deferred);  // the second blocking takes most of them
      EXPECT_GT(st.deferred, 0u);
      const auto r = mesh::check_all(T);
      ASSERT_TRUE(r.ok()) << (r.problems.empty() ? "" : r.problems[0]);
      views.push_back(T.to_view());
      moves.push_back(st.moves);
    }
    for (std::size_t i = 1; i < views.size(); ++i) {
      EXPECT_EQ(moves[i], moves[0]) << "block " << block << ", threads " << i + 1;
      EXPECT_EQ(calls[i], calls[0]) << "block " << block << ", threads " << i + 1;
      ASSERT_EQ(views[i].triangles, views[0].triangles) << "block " << block << ", threads " << i + 1;
      ASSERT_EQ(views[i].vertices.size(), views[0].vertices.size());
      for (std::size_t v = 0; v < views[0].vertices.size(); ++v)
        ASSERT_EQ(views[i].vertices[v], views[0].vertices[v]) << "block " << block << ", threads " << i + 1;
    }
  }
}

// Vertices across a constraint (here the two sides of a thin strip of land, 0.15 f wide, with
// differently spaced input vertices) are no mesh neighbours, so no test of a move's triangles
// sees them: the smoothing must still not bring a vertex nearer to one of them than it was,
// unless they stay f/2 apart (the report's nn is over all vertices: Theorem 4.4).
TEST(Smooth, NoVertexComesNearerAcrossAThinStripOfLand) {
  pslg::Pslg p;
  p.points = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  for (Index i = 0; i < 4; ++i) p.segments.push_back({i, static_cast<Index>((i + 1) % 4)});
  // the strip (a hole, clockwise): bottom side y = 5 with three vertices, top side y = 5.15 with five
  const std::vector<Point2> strip = {{1, 5}, {1, 5.15}, {2.7, 5.15}, {4.1, 5.15}, {6.3, 5.15}, {9, 5.15}, {9, 5}, {4.9, 5}};
  const Index base = static_cast<Index>(p.points.size());
  for (Point2 q : strip) p.points.push_back(q);
  for (Index i = 0; i < strip.size(); ++i) p.segments.push_back({base + i, base + static_cast<Index>((i + 1) % strip.size())});
  p.holes.push_back({5, 5.07});
  FnField f([](Point2 q) { return 0.6 + 0.05 * std::fabs(q.x - 5); });
  auto T = refined(p, f, 1.0, 30);
  // Distances of the vertex pairs within 1 of each other that are not mesh neighbours.
  auto hidden_pairs = [&](const mesh::Triangulation& M) {
    std::set<std::pair<Index, Index>> edges;
    for (TriangleId t = 0; t < M.num_slots(); ++t)
      if (!M.dead(t))
        for (int k = 0; k < 3; ++k) {
          const Index a = M.corner(t, k), b = M.org(3 * t + (k + 1) % 3);
          edges.insert({std::min(a, b), std::max(a, b)});
        }
    std::map<std::pair<Index, Index>, double> d;
    for (Index a = 0; a < M.num_vertices(); ++a)
      for (Index b = a + 1; b < M.num_vertices(); ++b)
        if (M.vertex_edge(a) != kNoId && M.vertex_edge(b) != kNoId && M.kind(a) != mesh::VertexKind::kSuper &&
            M.kind(b) != mesh::VertexKind::kSuper && dist(M.point(a), M.point(b)) < 1 && !edges.count({a, b}))
          d[{a, b}] = dist(M.point(a), M.point(b));
    return d;
  };
  const auto before = hidden_pairs(T);
  refine::SmoothOptions so;
  so.min_angle_deg = 30;
  const refine::SmoothStats st = refine::smooth(T, f, so);
  EXPECT_GT(st.segment_moves, 0u);
  const auto after = hidden_pairs(T);
  ASSERT_FALSE(before.empty());
  // Pairs across the strip, hidden before and after: nearer only while at least f/2 apart (f >= 0.6).
  for (const auto& [ab, d1] : after) {
    const auto it = before.find(ab);
    if (it != before.end() && d1 < it->second - 1e-12) {
      EXPECT_GE(d1, 0.5 * 0.6 * (1 - 1e-9)) << ab.first << " " << ab.second;
    }
  }
  auto r = mesh::check_all(T);
  EXPECT_TRUE(r.ok());
}
