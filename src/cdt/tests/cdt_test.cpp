// CDT tests: invariants on random/adversarial PSLGs and CGAL's constrained Delaunay as an oracle.
#include <gtest/gtest.h>
#include <set>
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include "base/error.hpp"
#include "cdt/cdt.hpp"
#include "cdt/tests/test_inputs.hpp"
#include "mesh/check.hpp"

using namespace fdr;
using fdr::testing::random_pslg;

namespace {
// Random interior segments may close loops: keep everything inside the box (exterior only).
const cdt::CdtOptions kBoxOnly{cdt::CdtOptions::Regions::kSeeds, "test"};
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using CDT = CGAL::Constrained_Delaunay_triangulation_2<K, CGAL::Default, CGAL::Exact_predicates_tag>;

void expect_valid(const mesh::Triangulation& T, const std::string& what) {
  auto r = mesh::check_all(T);
  ASSERT_TRUE(r.ok()) << what << ": " << (r.problems.empty() ? "" : r.problems[0]) << " (" << r.count << " problems)";
}

std::set<std::pair<std::pair<double, double>, std::pair<double, double>>> edges_of(const mesh::MeshView& m) {
  std::set<std::pair<std::pair<double, double>, std::pair<double, double>>> s;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) {
      auto a = m.vertices[t[k]], b = m.vertices[t[(k + 1) % 3]];
      auto pa = std::make_pair(a.x, a.y), pb = std::make_pair(b.x, b.y);
      if (pb < pa) std::swap(pa, pb);
      s.insert({pa, pb});
    }
  return s;
}
}  // namespace

TEST(Cdt, SquareWithInteriorPoint) {
  pslg::Pslg p = random_pslg(1, 0, 0);
  p.points.push_back({5, 5});
  auto T = cdt::build_cdt(p);
  expect_valid(T, "square");
  EXPECT_EQ(T.num_live_triangles(), 4u);
  EXPECT_NEAR(T.area(), 100.0, 1e-12);
}

TEST(Cdt, RandomPslgsAreValidAndConserveArea) {
  for (unsigned seed = 0; seed < 200; ++seed) {
    auto p = random_pslg(seed, 10 + seed % 90, static_cast<int>(seed % 25));
    auto T = cdt::build_cdt(p, kBoxOnly);
    expect_valid(T, "seed " + std::to_string(seed));
    EXPECT_NEAR(T.area(), 100.0, 1e-10) << seed;
  }
}

TEST(Cdt, MatchesCgalConstrainedDelaunay) {
  for (unsigned seed = 100; seed < 160; ++seed) {
    auto p = random_pslg(seed, 50 + seed % 50, 15);
    auto T = cdt::build_cdt(p, kBoxOnly);
    auto mine = edges_of(T.to_view());
    CDT cg;
    std::vector<CDT::Vertex_handle> vh;
    for (auto q : p.points) vh.push_back(cg.insert(K::Point_2(q.x, q.y)));
    for (auto s : p.segments) cg.insert_constraint(vh[s.a], vh[s.b]);
    std::set<std::pair<std::pair<double, double>, std::pair<double, double>>> theirs;
    for (auto e = cg.finite_edges_begin(); e != cg.finite_edges_end(); ++e) {
      auto a = e->first->vertex(cg.cw(e->second))->point(), b = e->first->vertex(cg.ccw(e->second))->point();
      auto pa = std::make_pair(a.x(), a.y()), pb = std::make_pair(b.x(), b.y());
      if (pb < pa) std::swap(pa, pb);
      theirs.insert({pa, pb});
    }
    // Random points: no four cocircular, so the CDT is unique; box = convex hull.
    EXPECT_EQ(mine, theirs) << "seed " << seed;
  }
}

TEST(Cdt, CocircularLatticeIsValid) {
  const int n = 30;
  pslg::Pslg p = fdr::testing::lattice_square(n);
  for (auto& q : p.points) q = {q.x * 0.1, q.y * 0.1};
  auto T = cdt::build_cdt(p);
  expect_valid(T, "lattice");
  EXPECT_EQ(T.num_live_triangles(), static_cast<std::size_t>(2 * n * n));
}

TEST(Cdt, NearCollinearPoints) {
  pslg::Pslg p = random_pslg(3, 0, 0);
  for (int i = 1; i < 200; ++i) {
    double x = i * 0.05;
    double y = 5.0 + ((i % 2) ? std::nextafter(x, 100.0) - x : 0.0);
    p.points.push_back({x, y});
  }
  auto T = cdt::build_cdt(p);
  expect_valid(T, "near-collinear");
  EXPECT_NEAR(T.area(), 100.0, 1e-10);
}

TEST(Cdt, ScaledAndTranslatedCopiesAreValid) {
  auto base = random_pslg(77, 80, 12);
  for (double s : {1e-6, 1e-3, 1.0, 1e3, 1e6}) {
    for (double off : {0.0, 1e7}) {
      pslg::Pslg p = base;
      for (auto& q : p.points) q = {q.x * s + off, q.y * s + off};
      auto T = cdt::build_cdt(p, kBoxOnly);
      expect_valid(T, "scale " + std::to_string(s) + " offset " + std::to_string(off));
      const double want = (p.points[1].x - p.points[0].x) * (p.points[2].y - p.points[1].y);  // rounded box
      EXPECT_NEAR(T.area(), want, 1e-9 * want);
    }
  }
}

TEST(Cdt, SegmentThroughVertexIsSplitThere) {
  pslg::Pslg p = random_pslg(5, 0, 0);
  p.points.push_back({2, 5});
  p.points.push_back({5, 5});  // lies on the segment below
  p.points.push_back({8, 5});
  p.segments.push_back({4, 6, 4, 1});
  cdt::CdtStats st;
  auto T = cdt::build_cdt(p, {}, &st);
  expect_valid(T, "through vertex");
  EXPECT_EQ(st.segments_split_at_vertices, 1u);
  EXPECT_NE(T.find_edge(4, 5) == kNoId ? T.find_edge(5, 4) : T.find_edge(4, 5), kNoId);
}

TEST(Cdt, CrossingSegmentsAreAnError) {
  pslg::Pslg p = random_pslg(5, 0, 0);
  p.points.insert(p.points.end(), {{1, 1}, {9, 9}, {1, 9}, {9, 1}});
  p.segments.push_back({4, 5, 4, 1});
  p.segments.push_back({6, 7, 4, 1});
  try {
    cdt::build_cdt(p);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidGeometry);
    EXPECT_NE(std::string(e.what()).find("crosses"), std::string::npos) << e.what();
  }
}

TEST(Cdt, HolesBySeedsAndNestedHolesByParity) {
  // Outer square, hole square, island square inside the hole.
  pslg::Pslg p;
  auto square = [&](double lo, double hi, int marker) {
    const Index b = static_cast<Index>(p.points.size());
    p.points.insert(p.points.end(), {{lo, lo}, {hi, lo}, {hi, hi}, {lo, hi}});
    for (Index i = 0; i < 4; ++i) p.segments.push_back({b + i, b + (i + 1) % 4, marker, static_cast<int>(b)});
  };
  square(0, 10, 1);
  square(2, 8, 2);
  square(4, 6, 1);
  auto parity = cdt::build_cdt(p);
  expect_valid(parity, "parity");
  EXPECT_NEAR(parity.area(), 100 - 36 + 4, 1e-12);
  pslg::Pslg q = p;
  q.holes.push_back({3, 3});  // seeds: only the ring between 2..8 and 4..6 is a hole
  auto seeds = cdt::build_cdt(q);
  expect_valid(seeds, "seeds");
  EXPECT_NEAR(seeds.area(), 100 - 36 + 4, 1e-12);
  pslg::Pslg r = p;
  r.holes.push_back({5, 5});  // the island is the hole; the ring stays
  auto seeds2 = cdt::build_cdt(r);
  EXPECT_NEAR(seeds2.area(), 100 - 4, 1e-12);
}

TEST(Cdt, DanglingSegmentsDoNotBreakParity) {
  pslg::Pslg p = random_pslg(9, 0, 0);
  p.points.insert(p.points.end(), {{0, 5}, {3, 5}, {5, 2}, {5, 8}});
  p.segments.push_back({4, 5, 4, 1});  // touches the boundary, dangles inside
  p.segments.push_back({6, 7, 4, 2});  // free-floating
  auto T = cdt::build_cdt(p);
  expect_valid(T, "dangling");
  EXPECT_NEAR(T.area(), 100.0, 1e-12);
}

TEST(Cdt, OverlappingSegmentsAreAnError) {
  pslg::Pslg p = random_pslg(5, 0, 0);
  p.points.insert(p.points.end(), {{1, 1}, {5, 5}, {8, 8}});
  p.segments.push_back({4, 6, 4, 1});  // (1,1)-(8,8) passes through (5,5)
  p.segments.push_back({5, 6, 4, 2});  // (5,5)-(8,8) overlaps it
  try {
    cdt::build_cdt(p);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidGeometry);
    EXPECT_NE(std::string(e.what()).find("overlaps"), std::string::npos) << e.what();
  }
}

TEST(Cdt, SegmentsThroughLatticeVerticesAreSplitExactly) {
  // Lattice points: many segments pass exactly through vertices (exact collinearity).
  const int n = 8;
  pslg::Pslg p = fdr::testing::lattice_square(n);
  auto id = [&](int i, int j) { return static_cast<Index>(j * (n + 1) + i); };
  p.segments.push_back({id(0, 0), id(n, n), 4, 1});          // through 7 interior vertices
  p.segments.push_back({id(1, 7), id(7, 1), 4, 2});          // crosses the diagonal at the vertex (4,4)
  cdt::CdtStats st;
  auto T = cdt::build_cdt(p, {cdt::CdtOptions::Regions::kSeeds, "lattice"}, &st);
  expect_valid(T, "lattice segments");
  EXPECT_GE(st.segments_split_at_vertices, 7u + 5u);
}
