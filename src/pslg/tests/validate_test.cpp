// validate() and find_crossings(): each invalid case caught with ids/coordinates, valid inputs pass.
#include <gtest/gtest.h>
#include <chrono>
#include <random>
#include "pslg/poly_io.hpp"
#include "predicates/predicates.hpp"
#include "pslg/segment_grid.hpp"
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

// classify() against a reference written from the definitions (four orientations, then the
// collinear cases), on a 4 x 4 lattice where shared endpoints, collinear and touching pairs
// abound: the shortcut for segments sharing one endpoint must give the same answers.
namespace {
Contact reference_contact(Point2 a, Point2 b, Point2 c, Point2 d) {
  using predicates::orient2d;
  auto inside = [](Point2 p, Point2 q, Point2 r) {  // r in the open segment pq
    if (orient2d(p, q, r) != 0) return false;
    return p.x != q.x ? (std::min(p.x, q.x) < r.x && r.x < std::max(p.x, q.x))
                      : (std::min(p.y, q.y) < r.y && r.y < std::max(p.y, q.y));
  };
  const int o1 = orient2d(a, b, c), o2 = orient2d(a, b, d), o3 = orient2d(c, d, a), o4 = orient2d(c, d, b);
  const bool shared = a == c || a == d || b == c || b == d;
  if (o1 == 0 && o2 == 0) {
    if ((a == c && b == d) || (a == d && b == c)) return Contact::kOverlap;
    if (inside(a, b, c) || inside(a, b, d) || inside(c, d, a) || inside(c, d, b)) return Contact::kOverlap;
    return shared ? Contact::kEndpoint : Contact::kNone;
  }
  if (o1 * o2 > 0 || o3 * o4 > 0) return Contact::kNone;
  if (o1 != 0 && o2 != 0 && o3 != 0 && o4 != 0) return Contact::kProper;
  return shared ? Contact::kEndpoint : Contact::kTouch;
}
}  // namespace

TEST(Classify, SameAsTheDefinitionsOnALattice) {
  std::vector<Point2> lat;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) lat.push_back({0.5 * i, 0.25 * j});
  std::size_t shared = 0, overlaps = 0;
  for (const Point2 a : lat)
    for (const Point2 b : lat) {
      if (a == b) continue;
      for (const Point2 c : lat)
        for (const Point2 d : lat) {
          if (c == d) continue;
          const Contact want = reference_contact(a, b, c, d);
          ASSERT_EQ(static_cast<int>(classify(a, b, c, d)), static_cast<int>(want))
              << "(" << a.x << "," << a.y << ")-(" << b.x << "," << b.y << ") vs (" << c.x << "," << c.y << ")-(" << d.x << "," << d.y << ")";
          shared += (a == c || a == d || b == c || b == d);
          overlaps += want == Contact::kOverlap;
        }
    }
  EXPECT_GT(shared, 10000u);
  EXPECT_GT(overlaps, 1000u);
}

TEST(InInterior, OnlyTheOpenSegment) {
  EXPECT_TRUE(in_interior({0, 0}, {2, 2}, {1, 1}));
  EXPECT_FALSE(in_interior({0, 0}, {2, 2}, {2, 2}));
  EXPECT_FALSE(in_interior({0, 0}, {2, 2}, {3, 3}));   // on the line, beyond the end
  EXPECT_FALSE(in_interior({0, 0}, {0, 2}, {0, -1}));  // vertical, below
  EXPECT_TRUE(in_interior({0, 2}, {0, 0}, {0, 1}));
  EXPECT_FALSE(in_interior({0, 0}, {2, 2}, {1, 1.0000000000000002}));
}

// find_contacts against brute force on random lattice PSLGs (chains, isolated points, zero-length
// segments, an alive mask): the same pairs with the same kinds and the same vertices on segments.
TEST(FindContacts, SameAsBruteForceOnRandomLatticeGraphs) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> coord(0, 7), pick(0, 1 << 20);
  for (int round = 0; round < 300; ++round) {
    std::vector<Point2> pts;
    const int np = 6 + round % 30;
    for (int i = 0; i < np; ++i) pts.push_back({0.5 * coord(rng), 0.25 * coord(rng)});
    std::vector<Segment> segs;
    const int ns = 3 + round % 25;
    for (int k = 0; k < ns; ++k) {
      const Index a = static_cast<Index>(pick(rng) % np);
      const Index b = k % 3 == 0 && !segs.empty() ? segs.back().b : static_cast<Index>(pick(rng) % np);  // chains
      segs.push_back({a, b, 1, 0});
    }
    std::vector<char> alive(pts.size());
    for (auto& v : alive) v = static_cast<char>(pick(rng) % 4 != 0);
    const std::vector<char>* mask = round % 2 ? &alive : nullptr;
    const Contacts got = find_contacts(pts, segs, mask);
    std::vector<std::pair<Index, Index>> want_pairs;
    std::vector<Contact> want_kinds;
    std::vector<std::pair<Index, Index>> want_on;
    auto ok = [&](const Segment& s) { return s.a != s.b && !(pts[s.a] == pts[s.b]); };
    for (Index i = 0; i < segs.size(); ++i)
      for (Index j = i + 1; j < segs.size(); ++j) {
        if (!ok(segs[i]) || !ok(segs[j])) continue;
        const Contact k = classify(pts[segs[i].a], pts[segs[i].b], pts[segs[j].a], pts[segs[j].b]);
        if (k == Contact::kNone || k == Contact::kEndpoint) continue;
        want_pairs.emplace_back(i, j);
        want_kinds.push_back(k);
      }
    for (Index p = 0; p < pts.size(); ++p) {
      if (mask && !(*mask)[p]) continue;
      for (Index s = 0; s < segs.size(); ++s) {
        if (!ok(segs[s]) || segs[s].a == p || segs[s].b == p) continue;
        if (in_interior(pts[segs[s].a], pts[segs[s].b], pts[p])) want_on.emplace_back(p, s);
      }
    }
    ASSERT_EQ(got.segment_pairs, want_pairs) << "round " << round;
    ASSERT_EQ(got.kinds, want_kinds) << "round " << round;
    ASSERT_EQ(got.vertex_on_segment, want_on) << "round " << round;
  }
}
