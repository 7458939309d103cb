// Tests of the PLC checks: every kind of bad input gives its exit code and a message naming the
// source, facet, vertex and coordinates; good inputs pass.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "base/error.hpp"
#include "plc/check.hpp"
#include "plc/intersections.hpp"
#include "plc/tests/plc_samples.hpp"

namespace fdr::plc {
namespace {

using namespace samples;

// Runs f, expecting an Error with `code` whose message contains every piece of `parts`.
void expect_error(const std::function<void()>& f, ExitCode code, const std::vector<std::string>& parts) {
  try {
    f();
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), code) << e.what();
    for (const auto& s : parts) EXPECT_NE(std::string(e.what()).find(s), std::string::npos) << e.what();
  }
}

TEST(PlcCheck, GoodInputsPass) {
  EXPECT_NO_THROW(check(unit_cube()));
  EXPECT_NO_THROW(check(stacked_layers(3)));
  EXPECT_NO_THROW(check(box_with_internal_facets()));
  EXPECT_NO_THROW(check(wedge_prism(10)));
  EXPECT_NO_THROW(check(wedge_prism(1)));
  Plc p = unit_cube();
  p.segments.push_back({add_point(p, {0.5, 0.5, 0.25}), add_point(p, {0.5, 0.5, 0.75})});
  p.holes.push_back({0.1, 0.1, 0.1});
  EXPECT_NO_THROW(check(p));
  const FacetTriangulation ft = check_and_triangulate(unit_cube());
  EXPECT_EQ(ft.triangles.size(), 6u);
}

TEST(PlcCheck, TiltedBox) {
  const Point3 o{1, 2, 3}, e1{2, 0.5, 0.25}, e2{-0.5, 1.5, 0.75}, e3{0.25, -0.5, 2};
  Plc p = parallelepiped(o, e1, e2, e3);
  p.regions.push_back({o + 0.5 * (e1 + e2 + e3), 1, -1});
  const FacetTriangulation ft = check_and_triangulate(p);
  for (const auto& t : ft.triangles) EXPECT_EQ(t.size(), 2u);
  p.holes.push_back(o + 1.25 * e1 + 0.5 * e2);
  expect_error([&] { check(p); }, ExitCode::kInvalidGeometry, {"tilted.poly: volume hole point 0", "outside the domain"});
}

TEST(PlcCheck, BoxWithTunnel) {
  Plc p = box_with_tunnel();
  p.regions.push_back({{0.5, 0.5, 2}, 1, -1});
  const FacetTriangulation ft = check_and_triangulate(p);
  EXPECT_EQ(ft.triangles[0].size(), 8u);  // a square ring
  p.regions.push_back({{2, 2, 2}, 2, -1});  // inside the tunnel: outside the domain
  expect_error([&] { check(p); }, ExitCode::kInvalidGeometry, {"tunnel.poly: region point 1 (2, 2, 2)", "outside"});
  // Without one tunnel wall the surface is open.
  p = box_with_tunnel();
  p.facets.pop_back();
  expect_error([&] { check(p); }, ExitCode::kInvalidGeometry, {"not closed"});
}

TEST(PlcCheck, NonFiniteCoordinates) {
  Plc p = unit_cube();
  p.points[3].y = NAN;
  expect_error([&] { check(p); }, ExitCode::kInvalidGeometry, {"cube.poly", "vertex 3", "non-finite"});
  p = unit_cube();
  p.regions.push_back({{0.5, INFINITY, 0.5}, 1, -1});
  expect_error([&] { check(p); }, ExitCode::kInvalidGeometry, {"region point 0", "non-finite"});
  p = unit_cube();
  p.regions.push_back({{0.5, 0.5, 0.5}, 1, NAN});
  expect_error([&] { check(p); }, ExitCode::kInvalidGeometry, {"region point 0", "volume bound"});
}

TEST(PlcCheck, IdsOutOfRange) {
  Plc p = unit_cube();
  p.facets[2].polygons[0][1] = 99;
  expect_error([&] { check(p); }, ExitCode::kInputMalformed,
               {"cube.poly: facet 2 (marker 2) polygon 0", "vertex id 99", "8 points"});
  p = unit_cube();
  p.segments.push_back({0, 8});
  expect_error([&] { check(p); }, ExitCode::kInputMalformed, {"segment 0", "vertex id 8"});
  p = unit_cube();
  p.point_markers = {1, 2, 3};
  expect_error([&] { check(p); }, ExitCode::kInputMalformed, {"3 point markers for 8 points"});
}

TEST(PlcCheck, DuplicatePoints) {
  Plc p = unit_cube();
  add_point(p, {1, 1, 0});
  expect_error([&] { check(p); }, ExitCode::kInvalidGeometry, {"vertex 8 and vertex 3 coincide at (1, 1, 0)"});
}

TEST(PlcCheck, DegeneratePolygons) {
  Plc p = unit_cube();
  p.facets[1].polygons[0] = {4, 5, 5, 7, 6};
  expect_error([&] { check(p); }, ExitCode::kInvalidGeometry, {"facet 1 (marker 1) polygon 0 is degenerate", "vertex 5"});
  p = unit_cube();
  const VertexId m = add_point(p, {0.5, 0, 0});
  p.facets[0].polygons.push_back({0, m, 1});
  expect_error([&] { check(p); }, ExitCode::kInvalidGeometry, {"facet 0 (marker 0) polygon 1 is degenerate", "one line"});
  p = unit_cube();
  p.facets[0].polygons.push_back({});
  expect_error([&] { check(p); }, ExitCode::kInvalidGeometry, {"polygon 1 has no vertices"});
  p = unit_cube();
  p.segments.push_back({2, 2});
  expect_error([&] { check(p); }, ExitCode::kInvalidGeometry, {"segment 0 is degenerate"});
}

TEST(PlcCheck, NonPlanarFacet) {
  Plc p = unit_cube();
  p.points[6].z = 1.0000000000000002;  // a corner of the top facet, one ulp up
  expect_error([&] { check(p); }, ExitCode::kInvalidGeometry, {"facet 1 (marker 1) is not planar", "vertex 6"});
}

TEST(PlcCheck, FacetHolePoints) {
  Plc p = unit_cube();
  p.facets[0].holes.push_back({0.5, 0.5, 0.25});
  expect_error([&] { check(p); }, ExitCode::kInvalidGeometry,
               {"facet 0 (marker 0): hole point 0", "not in the facet's plane"});
  p = unit_cube();
  p.facets[0].holes.push_back({1.5, 0.5, 0});
  expect_error([&] { check(p); }, ExitCode::kInvalidGeometry, {"facet 0 (marker 0)", "hole 0", "outside"});
}

TEST(PlcCheck, VolumePointsOutside) {
  Plc p = unit_cube();
  p.holes.push_back({0.5, 0.5, 1.5});
  expect_error([&] { check(p); }, ExitCode::kInvalidGeometry,
               {"volume hole point 0 (0.5, 0.5, 1.5) lies outside the domain"});
  p = unit_cube();
  p.regions.push_back({{-0.25, 0.5, 0.5}, 3, -1});
  expect_error([&] { check(p); }, ExitCode::kInvalidGeometry, {"region point 0", "outside the domain"});
  p = unit_cube();
  p.regions.push_back({{0.5, 0.5, 1}, 3, -1});
  expect_error([&] { check(p); }, ExitCode::kInvalidGeometry, {"region point 0", "lies on facet 1"});
}

TEST(PlcCheck, BoundaryNotClosed) {
  Plc p;
  p.source = "open.poly";
  add_box_faces(p, add_box_corners(p, {0, 0, 0}, {1, 1, 1}), 0, 1);  // no top
  expect_error([&] { check(p); }, ExitCode::kInvalidGeometry, {"open.poly: facet", "boundary is not closed", "edge"});
  EXPECT_NO_THROW(check(p, {.closed = false}));
  // A flap outside the cube, hanging from one of its edges.
  p = unit_cube();
  add_facet(p, {{0, 1, add_point(p, {1, -1, 0}), add_point(p, {0, -1, 0})}}, 9);
  expect_error([&] { check(p); }, ExitCode::kInvalidGeometry, {"facet 6 (marker 9)", "not closed"});
}

TEST(PlcCheck, IntersectingFacets) {
  // A square crossing the cube.
  Plc p = unit_cube();
  add_facet(p, {{add_point(p, {0.5, -1, -1}), add_point(p, {0.5, 2, -1}), add_point(p, {0.5, 2, 2}),
                 add_point(p, {0.5, -1, 2})}}, 4);
  expect_error([&] { check(p); }, ExitCode::kInvalidGeometry, {"intersect other than in shared vertices", "marker 4"});
  // A vertex of an internal facet touching the inside of the bottom facet.
  p = unit_cube();
  add_facet(p, {{add_point(p, {0.5, 0.5, 0}), add_point(p, {0.75, 0.5, 0.5}), add_point(p, {0.25, 0.5, 0.5})}}, 5);
  expect_error([&] { check(p); }, ExitCode::kInvalidGeometry, {"facet 0 (marker 0) and facet 6 (marker 5) intersect"});
  // The wall of box_with_internal_facets without its foot in the bottom facet.
  p = box_with_internal_facets();
  p.facets[0].polygons.pop_back();
  expect_error([&] { check(p); }, ExitCode::kInvalidGeometry, {"intersect", "polygon edge of both facets"});
  // The same facet twice.
  p = unit_cube();
  p.facets.push_back(p.facets[3]);
  expect_error([&] { check(p); }, ExitCode::kInvalidGeometry, {"facet 3 (marker 3) and facet 6"});
  // A free segment through a facet.
  p = unit_cube();
  p.segments.push_back({add_point(p, {0.5, 0.5, 0.5}), add_point(p, {0.5, 0.5, 1.5})});
  expect_error([&] { check(p); }, ExitCode::kInvalidGeometry, {"segment 0", "meets facet 1"});
  // Free segments crossing each other, or overlapping from a common end.
  p = unit_cube();
  const VertexId a = add_point(p, {0.25, 0.5, 0.5}), b = add_point(p, {0.75, 0.5, 0.5});
  const VertexId c = add_point(p, {0.5, 0.25, 0.5}), d = add_point(p, {0.5, 0.75, 0.5});
  const VertexId e = add_point(p, {0.5, 0.5, 0.5});
  p.segments = {{a, e}, {c, d}};  // ending inside another segment is bad input too
  expect_error([&] { check(p); }, ExitCode::kInvalidGeometry, {"segment 0", "meets segment 1"});
  p.segments = {{a, b}, {c, d}};
  expect_error([&] { check(p); }, ExitCode::kInvalidGeometry, {"segment 0", "meets segment 1", "shared end"});
  p.segments = {{a, b}, {a, e}};
  expect_error([&] { check(p); }, ExitCode::kInvalidGeometry, {"segment 0", "meets segment 1"});
  p.segments = {{a, e}, {e, b}, {c, e}};
  EXPECT_NO_THROW(check(p));
}

TEST(PlcCheck, PolygonsCrossingInsideAFacet) {
  Plc p = unit_cube();
  p.facets[0].polygons[0] = {0, 3, 2, 1};  // a bow tie: 0-3 crosses 2-1
  expect_error([&] { check(p); }, ExitCode::kInvalidGeometry, {"cube.poly: facet 0 (marker 0)", "crosses"});
}

TEST(PlcCheck, PairTests) {
  Plc p;
  for (Point3 q : {Point3{0, 0, 0}, Point3{1, 0, 0}, Point3{0, 1, 0}, Point3{0.5, 0.5, 0}, Point3{-1, 0, 0},
                   Point3{0, 0, 1}, Point3{0.25, 0.25, -1}, Point3{-1, -1, 0}, Point3{0.125, 0.25, 0}})
    add_point(p, q);
  // Shared edge 0-1: off the plane fine; coplanar on one side overlaps, on opposite sides fine.
  EXPECT_FALSE(improper_triangle_pair(p, {0, 1, 2}, {1, 0, 5}));
  EXPECT_TRUE(improper_triangle_pair(p, {0, 1, 2}, {0, 1, 3}));
  EXPECT_FALSE(improper_triangle_pair(p, {0, 1, 2}, {0, 2, 4}));
  // Shared vertex 0: a coplanar triangle beside it is fine, one inside it is not, one pierced by
  // the other's opposite edge is not.
  EXPECT_FALSE(improper_triangle_pair(p, {0, 1, 2}, {0, 4, 7}));
  EXPECT_TRUE(improper_triangle_pair(p, {0, 1, 2}, {0, 3, 8}));
  EXPECT_TRUE(improper_triangle_pair(p, {0, 1, 2}, {0, 5, 6}));
  EXPECT_FALSE(improper_triangle_pair(p, {0, 1, 2}, {0, 5, 4}));
  // No shared vertex.
  EXPECT_FALSE(improper_triangle_pair(p, {1, 2, 8}, {0, 4, 7}));
  EXPECT_TRUE(improper_triangle_pair(p, {1, 2, 4}, {3, 5, 6}));
  EXPECT_FALSE(improper_segment_triangle(p, {0, 5}, {0, 1, 2}));
  EXPECT_TRUE(improper_segment_triangle(p, {0, 3}, {0, 1, 2}));
  EXPECT_FALSE(improper_segment_triangle(p, {0, 4}, {0, 1, 2}));
  EXPECT_TRUE(improper_segment_triangle(p, {5, 6}, {0, 1, 2}));
  EXPECT_FALSE(improper_segment_triangle(p, {1, 2}, {0, 1, 2}));
}

// Many facet triangles: the box search keeps the check quick (all pairs would take long).
TEST(PlcCheck, ManyTrianglesQuickly) {
  Plc p = unit_cube();
  std::vector<std::vector<VertexId>> bottom = p.facets[0].polygons;
  for (int i = 1; i < 150; ++i)
    for (int j = 1; j < 150; j += 2) bottom.push_back({add_point(p, {i / 150.0, j / 150.0, 0})});
  p.facets[0].polygons = bottom;
  const FacetTriangulation ft = check_and_triangulate(p);
  EXPECT_GT(ft.triangles[0].size(), 20000u);
}

}  // namespace
}  // namespace fdr::plc
