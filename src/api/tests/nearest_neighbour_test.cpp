// The quality report's nearest neighbours and orthogonality from the mesh's own adjacency
// (quality/mesh_adjacency.hpp) against brute force / the adjacency-free path, on meshes the core
// makes: random points, constraints that hide the nearest vertex, holes, narrow gaps across the
// exterior, a vertex where two parts touch, and meshes that are not constrained Delaunay.
#include <gtest/gtest.h>
#include <numbers>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>
#include <algorithm>
#include "api/triangulate.hpp"
#include "quality/mesh_adjacency.hpp"
#include "quality/orthogonality.hpp"
#include "quality/report.hpp"

namespace {
using fdr::Index;
using fdr::Point2;

std::vector<double> brute_force(const fdr::MeshView& m) {
  std::vector<double> nn(m.vertices.size(), std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < m.vertices.size(); ++i)
    for (std::size_t j = 0; j < m.vertices.size(); ++j)
      if (i != j) nn[i] = std::min(nn[i], fdr::norm2(m.vertices[j] - m.vertices[i]));
  return nn;
}

// Exact equality with the brute force, with and without a second thread.
void expect_exact(const fdr::MeshView& m, const char* what) {
  ASSERT_EQ(m.neighbours.size(), 3 * m.triangles.size()) << what;
  const std::vector<double> want = brute_force(m);
  for (unsigned threads : {1u, 2u}) {
    const std::vector<double> got = fdr::quality::mesh_nearest_neighbour_sq(m, m.neighbours, threads);
    ASSERT_EQ(got.size(), want.size()) << what;
    std::size_t wrong = 0;
    for (std::size_t i = 0; i < want.size(); ++i) wrong += got[i] != want[i];
    EXPECT_EQ(wrong, 0u) << what << " (" << threads << " threads)";
  }
  // The adjacency built from the triangles alone is the mesher's.
  fdr::MeshView bare = m;
  bare.neighbours.clear();
  EXPECT_EQ(fdr::quality::half_edge_neighbours(bare), m.neighbours) << what;
}

fdr::Pslg polygon(const std::vector<Point2>& ring) {
  fdr::Pslg g;
  g.points = ring;
  for (Index i = 0; i < ring.size(); ++i) g.segments.push_back({i, static_cast<Index>((i + 1) % ring.size()), 1, 0});
  return g;
}

TEST(NearestNeighbour, RandomPointsCdtAndRefined) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 10.0);
  fdr::Pslg g = polygon({{0, 0}, {10, 0}, {10, 10}, {0, 10}});
  for (int i = 0; i < 600; ++i) g.points.push_back({u(rng), u(rng)});
  fdr::Triangulator t(g);
  expect_exact(t.view(), "random points, CDT");
  t.refine(fdr::make_spacing("0.6"));
  expect_exact(t.view(), "random points, refined");
}

TEST(NearestNeighbour, ConstraintHidesTheNearestVertex) {
  // Points 0.02 apart on either side of a long interior segment: in the CDT they are not joined.
  fdr::Pslg g = polygon({{0, 0}, {10, 0}, {10, 10}, {0, 10}});
  const Index a = static_cast<Index>(g.points.size());
  g.points.push_back({0, 5});
  g.points.push_back({10, 5});
  g.segments.push_back({a, a + 1, 2, 1});
  for (int i = 1; i < 10; ++i) {
    g.points.push_back({i + 0.1 * i, 4.99});
    g.points.push_back({i + 0.1 * i, 5.01});
    g.points.push_back({i + 0.05, 3.0 + 0.1 * i});
  }
  fdr::Triangulator t(g);
  const fdr::MeshView cdt = t.view();
  expect_exact(cdt, "hidden across a segment, CDT");
  t.refine(fdr::make_spacing("0.8"));
  expect_exact(t.view(), "hidden across a segment, refined");
}

TEST(NearestNeighbour, NarrowGapAcrossTheExteriorAndHoles) {
  // A U-shaped domain whose two arms are 0.05 apart across the exterior slot, and a square hole
  // whose inner corners face each other closely.
  fdr::Pslg g = polygon({{0, 0}, {10, 0}, {10, 10}, {5.025, 10}, {5.025, 2}, {4.975, 2}, {4.975, 10}, {0, 10}});
  const Index h = static_cast<Index>(g.points.size());
  for (const Point2 p : {Point2{1, 4}, Point2{3, 4}, Point2{3, 6}, Point2{1, 6}}) g.points.push_back(p);
  for (Index i = 0; i < 4; ++i) g.segments.push_back({h + i, h + (i + 1) % 4, 3, 2});
  g.holes.push_back({2, 5});
  g.points.push_back({4.9, 6});   // close to the slot from the left arm
  g.points.push_back({5.1, 6.01});  // and from the right arm
  fdr::Triangulator t(g);
  expect_exact(t.view(), "slot and hole, CDT");
  t.refine(fdr::make_spacing("0.7"));
  expect_exact(t.view(), "slot and hole, refined");
}

TEST(NearestNeighbour, TwoPartsTouchingAtAVertex) {
  // Two squares sharing one corner (two fans around it), refined, and the bowtie from Boothbay.
  fdr::Pslg g = polygon({{0, 0}, {2, 0}, {2, 2}, {4, 2}, {4, 4}, {2, 4}, {2, 2}, {0, 2}});
  fdr::TriangulateOptions o;
  o.strict = false;
  fdr::Triangulator t(g, o);
  t.refine(fdr::make_spacing("0.3"));
  expect_exact(t.view(), "two squares touching");
  fdr::Triangulator b(fdr::read_pslg(std::string(FDR_TESTDATA_DIR) + "/poly/bowtie_vertex_gom_raw.poly"), o);
  expect_exact(b.view(), "bowtie, CDT");
}

TEST(NearestNeighbour, NotConstrainedDelaunayStillExact) {
  // Flip interior edges of a Delaunay mesh (as the view's triangles and neighbours) so that it is
  // no longer Delaunay: the shortcut must notice and walk every vertex.
  fdr::Pslg g = polygon({{0, 0}, {10, 0}, {10, 10}, {0, 10}});
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 10.0);
  for (int i = 0; i < 300; ++i) g.points.push_back({u(rng), u(rng)});
  fdr::Triangulator t(g);
  fdr::MeshView m = t.view();
  std::size_t flips = 0;
  std::vector<char> touched(m.triangles.size(), 0);
  for (std::size_t h = 0; h < m.neighbours.size() && flips < 40; ++h) {
    const Index gh = m.neighbours[h];
    const std::size_t t0 = h / 3, t1 = gh == fdr::kNoId ? 0 : gh / 3;
    if (gh == fdr::kNoId || touched[t0] || touched[t1]) continue;
    // Quad a b c d: t0 = (a, b, c) with edge k = a -> b, t1 = (b, a, d); flip to (d, c, a), (c, d, b).
    const int k = static_cast<int>(h % 3), j = static_cast<int>(gh % 3);
    const Index a = m.triangles[t0][k], b = m.triangles[t0][(k + 1) % 3], c = m.triangles[t0][(k + 2) % 3];
    const Index d = m.triangles[t1][(j + 2) % 3];
    auto ccw = [&](Index p, Index q, Index r) {
      const Point2 P = m.vertices[p], Q = m.vertices[q], R = m.vertices[r];
      return (Q.x - P.x) * (R.y - P.y) - (Q.y - P.y) * (R.x - P.x) > 0;
    };
    if (!ccw(d, c, a) || !ccw(c, d, b)) continue;  // not convex: no flip
    m.triangles[t0] = {d, c, a};
    m.triangles[t1] = {c, d, b};
    touched[t0] = touched[t1] = 1;
    ++flips;
  }
  ASSERT_GT(flips, 10u);
  m.neighbours.clear();
  m.neighbours = fdr::quality::half_edge_neighbours(m);
  expect_exact(m, "flipped edges");
}

TEST(NearestNeighbour, UnusedVertexNeedsTheGlobalSearch) {
  fdr::Triangulator t(polygon({{0, 0}, {1, 0}, {0, 1}}));
  fdr::MeshView m = t.view();
  m.vertices.push_back({0.2, 0.2});
  EXPECT_TRUE(fdr::quality::mesh_nearest_neighbour_sq(m, m.neighbours).empty());
}

// Issue 7 (GIS report): the shortcut and the walk skip S edges that cannot matter (a vertex's own,
// the boundary edges of its own triangles, those nearest at an endpoint not nearer than the
// bound) and find S edges in a cell index. Coast-like meshes where those cases occur: a comb
// whose teeth face each other across narrow exterior slots with vertices exactly opposite (the
// nearest vertex across the exterior is itself on the re-entry edge), concave star-shaped coasts
// with many islands (holes) close to each other and to the coast, CDT and refined.
TEST(NearestNeighbour, CoastsCombsAndIslands) {
  // Comb: 6 teeth of width 1 separated by slots of width 0.01, each side of a slot split at the
  // same heights.
  {
    std::vector<Point2> ring{{0, 0}};
    const int teeth = 6;
    const double slot = 0.01;
    double x = 0;
    for (int k = 0; k < teeth; ++k) {
      // up the left side of tooth k (facing the previous slot), over its top, down its right side
      for (int i = 0; i <= 20; ++i) ring.push_back({x, 1 + 0.2 * i});
      ring.push_back({x + 0.5, 5.3});
      for (int i = 20; i >= 0; --i) ring.push_back({x + 1, 1 + 0.2 * i});
      x += 1 + slot;
    }
    ring.back() = {x - slot, 1};
    ring.push_back({x - slot, 0});
    ring.erase(ring.begin() + 1);  // the first tooth starts at (0, 1.2): (0, 0) -> (0, 1.2) is a side
    fdr::Pslg g = polygon(ring);
    fdr::TriangulateOptions o;
    o.strict = false;
    fdr::Triangulator t(g, o);
    expect_exact(t.view(), "comb, CDT");
    t.refine(fdr::make_spacing("0.15"));
    expect_exact(t.view(), "comb, refined");
  }
  for (unsigned seed : {11u, 12u, 13u}) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0, 1);
    // A star-shaped coast (radius 8..10 around (10, 10): concave bays), islands on a jittered grid.
    std::vector<Point2> ring;
    const int n = 160;
    for (int i = 0; i < n; ++i) {
      const double a = 2 * std::numbers::pi * i / n, r = 8 + 2 * u(rng);
      ring.push_back({10 + r * std::cos(a), 10 + r * std::sin(a)});
    }
    fdr::Pslg g = polygon(ring);
    for (int j = 0; j < 9; ++j)
      for (int i = 0; i < 9; ++i) {
        const Point2 c{10 - 5.6 + 1.4 * i + 0.3 * (u(rng) - 0.5), 10 - 5.6 + 1.4 * j + 0.3 * (u(rng) - 0.5)};
        if (std::hypot(c.x - 10, c.y - 10) > 7 || u(rng) < 0.3) continue;
        const double s = 0.2 + 0.35 * u(rng);  // islands up to 0.04 apart
        const Index b = static_cast<Index>(g.points.size());
        const int k = 3 + static_cast<int>(3 * u(rng));
        for (int q = 0; q < k; ++q) {
          const double a = 2 * std::numbers::pi * q / k + u(rng) * 0.5;
          g.points.push_back({c.x + s * std::cos(a), c.y + s * std::sin(a)});
        }
        for (int q = 0; q < k; ++q) g.segments.push_back({b + q, b + (q + 1) % k, 2, 0});
        g.holes.push_back(c);
      }
    fdr::Triangulator t(g);
    expect_exact(t.view(), "coast and islands, CDT");
    t.refine(fdr::make_spacing("0.25"));
    expect_exact(t.view(), "coast and islands, refined");
  }
}

TEST(NearestNeighbour, ReportIsTheSameWithAndWithoutTheAdjacency) {
  // compute_quality on the mesher's view (adjacency: the walk) and on a copy without it (k-d
  // tree, adjacency rebuilt from the triangles): every figure equal.
  fdr::Pslg g = polygon({{0, 0}, {10, 0}, {10, 10}, {5.025, 10}, {5.025, 2}, {4.975, 2}, {4.975, 10}, {0, 10}});
  g.points.push_back({4.9, 6});
  fdr::Triangulator t(g);
  const auto f = fdr::make_spacing("0.05*paper-f1");
  t.refine(f);
  const fdr::MeshView m = t.view();
  ASSERT_GT(m.triangles.size(), 5000u);  // large enough for the second thread
  fdr::MeshView bare = m;
  bare.neighbours.clear();
  const fdr::quality::RunInfo ri;
  const auto a = fdr::quality::compute_quality(m, nullptr, 1.0, -1, ri);
  const auto b = fdr::quality::compute_quality(bare, nullptr, 1.0, -1, ri);
  EXPECT_EQ(a.nn_min, b.nn_min);
  EXPECT_EQ(a.orthogonality.interior_edges, b.orthogonality.interior_edges);
  EXPECT_EQ(a.orthogonality.orthogonality_max, b.orthogonality.orthogonality_max);
  EXPECT_EQ(a.orthogonality.orthogonality_p99, b.orthogonality.orthogonality_p99);
  EXPECT_EQ(a.orthogonality.smoothness_max, b.orthogonality.smoothness_max);
  EXPECT_EQ(a.orthogonality.smoothness_p99, b.orthogonality.smoothness_p99);
  std::ostringstream ja, jb;
  fdr::quality::write_json(a, ja);
  fdr::quality::write_json(b, jb);
  EXPECT_EQ(ja.str(), jb.str());
}

TEST(Orthogonality, P99EqualsASortOnTheMesherMesh) {
  // The bucket-count p99 against the nearest rank of all values sorted (computed here).
  fdr::Triangulator t(polygon({{0, 0}, {10, 0}, {10, 10}, {0, 10}}));
  t.refine(fdr::make_spacing("0.08*paper-f1"));
  const fdr::MeshView m = t.view();
  std::vector<double> ortho, smooth;
  auto centre = [&](std::size_t tr) {
    const Point2 a = m.vertices[m.triangles[tr][0]], b = m.vertices[m.triangles[tr][1]], c = m.vertices[m.triangles[tr][2]];
    const double bx = b.x - a.x, by = b.y - a.y, cx = c.x - a.x, cy = c.y - a.y;
    const double b2 = bx * bx + by * by, c2 = cx * cx + cy * cy, d = 2.0 * (bx * cy - by * cx);
    Point2 cc{a.x + (cy * b2 - by * c2) / d, a.y + (bx * c2 - cx * b2) / d};
    auto side = [](Point2 p, Point2 q, Point2 r) { return (q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x); };
    if (side(a, b, cc) >= 0 && side(b, c, cc) >= 0 && side(c, a, cc) >= 0) return std::make_pair(cc, 0.5 * std::fabs(side(a, b, c)));
    auto nearest = [](Point2 p, Point2 s, Point2 e) {
      const Point2 dd = e - s;
      const double l2 = fdr::norm2(dd);
      const double tt = l2 > 0 ? std::clamp(fdr::dot(p - s, dd) / l2, 0.0, 1.0) : 0.0;
      return s + tt * dd;
    };
    Point2 best = nearest(cc, a, b);
    for (const Point2 q : {nearest(cc, b, c), nearest(cc, c, a)})
      if (fdr::norm2(q - cc) < fdr::norm2(best - cc)) best = q;
    return std::make_pair(best, 0.5 * std::fabs(side(a, b, c)));
  };
  for (std::size_t h = 0; h < m.neighbours.size(); ++h) {
    const Index g = m.neighbours[h];
    const Index a = m.triangles[h / 3][h % 3], b = m.triangles[h / 3][(h % 3 + 1) % 3];
    if (g == fdr::kNoId || a > b) continue;
    const auto [ct, at] = centre(h / 3);
    const auto [cu, au] = centre(g / 3);
    const Point2 e = m.vertices[b] - m.vertices[a], l = ct - cu;
    const double el = std::sqrt(fdr::norm2(e)) * std::sqrt(fdr::norm2(l));
    ortho.push_back(el > 0 ? std::fabs(fdr::dot(e, l)) / el : 0.0);
    smooth.push_back(std::max(at, au) / std::min(at, au));
  }
  std::sort(ortho.begin(), ortho.end());
  std::sort(smooth.begin(), smooth.end());
  const std::size_t k = static_cast<std::size_t>(std::ceil(0.99 * static_cast<double>(ortho.size()))) - 1;
  for (unsigned threads : {1u, 2u}) {
    const auto s = fdr::quality::compute_orthogonality(m, threads);
    EXPECT_EQ(s.interior_edges, ortho.size());
    EXPECT_EQ(s.orthogonality_p99.value_or(-1), ortho[k]);
    EXPECT_EQ(s.smoothness_p99.value_or(-1), smooth[k]);
    EXPECT_EQ(s.orthogonality_max.value_or(-1), ortho.back());
    EXPECT_EQ(s.smoothness_max.value_or(-1), smooth.back());
  }
}

}  // namespace
