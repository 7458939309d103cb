// build_cdt's steps one by one, and the triangulation's segment lookup through splits and flips
// against a map from vertex pairs (what the lookup replaced).
#include <gtest/gtest.h>
#include <map>
#include <random>
#include "cdt/insert.hpp"
#include "cdt/steps.hpp"
#include "cdt/tests/test_inputs.hpp"
#include "mesh/check.hpp"
#include "predicates/predicates.hpp"

using namespace fdr;
using fdr::testing::random_pslg;

namespace {

// Outer square, a hole square and an island square inside the hole (markers as given).
pslg::Pslg nested_squares(int middle_marker) {
  pslg::Pslg p;
  auto square = [&](double lo, double hi, int marker) {
    const Index b = static_cast<Index>(p.points.size());
    p.points.insert(p.points.end(), {{lo, lo}, {hi, lo}, {hi, hi}, {lo, hi}});
    for (Index i = 0; i < 4; ++i) p.segments.push_back({b + i, b + (i + 1) % 4, marker, static_cast<int>(b)});
  };
  square(0, 10, 1);
  square(2, 8, middle_marker);
  square(4, 6, 1);
  return p;
}

// The triangulation after the segments, before any region is removed.
mesh::Triangulation with_segments(const pslg::Pslg& p, std::vector<Index>* alias_out = nullptr) {
  mesh::Triangulation T;
  const Box2 box = p.bbox();
  cdt::start_triangulation(T, p, box);
  const std::vector<Index> alias = cdt::insert_points(T, p, box, "test", nullptr);
  cdt::insert_segments(T, p, alias, "test", nullptr);
  if (alias_out) *alias_out = alias;
  return T;
}

// The component of the triangle that strictly contains p (kNoId if p is on an edge: the test
// points are chosen off every edge).
Index component_at(const mesh::Triangulation& T, const cdt::Components& c, Point2 p) {
  for (TriangleId t = 0; t < T.num_slots(); ++t) {
    if (T.dead(t)) continue;
    const Point2 a = T.point(T.corner(t, 0)), b = T.point(T.corner(t, 1)), d = T.point(T.corner(t, 2));
    if (predicates::orient2d(a, b, p) > 0 && predicates::orient2d(b, d, p) > 0 && predicates::orient2d(d, a, p) > 0)
      return c.of_slot[t];
  }
  return kNoId;
}

}  // namespace

TEST(CdtSteps, StartAndInsertPointsKeepInputIdsAndAliasDuplicates) {
  pslg::Pslg p = random_pslg(3, 10, 0);
  p.points.push_back(p.points[4]);  // a duplicate
  p.point_markers.assign(p.points.size(), 0);
  p.point_markers[2] = 9;
  mesh::Triangulation T;
  const Box2 box = p.bbox();
  cdt::start_triangulation(T, p, box);
  EXPECT_EQ(T.num_vertices(), p.points.size() + 3);
  EXPECT_EQ(T.num_live_triangles(), 1u);
  EXPECT_EQ(T.kind(static_cast<Index>(p.points.size())), mesh::VertexKind::kSuper);
  EXPECT_EQ(T.point_marker(2), 9);
  cdt::CdtStats st;
  const std::vector<Index> alias = cdt::insert_points(T, p, box, "test", &st);
  EXPECT_EQ(st.duplicate_points, 1u);
  EXPECT_EQ(alias.back(), 4u);
  for (Index i = 0; i + 1 < alias.size(); ++i) EXPECT_EQ(alias[i], i);
  EXPECT_EQ(T.num_vertices(), p.points.size() + 3);  // no vertex added by the insertion
  EXPECT_TRUE(mesh::check_topology(T).ok());
  EXPECT_TRUE(mesh::check_delaunay(T).ok());
  EXPECT_EQ(T.vertex_edge(static_cast<Index>(p.points.size()) - 1), kNoId);  // the duplicate
}

TEST(CdtSteps, ComponentsDepthAndRemoval) {
  const pslg::Pslg p = nested_squares(2);
  mesh::Triangulation T = with_segments(p);
  EXPECT_TRUE(mesh::check_segments(T).ok());
  const cdt::Components c = cdt::find_components(T);
  ASSERT_EQ(c.size(), 4u);  // outside, outer ring, hole ring, island
  const Index out = component_at(T, c, {-1.3, -0.7}), ring = component_at(T, c, {1.1, 0.37}), hole = component_at(T, c, {3.3, 2.71}),
              island = component_at(T, c, {5.13, 4.77});
  EXPECT_TRUE(c.touches_super[out]);
  EXPECT_FALSE(c.touches_super[island]);
  const std::vector<int> depth = cdt::nesting_depth(c);
  EXPECT_EQ(depth[out], 0);
  EXPECT_EQ(depth[ring], 1);
  EXPECT_EQ(depth[hole], 2);
  EXPECT_EQ(depth[island], 3);
  cdt::CdtOptions parity;
  parity.regions = cdt::CdtOptions::Regions::kParity;
  const std::vector<bool> by_parity = cdt::components_to_remove(T, p, parity, c, depth);
  EXPECT_TRUE(by_parity[out] && by_parity[hole] && !by_parity[ring] && !by_parity[island]);
  pslg::Pslg seeded = p;
  seeded.holes.push_back({5, 5});
  cdt::CdtOptions seeds;
  seeds.regions = cdt::CdtOptions::Regions::kSeeds;
  const std::vector<bool> by_seeds = cdt::components_to_remove(T, seeded, seeds, c, depth);
  EXPECT_TRUE(by_seeds[out] && by_seeds[island] && !by_seeds[ring] && !by_seeds[hole]);
  cdt::CdtStats st;
  cdt::remove_components(T, c, by_seeds, &st);
  EXPECT_GT(st.removed_triangles, 0u);
  EXPECT_NEAR(T.area(), 100 - 4, 1e-12);
}

TEST(CdtSteps, BreaklinesDoNotCountForDepth) {
  const pslg::Pslg p = nested_squares(pslg::kBreaklineMarker);
  mesh::Triangulation T = with_segments(p);
  const cdt::Components c = cdt::find_components(T);
  const std::vector<int> depth = cdt::nesting_depth(c);
  EXPECT_EQ(depth[component_at(T, c, {1.1, 0.37})], 1);
  EXPECT_EQ(depth[component_at(T, c, {3.3, 2.71})], 1);  // across the breakline: the same depth
  EXPECT_EQ(depth[component_at(T, c, {5.13, 4.77})], 2);
}

TEST(CdtSteps, RegionsAreAssignedPerComponentLaterSeedWins) {
  pslg::Pslg p = nested_squares(2);
  p.regions.push_back({{1.1, 0.37}, 0, 0});
  p.regions.push_back({{5.13, 4.77}, 0, 0});
  p.regions.push_back({{9.3, 9.1}, 0, 0});  // the same ring as the first: wins
  mesh::Triangulation T = with_segments(p);
  const cdt::Components c = cdt::find_components(T);
  cdt::assign_regions(T, p, c);
  ASSERT_TRUE(T.has_regions());
  for (TriangleId t = 0; t < T.num_slots(); ++t) {
    if (T.dead(t)) continue;
    const Index k = c.of_slot[t];
    if (k == component_at(T, c, {1.1, 0.37})) EXPECT_EQ(T.region(t), 2);
    else if (k == component_at(T, c, {5.13, 4.77})) EXPECT_EQ(T.region(t), 1);
    else EXPECT_EQ(T.region(t), -1);
  }
}

// Random subsegment splits (at rounded midpoints, through the Inserter) and random flips of
// unconstrained edges; after each round every constrained edge's segment is the one a map from
// vertex pairs, kept as the old code kept it, gives, and split subsegments are no longer found.
TEST(CdtSteps, SegmentLookupFollowsSplitsAndFlips) {
  for (unsigned seed : {5u, 11u}) {
    const pslg::Pslg p = random_pslg(seed, 25, 10);
    mesh::Triangulation T = cdt::build_cdt(p);
    auto key = [](Index a, Index b) { return a < b ? std::make_pair(a, b) : std::make_pair(b, a); };
    std::map<std::pair<Index, Index>, Index> want;
    for (TriangleId t = 0; t < T.num_slots(); ++t)
      for (int k = 0; k < 3 && !T.dead(t); ++k) {
        const HalfEdge h = 3 * t + static_cast<Index>(k);
        if (T.constrained(h)) want[key(T.org(h), T.dst(h))] = T.segment_of(T.org(h), T.dst(h));
      }
    ASSERT_FALSE(want.empty());
    std::mt19937 rng(seed);
    std::vector<std::pair<Index, Index>> gone;
    cdt::Inserter ins(T);
    for (int round = 0; round < 4; ++round) {
      for (int i = 0; i < 40; ++i) {  // splits
        const TriangleId t = static_cast<TriangleId>(rng() % T.num_slots());
        const HalfEdge h = 3 * t + rng() % 3;
        if (T.dead(t) || !T.constrained(h)) continue;
        const Index a = T.org(h), b = T.dst(h);
        const Point2 m = 0.5 * (T.point(a) + T.point(b));
        if (!ins.build_cavity(m, {cdt::LocateKind::kOnEdge, h})) continue;
        const Index v = ins.commit(m, mesh::VertexKind::kSegment);
        const Index s = want.at(key(a, b));
        want.erase(key(a, b));
        gone.push_back({a, b});
        want[key(a, v)] = want[key(v, b)] = s;
        EXPECT_EQ(T.segment_of_vertex(v), s);
      }
      for (int i = 0; i < 40; ++i) {  // flips of convex unconstrained interior edges
        const TriangleId t = static_cast<TriangleId>(rng() % T.num_slots());
        const HalfEdge h = 3 * t + rng() % 3;
        if (T.dead(t) || T.constrained(h) || T.twin(h) == kNoId) continue;
        const Index a = T.org(h), b = T.dst(h), c = T.apex(h), d = T.apex(T.twin(h));
        using predicates::orient2d;
        if (orient2d(T.point(c), T.point(d), T.point(a)) * orient2d(T.point(c), T.point(d), T.point(b)) >= 0) continue;
        cdt::flip_edge(T, h);
      }
      ASSERT_TRUE(mesh::check_topology(T).ok());
      std::size_t constrained = 0;
      for (TriangleId t = 0; t < T.num_slots(); ++t)
        for (int k = 0; k < 3 && !T.dead(t); ++k) {
          const HalfEdge h = 3 * t + static_cast<Index>(k);
          if (!T.constrained(h)) continue;
          ++constrained;
          const auto it = want.find(key(T.org(h), T.dst(h)));
          ASSERT_NE(it, want.end());
          EXPECT_EQ(T.segment_of(T.org(h), T.dst(h)), it->second);
          EXPECT_NE(T.find_subsegment(T.org(h), T.dst(h)), kNoId);
        }
      EXPECT_GT(constrained, 0u);
      for (const auto& [a, b] : gone) EXPECT_EQ(T.find_subsegment(a, b), kNoId);
      EXPECT_TRUE(mesh::check_segments(T).ok());
    }
    EXPECT_FALSE(gone.empty());
  }
}
