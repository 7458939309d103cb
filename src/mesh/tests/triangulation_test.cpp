// Triangulation's storage: slots killed and reused, the segment of every subsegment after splits,
// input point markers beside the Steiner points' segment indices, and take_view over all of it.
#include <gtest/gtest.h>
#include "mesh/check.hpp"
#include "mesh/take_view.hpp"
#include "mesh/triangulation.hpp"

namespace fdr::mesh {
namespace {

// The unit square as two triangles (0 1 2) and (0 2 3), boundary edges constrained: 0-1 and 1-2
// are input segment 0 and 1; 2-3 and 3-0 belong to no segment (a hull).
Triangulation square() {
  Triangulation t;
  t.add_vertex({0, 0}, VertexKind::kInput);
  t.add_vertex({1, 0}, VertexKind::kInput);
  t.add_vertex({1, 1}, VertexKind::kInput);
  t.add_vertex({0, 1}, VertexKind::kInput);
  t.set_point_marker(1, 7);
  t.new_triangle(0, 1, 2);
  t.new_triangle(0, 2, 3);
  t.link(2, 3);  // 2->0 of the first, 0->2 of the second
  t.add_input_segment({0, 1, 11, 0});
  t.add_input_segment({1, 2, 12, 1});
  const Index ring[4][3] = {{0, 1, 0}, {1, 2, 1}, {2, 3, kNoId}, {3, 0, kNoId}};
  for (const auto& e : ring) {
    t.set_constrained(t.find_edge(e[0], e[1]), true);
    t.set_segment(e[0], e[1], e[2]);
  }
  return t;
}

TEST(Triangulation, KilledSlotsAreReusedLastFreedFirst) {
  Triangulation t = square();
  EXPECT_EQ(t.num_slots(), 2u);
  t.kill_triangle(0);
  t.kill_triangle(1);
  EXPECT_TRUE(t.dead(0));
  EXPECT_EQ(t.num_live_triangles(), 0u);
  const TriangleId a = t.new_triangle(0, 1, 3);
  EXPECT_EQ(a, 1u);  // the last freed
  EXPECT_FALSE(t.dead(a));
  EXPECT_FALSE(t.constrained(3 * a));  // a reused slot starts without constraints or twins
  EXPECT_EQ(t.twin(3 * a), kNoId);
  EXPECT_EQ(t.corner(a, 2), 3u);
  EXPECT_EQ(t.vertex_edge(3), 3 * a + 2);
  EXPECT_EQ(t.new_triangle(1, 2, 3), 0u);
  EXPECT_EQ(t.new_triangle(0, 1, 2), 2u);  // no free slot left: a new one
  EXPECT_EQ(t.num_slots(), 3u);
  EXPECT_EQ(t.num_live_triangles(), 3u);
}

TEST(Triangulation, RegionsGrowWithTheSlots) {
  Triangulation t = square();
  EXPECT_FALSE(t.has_regions());
  EXPECT_EQ(t.region(1), -1);
  t.init_regions();
  t.set_region(1, 4);
  for (int i = 0; i < 100; ++i) {
    const TriangleId n = t.new_triangle(0, 1, 2);
    t.set_region(n, i % 3);
  }
  EXPECT_EQ(t.region(0), -1);
  EXPECT_EQ(t.region(1), 4);
  EXPECT_EQ(t.region(101), 99 % 3);
  EXPECT_EQ(t.region(500), -1);  // beyond the slots
}

TEST(Triangulation, HalfEdgeCornersAndMarks) {
  Triangulation t = square();
  EXPECT_EQ(t.org(4), 2u);
  EXPECT_EQ(t.dst(4), 3u);
  EXPECT_EQ(t.apex(4), 0u);
  EXPECT_EQ(t.dst(5), 0u);
  EXPECT_EQ(t.apex(3), 3u);
  t.mark(1, Triangulation::kMarkA);
  EXPECT_TRUE(t.marked(1, Triangulation::kMarkA | Triangulation::kMarkB));
  EXPECT_FALSE(t.marked(0, Triangulation::kMarkA));
  t.unmark(1, Triangulation::kMarkA);
  EXPECT_FALSE(t.marked(1, Triangulation::kMarkA));
  EXPECT_TRUE(t.constrained(4));  // marks leave the constraint bits alone
  t.clear_constraints(1);
  EXPECT_FALSE(t.constrained(4));
  EXPECT_FALSE(t.dead(1));
}

TEST(Triangulation, SegmentOfInputPairsAndSteinerPoints) {
  Triangulation t = square();
  EXPECT_EQ(t.segment_of(0, 1), 0u);
  EXPECT_EQ(t.segment_of(1, 0), 0u);
  EXPECT_EQ(t.segment_of(2, 1), 1u);
  EXPECT_EQ(t.segment_of(2, 3), kNoId);  // hull
  EXPECT_EQ(t.segment_of(0, 2), kNoId);  // no subsegment
  // Split 0-1 at a Steiner point, then the half 4-1 again: every piece keeps segment 0.
  const Index v = t.add_vertex({0.5, 0}, VertexKind::kSegment);
  t.split_segment(0, 1, v);
  const Index w = t.add_vertex({0.75, 0}, VertexKind::kSegment);
  t.split_segment(v, 1, w);
  EXPECT_EQ(t.segment_of(0, v), 0u);
  EXPECT_EQ(t.segment_of(v, w), 0u);
  EXPECT_EQ(t.segment_of(1, w), 0u);
  EXPECT_EQ(t.segment_of_vertex(v), 0u);
  EXPECT_EQ(t.segment_of_vertex(1), kNoId);
  EXPECT_EQ(t.segment_vertex_index(v), 0u);
  EXPECT_EQ(t.segment_vertex_index(w), 1u);
  EXPECT_EQ(t.segment_vertex_index(0), kNoId);
  // A hull edge split: the Steiner point belongs to no segment.
  const Index h = t.add_vertex({0.5, 1}, VertexKind::kSegment);
  t.split_segment(2, 3, h);
  EXPECT_EQ(t.segment_of(2, h), kNoId);
  EXPECT_EQ(t.segment_vertex_index(h), 2u);
  // Markers: input vertices keep theirs, Steiner points have none.
  EXPECT_EQ(t.point_marker(1), 7);
  EXPECT_EQ(t.point_marker(v), 0);
  t.set_point_marker(v, 5);  // ignored: a Steiner point has no marker
  EXPECT_EQ(t.point_marker(v), 0);
  EXPECT_EQ(t.segment_of(0, v), 0u);
}

TEST(Triangulation, FindSubsegmentSeesSplits) {
  Triangulation t = square();
  EXPECT_NE(t.find_subsegment(0, 1), kNoId);
  EXPECT_EQ(t.find_subsegment(0, 2), kNoId);  // an edge, not constrained
  // Split 0-1 at v by hand: triangle 0 becomes (0 v 2) + (v 1 2).
  const Index v = t.add_vertex({0.5, 0}, VertexKind::kSegment);
  const HalfEdge diag = t.twin(2);
  t.kill_triangle(0);
  const TriangleId a = t.new_triangle(0, v, 2), b = t.new_triangle(v, 1, 2);
  t.link(3 * a + 1, 3 * b + 2);
  t.link(3 * a + 2, diag);
  t.set_constrained(3 * a, true);
  t.set_constrained(3 * b, true);
  t.set_constrained(3 * b + 1, true);
  t.split_segment(0, 1, v);
  EXPECT_EQ(t.find_subsegment(0, 1), kNoId);  // stale: split
  EXPECT_EQ(t.find_subsegment(0, v), 3 * a);
  EXPECT_EQ(t.find_subsegment(1, v), 3 * b);
  EXPECT_EQ(t.find_subsegment(v, 2), kNoId);
  EXPECT_TRUE(check_topology(t).ok());
  EXPECT_TRUE(check_segments(t).ok());
  const MeshEdge e = t.mesh_edge(3 * b);
  EXPECT_EQ(e.marker, 11);
  EXPECT_EQ(e.part, 0);
}

TEST(Triangulation, TakeViewMarkersAndEdgesAsToView) {
  Triangulation t = square();
  const Index v = t.add_vertex({0.5, 0}, VertexKind::kSegment);
  const HalfEdge diag = t.twin(2);
  t.kill_triangle(0);
  const TriangleId a = t.new_triangle(0, v, 2), b = t.new_triangle(v, 1, 2);
  t.link(3 * a + 1, 3 * b + 2);
  t.link(3 * a + 2, diag);
  for (HalfEdge h : {3 * a, 3 * b, 3 * b + 1}) t.set_constrained(h, true);
  t.split_segment(0, 1, v);
  const MeshView want = t.to_view();
  const MeshView got = take_view(t);
  EXPECT_EQ(got.vertices, want.vertices);
  EXPECT_EQ(got.triangles, want.triangles);
  EXPECT_EQ(got.neighbours, want.neighbours);
  EXPECT_EQ(got.vertex_marker, want.vertex_marker);
  ASSERT_EQ(got.edges.size(), want.edges.size());
  for (std::size_t i = 0; i < got.edges.size(); ++i) {
    EXPECT_EQ(got.edges[i].a, want.edges[i].a);
    EXPECT_EQ(got.edges[i].marker, want.edges[i].marker);
    EXPECT_EQ(got.edges[i].part, want.edges[i].part);
  }
  // The Steiner point takes its segment's marker (11), input vertex 1 keeps its own (7).
  EXPECT_EQ(want.vertex_marker[v], 11);
  EXPECT_EQ(want.vertex_marker[1], 7);
  EXPECT_EQ(t.num_vertices(), 0u);
}

}  // namespace
}  // namespace fdr::mesh
