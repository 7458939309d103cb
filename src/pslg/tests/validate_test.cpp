// validate() and find_crossings(): each invalid case caught with ids/coordinates, valid inputs pass.
#include <gtest/gtest.h>
#include <chrono>
#include <random>
#include "pslg/poly_io.hpp"
#include "predicates/predicates.hpp"
#include "pslg/validate.hpp"
#include "test_util.hpp"

using namespace fdr;
using namespace fdr::pslg;
using namespace fdr::pslg::test;

namespace {

Pslg make(std::vector<Point2> pts, std::vector<std::pair<Index, Index>> segs) {
  Pslg g;
  g.points = std::move(pts);
  for (auto [a, b] : segs) g.segments.push_back({a, b, 1, 0});
  return g;
}

// Brute-force O(n^2) oracle for find_crossings using the same exact rules.
std::vector<std::pair<Index, Index>> brute_crossings(const Pslg& g) {
  std::vector<std::pair<Index, Index>> out;
  auto seg_ok = [&](const Segment& s) { return s.a != s.b && !(g.points[s.a] == g.points[s.b]); };
  for (Index i = 0; i < g.segments.size(); ++i)
    for (Index j = i + 1; j < g.segments.size(); ++j) {
      const Segment &s = g.segments[i], &t = g.segments[j];
      if (!seg_ok(s) || !seg_ok(t)) continue;
      const Point2 a = g.points[s.a], b = g.points[s.b], c = g.points[t.a], d = g.points[t.b];
      const int o1 = predicates::orient2d(a, b, c), o2 = predicates::orient2d(a, b, d);
      const int o3 = predicates::orient2d(c, d, a), o4 = predicates::orient2d(c, d, b);
      bool bad = false;
      if (o1 * o2 < 0 && o3 * o4 < 0) bad = true;
      auto inside = [](Point2 p, Point2 q, Point2 r) {  // r strictly inside pq, given collinear
        return (std::min(p.x, q.x) < r.x && r.x < std::max(p.x, q.x)) ||
               (p.x == q.x && std::min(p.y, q.y) < r.y && r.y < std::max(p.y, q.y));
      };
      if (o1 == 0 && inside(a, b, c)) bad = true;
      if (o2 == 0 && inside(a, b, d)) bad = true;
      if (o3 == 0 && inside(c, d, a)) bad = true;
      if (o4 == 0 && inside(c, d, b)) bad = true;
      if (o1 == 0 && o2 == 0 && ((a == c && b == d) || (a == d && b == c))) bad = true;
      if (bad) out.emplace_back(i, j);
    }
  return out;
}

}  // namespace

TEST(Validate, ValidInputsPass) {
  EXPECT_NO_THROW(validate(read_poly(testdata("poly/square_with_hole.poly")), "a"));
  EXPECT_NO_THROW(validate(read_poly(testdata("poly/interior_segment.poly")), "b"));
  EXPECT_NO_THROW(validate(read_poly(testdata("poly/wedge_1deg.poly")), "c"));
  EXPECT_NO_THROW(validate(Pslg{}, "empty"));
  // Segments meeting at shared endpoints, a free point off every segment.
  Pslg g = make({{0, 0}, {1, 0}, {0, 1}, {0.25, 0.25}}, {{0, 1}, {1, 2}, {2, 0}});
  EXPECT_NO_THROW(validate(g, "tri"));
  // Collinear segments that only share an endpoint.
  EXPECT_NO_THROW(validate(make({{0, 0}, {1, 0}, {2, 0}}, {{0, 1}, {1, 2}}), "line"));
}

TEST(Validate, EachInvalidCaseIsNamed) {
  expect_error([] { validate(make({{0, 0}, {1, 0}, {0, 0}}, {{0, 1}}), "dup.poly"); }, ExitCode::kInvalidGeometry,
               {"dup.poly: ", "vertices 0 and 2", "(0, 0)"});
  expect_error([] { validate(make({{0, 0}, {1, 0}}, {{0, 1}, {1, 1}}), "zl"); }, ExitCode::kInvalidGeometry,
               {"zl: ", "zero-length segment 1"});
  expect_error([] { validate(make({{0, 0}, {1, 0}}, {{0, 1}, {1, 0}}), "ds"); }, ExitCode::kInvalidGeometry,
               {"duplicate segments 0 and 1"});
  expect_error([] { validate(make({{0, 0}, {2, 0}, {1, 0}}, {{0, 1}}), "vs"); }, ExitCode::kInvalidGeometry,
               {"vertex 2 (1, 0) lies inside segment 0"});
  expect_error([] { validate(make({{0, 0}, {2, 2}, {2, 0}, {0, 2}}, {{0, 1}, {2, 3}}), "x"); },
               ExitCode::kInvalidGeometry, {"x: ", "segment 0", "segment 1", "cross", "(1, 1)"});
  // Collinear overlap: 0-2 and 1-3 on the x axis; the vertex test fires first (vertex 1 in 0-2).
  expect_error([] { validate(make({{0, 0}, {1, 0}, {2, 0}, {3, 0}}, {{0, 2}, {1, 3}}), "ov"); },
               ExitCode::kInvalidGeometry, {"ov: ", "lies inside segment"});
  expect_error([] { validate(make({{0, 0}, {1, 0}}, {{0, 5}}), "rng"); }, ExitCode::kInvalidGeometry,
               {"segment 0 refers to vertex 5"});
  expect_error([] { validate(make({{0, 0}, {1, NAN}}, {}), "nan"); }, ExitCode::kInvalidGeometry, {"non-finite"});
  expect_error([] { validate(read_poly(testdata("poly/invalid_crossing.poly")), "invalid_crossing.poly"); },
               ExitCode::kInvalidGeometry, {"invalid_crossing.poly: ", "cross"});
  expect_error(
      [] { validate(read_poly(testdata("poly/invalid_duplicate_vertex.poly")), "invalid_duplicate_vertex.poly"); },
      ExitCode::kInvalidGeometry, {"vertices 1 and 3"});
}

TEST(Validate, WorldCoordinatesInMessages) {
  Pslg g = make({{0, 0}, {2, 2}, {2, 0}, {0, 2}}, {{0, 1}, {2, 3}});
  g.origin = {1000, -500};
  expect_error([&] { validate(g, "w"); }, ExitCode::kInvalidGeometry, {"(1001, -499)"});
}

TEST(FindCrossings, Kinds) {
  // proper crossing, T-touch, collinear overlap, identical copies, shared endpoint (none).
  Pslg g = make({{0, 0}, {4, 0}, {2, -1}, {2, 0}, {3, 0}, {5, 0}, {0, 3}, {1, 3}},
                {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {7, 6}});
  const auto c = find_crossings(g);
  const std::vector<std::pair<Index, Index>> want{{0, 1}, {0, 2}, {3, 4}};
  EXPECT_EQ(c, want);
  EXPECT_EQ(find_vertices_on_segments(g), (std::vector<std::pair<Index, Index>>{{1, 2}, {3, 0}, {4, 0}}));
}

TEST(FindCrossings, MatchesBruteForceOnRandomSoups) {
  std::mt19937_64 rng(3);
  for (int k = 0; k < 200; ++k) {
    Pslg g;
    // Small integer lattice: many exact collinearities, touches and overlaps.
    const int n = 5 + static_cast<int>(rng() % 30), m = 1 + static_cast<int>(rng() % 40);
    const int span = 2 + static_cast<int>(rng() % 8);
    for (int i = 0; i < n; ++i)
      g.points.push_back({static_cast<double>(rng() % span) * 0.5, static_cast<double>(rng() % span) * 0.25});
    for (int i = 0; i < m; ++i) g.segments.push_back({static_cast<Index>(rng() % n), static_cast<Index>(rng() % n), 1, 0});
    ASSERT_EQ(find_crossings(g), brute_crossings(g)) << "case " << k;
  }
}

TEST(Validate, HundredThousandSegmentsIsFast) {
  // A 317 x 317 lattice of little squares' horizontal and vertical edges (~200k segments), valid.
  Pslg g;
  const int n = 317;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) g.points.push_back({i * 1.0 + 0.001 * j, j * 1.0});
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Index v = static_cast<Index>(j * n + i);
      if (i + 1 < n) g.segments.push_back({v, v + 1, 1, 0});
      if (j + 1 < n) g.segments.push_back({v, v + static_cast<Index>(n), 1, 0});
    }
  ASSERT_GT(g.segments.size(), 100000u);
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_NO_THROW(validate(g, "lattice"));
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("validate: %zu segments in %.3f s\n", g.segments.size(), s);
  EXPECT_LT(s, 1.0);
  // One extra diagonal across the whole lattice crosses ~n segments: all reported.
  g.segments.push_back({0, static_cast<Index>(n * n - 1), 1, 0});
  const auto c = find_crossings(g);
  EXPECT_GT(c.size(), static_cast<std::size_t>(n));
}
