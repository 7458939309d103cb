// clean(): random soups come out valid, bow-ties and crossing rings split, spikes cancel,
// tiny rings drop, simplification stays within tolerance, and the result is deterministic.
#include <gtest/gtest.h>
#include <cmath>
#include <cstring>
#include <map>
#include <random>
#include "pslg/clean.hpp"
#include "pslg/poly_io.hpp"
#include "predicates/predicates.hpp"
#include "pslg/validate.hpp"
#include "test_util.hpp"

using namespace fdr;
using namespace fdr::pslg;
using namespace fdr::pslg::test;

namespace {

// Appends a closed ring through pts with the given part and marker.
void add_ring(Pslg* g, const std::vector<Point2>& pts, std::int32_t part, std::int32_t marker = 1) {
  const Index base = static_cast<Index>(g->points.size());
  for (const auto& p : pts) g->points.push_back(p);
  const Index n = static_cast<Index>(pts.size());
  for (Index i = 0; i < n; ++i) g->segments.push_back({base + i, base + (i + 1) % n, marker, part});
}

std::size_t count_kind(const std::vector<Repair>& r, const std::string& kind) {
  std::size_t n = 0;
  for (const auto& x : r) n += x.kind == kind;
  return n;
}

void expect_identical(const Pslg& a, const Pslg& b) {
  ASSERT_EQ(a.points.size(), b.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    EXPECT_EQ(std::memcmp(&a.points[i], &b.points[i], sizeof(Point2)), 0) << i;
  }
  ASSERT_EQ(a.segments.size(), b.segments.size());
  for (std::size_t i = 0; i < a.segments.size(); ++i) {
    EXPECT_EQ(a.segments[i].a, b.segments[i].a);
    EXPECT_EQ(a.segments[i].b, b.segments[i].b);
    EXPECT_EQ(a.segments[i].marker, b.segments[i].marker);
    EXPECT_EQ(a.segments[i].part, b.segments[i].part);
  }
  EXPECT_EQ(a.point_markers, b.point_markers);
}

// Degree of each point over boundary segments.
std::vector<int> degrees(const Pslg& g) {
  std::vector<int> d(g.points.size(), 0);
  for (const auto& s : g.segments) ++d[s.a], ++d[s.b];
  return d;
}

Pslg random_soup(std::mt19937_64& rng, int k) {
  Pslg g;
  const int n = 4 + static_cast<int>(rng() % 40);
  const int mode = k % 4;
  std::uniform_real_distribution<double> u(0, 100);
  for (int i = 0; i < n; ++i) {
    Point2 p{u(rng), u(rng)};
    if (mode == 1) p = {std::floor(p.x / 10), std::floor(p.y / 10)};  // lattice: many collinearities
    if (mode == 2 && i > 0 && rng() % 3 == 0) p = g.points[rng() % i] + Point2{1e-9, -1e-9};  // near-duplicates
    if (mode == 3) p = {p.x * 1e-9 + 1e6, p.y};  // thin, far from the origin
    g.points.push_back(p);
  }
  const int m = 1 + static_cast<int>(rng() % 40);
  for (int i = 0; i < m; ++i) {
    const Index a = static_cast<Index>(rng() % n), b = static_cast<Index>(rng() % n);
    const std::int32_t marker = rng() % 4 == 0 ? kBreaklineMarker : 1;
    g.segments.push_back({a, b, marker, static_cast<std::int32_t>(rng() % 3)});
  }
  if (rng() % 2) g.point_markers.assign(g.points.size(), 9);
  return g;
}

}  // namespace

TEST(Clean, RandomSoupsComeOutValid) {
  std::mt19937_64 rng(20240601);
  for (int k = 0; k < 400; ++k) {
    const Pslg in = random_soup(rng, k);
    CleanOptions opt;
    opt.snap_distance = (k % 3 == 0) ? 1e-6 : 0;
    std::vector<Repair> rep;
    Pslg out;
    ASSERT_NO_THROW(out = clean(in, opt, &rep)) << "case " << k;
    EXPECT_NO_THROW(validate(out, "soup")) << "case " << k;
    EXPECT_TRUE(find_crossings(out).empty()) << "case " << k;
    EXPECT_TRUE(find_vertices_on_segments(out).empty()) << "case " << k;
    if (!in.point_markers.empty()) {
      EXPECT_EQ(out.point_markers.size(), out.points.size());
    }
    // Every point of the result is used by a segment or was a free input point.
    const auto d = degrees(out);
    std::vector<char> free_in(in.points.size(), 1);
    for (const auto& s : in.segments) free_in[s.a] = free_in[s.b] = 0;
    for (std::size_t v = 0; v < out.points.size(); ++v) {
      if (d[v] > 0) continue;
      bool was_free = false;
      for (std::size_t i = 0; i < in.points.size(); ++i)
        if (free_in[i] && in.points[i] == out.points[v]) was_free = true;
      EXPECT_TRUE(was_free) << "case " << k << " point " << v;
    }
    // Determinism: a second run gives the same bits.
    std::vector<Repair> rep2;
    expect_identical(out, clean(in, opt, &rep2));
    EXPECT_EQ(rep.size(), rep2.size());
    // Idempotence: a clean PSLG needs no repair.
    std::vector<Repair> rep3;
    const Pslg again = clean(out, opt, &rep3);
    EXPECT_TRUE(rep3.empty()) << "case " << k << ": " << (rep3.empty() ? "" : rep3[0].kind);
    expect_identical(out, again);
  }
}

TEST(Clean, BowTieIsSplit) {
  Pslg g = read_poly(testdata("poly/invalid_crossing.poly"));
  std::vector<Repair> rep;
  const Pslg out = clean(g, {}, &rep);
  EXPECT_NO_THROW(validate(out, "bowtie"));
  ASSERT_EQ(out.points.size(), 5u);
  EXPECT_EQ(out.points[4], (Point2{1, 1}));
  EXPECT_EQ(out.segments.size(), 6u);
  EXPECT_EQ(degrees(out)[4], 4);
  ASSERT_EQ(count_kind(rep, "crossing_split"), 1u);
  EXPECT_EQ(rep[0].where, (Point2{1, 1}));
}

TEST(Clean, TwoCrossingRingsAreSplit) {
  Pslg g;
  add_ring(&g, {{0, 0}, {4, 0}, {4, 4}, {0, 4}}, 0);
  add_ring(&g, {{2, 1}, {6, 1}, {6, 3}, {2, 3}}, 1);
  std::vector<Repair> rep;
  const Pslg out = clean(g, {}, &rep);
  EXPECT_NO_THROW(validate(out, "rings"));
  EXPECT_EQ(count_kind(rep, "crossing_split"), 2u);
  EXPECT_EQ(out.points.size(), 10u);
  EXPECT_EQ(out.segments.size(), 12u);
  // Parts are carried onto the pieces.
  std::map<std::int32_t, int> per_part;
  for (const auto& s : out.segments) ++per_part[s.part];
  EXPECT_EQ(per_part[0], 6);
  EXPECT_EQ(per_part[1], 6);
}

TEST(Clean, SpikeIsCancelled) {
  // Square ring with a backtracking spike a->b->a out of its top edge: 0 1 2 S 2' 3 where the
  // ring revisits point 2 via a duplicate of it.
  Pslg g;
  g.points = {{0, 0}, {4, 0}, {4, 4}, {6, 7}, {4, 4}, {0, 4}};
  for (Index i = 0; i < 6; ++i) g.segments.push_back({i, (i + 1) % 6, 1, 0});
  std::vector<Repair> rep;
  const Pslg out = clean(g, {}, &rep);
  EXPECT_NO_THROW(validate(out, "spike"));
  EXPECT_EQ(out.points.size(), 4u);  // the spike tip is gone
  EXPECT_EQ(out.segments.size(), 4u);
  EXPECT_EQ(count_kind(rep, "backtrack"), 1u);
  EXPECT_EQ(count_kind(rep, "snap"), 1u);
  for (const auto& p : out.points) EXPECT_FALSE(p == (Point2{6, 7}));
}

TEST(Clean, CollinearSpikeAndOverlapCancel) {
  // Ring 0->1->2->3->0 plus a spike running back along the bottom edge: 1 -> (2,0) -> 1
  // expressed as an overlapping detour 0->(3,0)->(1,0)->(4,0)...
  Pslg g;
  g.points = {{0, 0}, {3, 0}, {1, 0}, {4, 0}, {4, 4}, {0, 4}};
  for (Index i = 0; i < 6; ++i) g.segments.push_back({i, (i + 1) % 6, 1, 7});
  std::vector<Repair> rep;
  const Pslg out = clean(g, {}, &rep);
  EXPECT_NO_THROW(validate(out, "zigzag"));
  // The zig-zag 0->3->1->4 covers [1,3] three times: one copy survives, the square is intact.
  double len = 0;
  for (const auto& s : out.segments) len += dist(out.points[s.a], out.points[s.b]);
  EXPECT_DOUBLE_EQ(len, 16.0);
  EXPECT_GE(count_kind(rep, "backtrack"), 1u);
  EXPECT_GE(count_kind(rep, "overlap_split"), 1u);
}

TEST(Clean, SharedEdgeCancelsAndBreaklinesMerge) {
  Pslg g;
  add_ring(&g, {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, 0);
  add_ring(&g, {{1, 0}, {2, 0}, {2, 1}, {1, 1}}, 1);
  // Two copies of a breakline inside, and one on top of a boundary edge.
  g.points.push_back({0.2, 0.5});
  g.points.push_back({0.8, 0.5});
  g.segments.push_back({8, 9, kBreaklineMarker, 2});
  g.segments.push_back({9, 8, kBreaklineMarker, 3});
  g.segments.push_back({0, 1, kBreaklineMarker, 4});
  std::vector<Repair> rep;
  const Pslg out = clean(g, {}, &rep);
  EXPECT_NO_THROW(validate(out, "merge"));
  EXPECT_EQ(count_kind(rep, "backtrack"), 1u);            // the shared edge x = 1
  EXPECT_EQ(count_kind(rep, "duplicate_segment"), 2u);    // breakline copy + breakline on boundary
  int breaklines = 0;
  for (const auto& s : out.segments) breaklines += s.marker == kBreaklineMarker;
  EXPECT_EQ(breaklines, 1);
  EXPECT_EQ(out.segments.size(), 7u);  // 6 boundary edges of the 2x1 rectangle + 1 breakline
}

TEST(Clean, SnapMergesNearPointsKeepingLowestIndex) {
  Pslg g;
  g.points = {{0, 0}, {10, 0}, {10.0004, 0.0003}, {10, 10}, {5, 5}};  // 4: a free point
  g.segments = {{0, 1, 1, 0}, {2, 3, 1, 0}, {3, 0, 1, 0}};
  CleanOptions opt;
  opt.snap_distance = 1e-3;
  std::vector<Repair> rep;
  const Pslg out = clean(g, opt, &rep);
  EXPECT_NO_THROW(validate(out, "snap"));
  ASSERT_EQ(out.points.size(), 4u);
  EXPECT_EQ(out.points[1], (Point2{10, 0}));
  EXPECT_EQ(out.points[3], (Point2{5, 5}));  // free points are kept
  ASSERT_EQ(count_kind(rep, "snap"), 1u);
  EXPECT_NEAR(rep[0].size, 5e-4, 1e-12);
}

TEST(Clean, ZeroLengthAndFreePointOnSegment) {
  Pslg g;
  g.points = {{0, 0}, {2, 0}, {0, 0}, {1, 0}};
  g.segments = {{0, 1, 1, 0}, {0, 2, 1, 0}};
  std::vector<Repair> rep;
  const Pslg out = clean(g, {}, &rep);
  EXPECT_NO_THROW(validate(out, "zl"));
  EXPECT_EQ(count_kind(rep, "zero_length"), 1u);
  EXPECT_EQ(count_kind(rep, "vertex_on_segment"), 1u);
  EXPECT_EQ(out.segments.size(), 2u);
}

TEST(Clean, TinyRingsDropWithSpacing) {
  Pslg g;
  add_ring(&g, {{0, 0}, {100, 0}, {100, 100}, {0, 100}}, 0);
  add_ring(&g, {{10, 10}, {11, 10}, {11, 11}, {10, 11}}, 1);      // 1 m^2
  add_ring(&g, {{50, 50}, {60, 50}, {60, 60}, {50, 60}}, 2);      // 100 m^2
  add_ring(&g, {{80, 80}, {80.5, 80}, {80.5, 81}}, 3);             // 0.25 m^2
  // A bow-tie island (figure eight after splitting) with 2 x 0.25 m^2.
  add_ring(&g, {{20, 20}, {21, 21}, {21, 20}, {20, 21}}, 4);
  CleanOptions opt;
  opt.min_island_area_factor = 1.0;
  opt.spacing = [](Point2) { return 3.0; };  // limit 9 m^2
  std::vector<Repair> rep;
  const Pslg out = clean(g, opt, &rep);
  EXPECT_NO_THROW(validate(out, "islands"));
  EXPECT_EQ(count_kind(rep, "tiny_island"), 3u);
  std::map<std::int32_t, int> per_part;
  for (const auto& s : out.segments) ++per_part[s.part];
  EXPECT_EQ(per_part.count(1), 0u);
  EXPECT_EQ(per_part.count(3), 0u);
  EXPECT_EQ(per_part.count(4), 0u);
  EXPECT_EQ(per_part[0], 4);
  EXPECT_EQ(per_part[2], 4);
  EXPECT_EQ(out.points.size(), 8u);
  for (const auto& r : rep)
    if (r.kind == "tiny_island" && r.part == 1) {
      EXPECT_DOUBLE_EQ(r.size, 1.0);
      EXPECT_DOUBLE_EQ(r.where.x, 10.5);
    }
  // Without a spacing function the factor cannot be applied.
  CleanOptions bad = opt;
  bad.spacing = nullptr;
  expect_error([&] { clean(g, bad, nullptr); }, ExitCode::kInvalidSpacing, {"spacing"});
  bad.spacing = [](Point2) { return -1.0; };
  expect_error([&] { clean(g, bad, nullptr); }, ExitCode::kInvalidSpacing, {"spacing f"});
}

TEST(Clean, SimplifyRemovesShortEdgesWithinTolerance) {
  // A 100 m square whose bottom edge is a zig-zag of 1 m steps with 0.05 m amplitude.
  Pslg g;
  std::vector<Point2> ring;
  for (int i = 0; i < 100; ++i) ring.push_back({static_cast<double>(i), (i % 2) ? 0.05 : 0.0});
  ring.push_back({100, 0});
  ring.push_back({100, 100});
  ring.push_back({0, 100});
  add_ring(&g, ring, 0);
  g.points.push_back({50.5, 0.04});  // a free point just inside, above the zig-zag at x = 50.5
  CleanOptions opt;
  opt.simplify_factor = 0.5;
  opt.simplify_tolerance = 0.1;
  opt.spacing = [](Point2) { return 4.0; };  // edges < 2 m are candidates
  std::vector<Repair> rep;
  const Pslg out = clean(g, opt, &rep);
  EXPECT_NO_THROW(validate(out, "simplify"));
  const std::size_t removed = count_kind(rep, "simplify");
  EXPECT_GT(removed, 30u);
  EXPECT_EQ(out.points.size(), g.points.size() - removed);
  for (const auto& r : rep) {
    if (r.kind == "simplify") { EXPECT_LT(r.size, 0.1); }
  }
  // The free point must not change side: it stays above every bottom segment covering x = 50.5.
  const Index fp = static_cast<Index>(out.points.size() - 1);
  EXPECT_EQ(out.points[fp], (Point2{50.5, 0.04}));
  for (const auto& s : out.segments) {
    const Point2 a = out.points[s.a], b = out.points[s.b];
    if (a.y < 1 && b.y < 1 && std::min(a.x, b.x) <= 50.5 && std::max(a.x, b.x) >= 50.5) {
      const Point2 l = a.x < b.x ? a : b, r = a.x < b.x ? b : a;
      EXPECT_EQ(predicates::orient2d(l, r, out.points[fp]), 1);
    }
  }
  // The three long edges were not touched; no new edge is longer than two old ones.
  int long_edges = 0;
  for (const auto& s : out.segments) {
    const double len = dist(out.points[s.a], out.points[s.b]);
    long_edges += len >= 99;
    EXPECT_TRUE(len >= 99 || len < 2.01) << len;
  }
  EXPECT_EQ(long_edges, 3);
}

TEST(Clean, FreePointOnSegmentStaysAVertexWhenSimplifying) {
  // Regression (stress case): a free point split into a segment must not be simplified away.
  Pslg g;
  g.points = {{0, 0}, {1, 0}, {1, 1}, {0.5, 0}};
  g.segments = {{0, 1, 1, 0}, {1, 2, 1, 0}, {2, 0, 1, 0}};
  CleanOptions opt;
  opt.simplify_factor = 1;
  opt.simplify_tolerance = 0.1;  // only the free point (deviation 0) would qualify
  opt.spacing = [](Point2) { return 10.0; };
  std::vector<Repair> rep;
  const Pslg out = clean(g, opt, &rep);
  EXPECT_NO_THROW(validate(out, "free"));
  EXPECT_EQ(count_kind(rep, "vertex_on_segment"), 1u);
  EXPECT_EQ(count_kind(rep, "simplify"), 0u);
  ASSERT_EQ(out.points.size(), 4u);
  EXPECT_EQ(out.points[3], (Point2{0.5, 0}));
  EXPECT_EQ(out.segments.size(), 4u);
}

TEST(Clean, IterationCapThrowsWithLocation) {
  // Zero splitting rounds allowed: the bow-tie cannot be repaired.
  Pslg g = read_poly(testdata("poly/invalid_crossing.poly"));
  CleanOptions opt;
  opt.max_iterations = 0;
  expect_error([&] { clean(g, opt, nullptr); }, ExitCode::kInvalidGeometry, {"clean:", "near ("});
}

TEST(Clean, ManyNearParallelCrossingsConverge) {
  // A fan of long, nearly parallel segments all crossing each other: rounded intersection points
  // create new crossings, which the iteration must resolve.
  Pslg g;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 60; ++i) {
    const Index a = static_cast<Index>(g.points.size());
    g.points.push_back({0, u(rng)});
    g.points.push_back({1000, u(rng) * 1e-3 + 0.5 * u(rng)});
    g.segments.push_back({a, a + 1, 1, i});
  }
  std::vector<Repair> rep;
  const Pslg out = clean(g, {}, &rep);
  EXPECT_NO_THROW(validate(out, "fan"));
  EXPECT_GT(count_kind(rep, "crossing_split"), 100u);
  expect_identical(out, clean(g, {}, nullptr));
}

TEST(Clean, KeepsHolesRegionsOrigin) {
  Pslg g = read_poly(testdata("poly/interior_segment.poly"));
  g.origin = {5e5, 6e6};
  g.holes.push_back({1, 1});
  const Pslg out = clean(g, {}, nullptr);
  EXPECT_EQ(out.origin, g.origin);
  EXPECT_EQ(out.holes.size(), 1u);
  EXPECT_EQ(out.regions.size(), 1u);
  expect_identical(out, g);
}
