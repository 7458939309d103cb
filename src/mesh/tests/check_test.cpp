// mesh checkers: a valid hand-built mesh passes; each invariant broken on purpose is caught.
#include <gtest/gtest.h>
#include <cmath>
#include "mesh/check.hpp"

namespace fdr::mesh {
namespace {

// Two triangles over the edge (0,0)-(4,0):     2 (2,1)
//                                             /   \      triangle 0: 0 1 2  (upper)
//                                 (0,0) 0 ------- 1 (4,0)
//                                             \   /      triangle 1: 1 0 3  (lower)
//                                               3 (2,-y)
// With y = 5 the shared edge is locally Delaunay; with y = 1 vertex 3 lies inside the
// circumcircle of triangle 0 (centre (2,-1.5), radius 2.5), so the edge is not.
Triangulation kite(double y) {
  Triangulation t;
  t.add_vertex({0, 0}, VertexKind::kInput);
  t.add_vertex({4, 0}, VertexKind::kInput);
  t.add_vertex({2, 1}, VertexKind::kInput);
  t.add_vertex({2, -y}, VertexKind::kInput);
  t.new_triangle(0, 1, 2);
  t.new_triangle(1, 0, 3);
  t.link(0, 3);  // half-edge 0->1 of triangle 0 and 1->0 of triangle 1
  // Boundary segments (outer ring), each its own input segment, constrained.
  const Index ring[4][2] = {{1, 2}, {2, 0}, {0, 3}, {3, 1}};
  for (Index s = 0; s < 4; ++s) {
    t.add_input_segment({ring[s][0], ring[s][1], 1, 0});
    t.set_segment(ring[s][0], ring[s][1], s);
    t.set_constrained(t.find_edge(ring[s][0], ring[s][1]), true);
  }
  return t;
}

TEST(MeshCheck, ValidMeshPasses) {
  const Triangulation t = kite(5);
  const CheckResult r = check_all(t);
  EXPECT_TRUE(r.ok()) << (r.problems.empty() ? "" : r.problems[0]);
  EXPECT_TRUE(check_spacing(t, [](Point2) { return 10.0; }, 1.0).ok());
}

TEST(MeshCheck, FlippedOrientation) {
  Triangulation t = kite(5);
  t.set_corners(0, t.corner(0, 1), t.corner(0, 0), t.corner(0, 2));  // triangle 0 becomes clockwise (and its twin endpoints mismatch)
  const CheckResult r = check_topology(t);
  ASSERT_FALSE(r.ok());
  bool orientation = false;
  for (const auto& p : r.problems) orientation |= p.find("not counter-clockwise") != std::string::npos;
  EXPECT_TRUE(orientation);
}

TEST(MeshCheck, BrokenTwin) {
  Triangulation t = kite(5);
  t.set_twin(3, 1);  // half-edge 3 claims half-edge 1 as its twin; half-edge 1 does not agree
  const CheckResult r = check_topology(t);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.problems[0].find("twin"), std::string::npos);
  EXPECT_FALSE(check_all(t).ok());
}

TEST(MeshCheck, NonDelaunayEdge) {
  const Triangulation t = kite(1);
  EXPECT_TRUE(check_topology(t).ok());
  const CheckResult r = check_delaunay(t);
  ASSERT_EQ(r.count, 1u);
  EXPECT_NE(r.problems[0].find("not locally Delaunay"), std::string::npos);
  // A constrained edge may be non-Delaunay (constrained Delaunay).
  Triangulation c = kite(1);
  c.set_constrained(0, true);
  c.set_constrained(3, true);
  EXPECT_TRUE(check_delaunay(c).ok());
}

TEST(MeshCheck, MissingSegment) {
  Triangulation t = kite(5);
  // Input segment 2-3 (through the middle, crossing edge 0-1): not a chain of mesh edges.
  t.add_input_segment({2, 3, 4, 1});
  const CheckResult r = check_segments(t);
  ASSERT_EQ(r.count, 1u);
  EXPECT_NE(r.problems[0].find("input segment 4"), std::string::npos);
  // Dropping the constraint bits of an existing segment is caught too.
  Triangulation u = kite(5);
  u.set_constrained(u.find_edge(1, 2), false);
  EXPECT_FALSE(check_segments(u).ok());
}

TEST(MeshCheck, SpacingBoundViolated) {
  const Triangulation t = kite(5);
  // Circumradii are 2.5 and 2.9: fine for f = 3 with B = 1, bad for f = 2.
  EXPECT_TRUE(check_spacing(t, [](Point2) { return 3.0; }, 1.0).ok());
  const CheckResult r = check_spacing(t, [](Point2) { return 2.0; }, 1.0);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.problems[0].find("R/f(c)"), std::string::npos);
  EXPECT_FALSE(check_spacing(t, [](Point2) { return 0.0; }, 1.0).ok());  // f must be positive
}

}  // namespace
}  // namespace fdr::mesh
