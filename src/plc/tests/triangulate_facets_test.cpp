// Tests of the facet triangulation: counts, areas, orientation, holes, non-convex facets, exact
// in-plane Delaunay on tilted facets, subsegments shared by several facets.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "base/error.hpp"
#include "plc/facet_frame.hpp"
#include "plc/tests/plc_samples.hpp"
#include "plc/triangulate_facets.hpp"
#include "predicates/predicates3d.hpp"

namespace fdr::plc {
namespace {

using namespace samples;

double area(const Plc& p, const Triangle& t) {
  return 0.5 * std::sqrt(norm2(cross(p.points[t[1]] - p.points[t[0]], p.points[t[2]] - p.points[t[0]])));
}

double facet_area(const Plc& p, const std::vector<Triangle>& tris) {
  double a = 0;
  for (const Triangle& t : tris) a += area(p, t);
  return a;
}

// Every triangle counter-clockwise seen from the side of the frame's normal.
void expect_oriented(const Plc& p, std::size_t f, const std::vector<Triangle>& tris) {
  const FacetFrame fr = facet_frame(p, f);
  const Point3 a = p.points[fr.p0], b = p.points[fr.p1], c = p.points[fr.p2];
  for (const Triangle& t : tris) {
    EXPECT_EQ(predicates::orient3d(p.points[t[0]], p.points[t[1]], p.points[t[2]], fr.off_plane),
              predicates::orient3d(a, b, c, fr.off_plane))
        << "facet " << f;
  }
}

const Subsegment* find_sub(const FacetTriangulation& ft, VertexId a, VertexId b) {
  if (a > b) std::swap(a, b);
  for (const auto& s : ft.subsegments)
    if (s.a == a && s.b == b) return &s;
  return nullptr;
}

TEST(TriangulateFacets, UnitCube) {
  const Plc p = unit_cube();
  const FacetTriangulation ft = triangulate_facets(p);
  ASSERT_EQ(ft.triangles.size(), 6u);
  ASSERT_EQ(ft.frames.size(), 6u);
  EXPECT_EQ(ft.frames[4].drop_axis, 0);
  std::size_t total = 0;
  for (std::size_t f = 0; f < 6; ++f) {
    EXPECT_EQ(ft.triangles[f].size(), 2u);
    EXPECT_DOUBLE_EQ(facet_area(p, ft.triangles[f]), 1.0);
    expect_oriented(p, f, ft.triangles[f]);
    total += ft.triangles[f].size();
  }
  EXPECT_EQ(total, 12u);
  ASSERT_EQ(ft.subsegments.size(), 12u);
  for (const auto& s : ft.subsegments) {
    EXPECT_LT(s.a, s.b);
    EXPECT_EQ(s.facets.size(), 2u);
  }
}

// A 3 x 3 square with a 1 x 1 hole, in the plane y = 1 and in a tilted plane.
Plc square_with_hole(bool tilted) {
  Plc p;
  // Plane through the origin spanned by e1, e2 (dyadic: the points are exactly coplanar).
  const Point3 e1 = tilted ? Point3{1, 0.5, 0.25} : Point3{1, 0, 0};
  const Point3 e2 = tilted ? Point3{-0.25, 0.75, 1} : Point3{0, 0, 1};
  const Point3 o = tilted ? Point3{0.5, -1, 2} : Point3{0, 1, 0};
  auto at = [&](double u, double v) { return o + u * e1 + v * e2; };
  std::vector<VertexId> outer, inner;
  for (auto [u, v] : {std::pair{0.0, 0.0}, {3.0, 0.0}, {3.0, 3.0}, {0.0, 3.0}}) outer.push_back(add_point(p, at(u, v)));
  for (auto [u, v] : {std::pair{1.0, 1.0}, {2.0, 1.0}, {2.0, 2.0}, {1.0, 2.0}}) inner.push_back(add_point(p, at(u, v)));
  add_facet(p, {outer, inner}, 5, {at(1.5, 1.5)});
  return p;
}

TEST(TriangulateFacets, FacetWithHole) {
  for (bool tilted : {false, true}) {
    const Plc p = square_with_hole(tilted);
    const FacetTriangulation ft = triangulate_facets(p);
    const double unit = tilted ? std::sqrt(norm2(cross(Point3{1, 0.5, 0.25}, Point3{-0.25, 0.75, 1}))) : 1.0;
    EXPECT_NEAR(facet_area(p, ft.triangles[0]), 8 * unit, 1e-12) << tilted;
    EXPECT_EQ(ft.triangles[0].size(), 8u);  // 8 vertices, 2 boundary loops: 8 triangles
    EXPECT_EQ(ft.subsegments.size(), 8u);
    for (const Triangle& t : ft.triangles[0]) {
      // No triangle has all three corners on the hole's boundary (ids 4..7).
      EXPECT_FALSE(t[0] >= 4 && t[1] >= 4 && t[2] >= 4);
    }
    expect_oriented(p, 0, ft.triangles[0]);
  }
}

TEST(TriangulateFacets, LShapedFacet) {
  Plc p;
  std::vector<VertexId> l;
  for (auto [x, y] : {std::pair{0.0, 0.0}, {2.0, 0.0}, {2.0, 1.0}, {1.0, 1.0}, {1.0, 2.0}, {0.0, 2.0}})
    l.push_back(add_point(p, {x, 7, y}));  // in the plane y = 7
  add_facet(p, {l});
  const FacetTriangulation ft = triangulate_facets(p);
  ASSERT_EQ(ft.triangles[0].size(), 4u);
  EXPECT_DOUBLE_EQ(facet_area(p, ft.triangles[0]), 3.0);
  for (const Triangle& t : ft.triangles[0]) {
    const Point3 c = (1.0 / 3) * (p.points[t[0]] + p.points[t[1]] + p.points[t[2]]);
    EXPECT_FALSE(c.x > 1 && c.z > 1) << "triangle in the notch";
  }
  EXPECT_EQ(ft.subsegments.size(), 6u);
}

// A tilted facet with many isolated vertices: the result is Delaunay in the facet's own plane,
// checked exactly against every vertex of the facet (no constraints inside a convex outline).
TEST(TriangulateFacets, TiltedFacetIsDelaunayInItsPlane) {
  Plc p;
  // A steep plane: the xy projection stretches one direction eightfold, so Delaunay in the
  // projection differs from Delaunay in the plane.
  const Point3 e1{1, 0, 0}, e2{0, 0.125, 1}, o{3, -2, 5};
  auto at = [&](double u, double v) { return o + u * e1 + v * e2; };
  std::vector<VertexId> outline;
  for (auto [u, v] : {std::pair{0.0, 0.0}, {8.0, 0.0}, {8.0, 8.0}, {0.0, 8.0}}) outline.push_back(add_point(p, at(u, v)));
  std::vector<std::vector<VertexId>> polys{outline};
  std::mt19937 rng(7);
  std::vector<std::pair<unsigned, unsigned>> used;
  while (used.size() < 60) {
    const unsigned i = rng() % 385, j = rng() % 385;
    if (std::find(used.begin(), used.end(), std::pair{i, j}) != used.end()) continue;
    used.emplace_back(i, j);
    polys.push_back({add_point(p, at(1 + i / 64.0, 1 + j / 64.0))});
  }
  add_facet(p, polys);
  const FacetFrame fr = facet_frame(p, 0);
  const FacetTriangulation ft = triangulate_facets(p);
  const auto& tris = ft.triangles[0];
  EXPECT_EQ(tris.size(), 2 * p.points.size() - 2 - 4);
  EXPECT_NEAR(facet_area(p, tris), 64 * std::sqrt(norm2(cross(e1, e2))), 1e-9);
  for (const Triangle& t : tris)
    for (VertexId v = 0; v < p.points.size(); ++v)
      ASSERT_LE(incircle_in_plane(p.points[t[0]], p.points[t[1]], p.points[t[2]], p.points[v], fr.off_plane), 0)
          << "vertex " << v << " inside the circle of " << t[0] << " " << t[1] << " " << t[2];
  expect_oriented(p, 0, tris);
}

TEST(TriangulateFacets, StackedLayersShareFacets) {
  const Plc p = stacked_layers(3);
  const FacetTriangulation ft = triangulate_facets(p);
  ASSERT_EQ(ft.triangles.size(), 4u + 12u);
  for (const auto& t : ft.triangles) EXPECT_EQ(t.size(), 2u);
  // A ring edge between two layers: the shared horizontal facet and the sides below and above.
  const Subsegment* s = find_sub(ft, 4, 5);
  ASSERT_NE(s, nullptr);
  EXPECT_EQ(s->facets, (std::vector<std::uint32_t>{1, 4, 8}));
  // A ring edge of the bottom: the bottom facet and one side.
  s = find_sub(ft, 0, 1);
  ASSERT_NE(s, nullptr);
  EXPECT_EQ(s->facets.size(), 2u);
}

TEST(TriangulateFacets, BoxWithInternalFacets) {
  const Plc p = box_with_internal_facets();
  const FacetTriangulation ft = triangulate_facets(p);
  // The bottom holds the wall's foot as an edge of its triangulation.
  const Subsegment* foot = find_sub(ft, 8, 9);
  ASSERT_NE(foot, nullptr);
  EXPECT_EQ(foot->facets, (std::vector<std::uint32_t>{0, 7}));
  EXPECT_DOUBLE_EQ(facet_area(p, ft.triangles[0]), 16.0);
  EXPECT_DOUBLE_EQ(facet_area(p, ft.triangles[6]), 4.0);
  EXPECT_DOUBLE_EQ(facet_area(p, ft.triangles[7]), 3.0);
  // The floating square's edges belong to it alone.
  const Subsegment* s = find_sub(ft, 12, 13);
  ASSERT_NE(s, nullptr);
  EXPECT_EQ(s->facets, (std::vector<std::uint32_t>{6}));
}

TEST(TriangulateFacets, PolygonEdgeSplitAtAVertexOnIt) {
  // A square whose edge 0-1 passes through isolated vertex 4: the subsegments are 0-4 and 4-1.
  Plc p;
  std::vector<VertexId> sq;
  for (auto [x, y] : {std::pair{0.0, 0.0}, {2.0, 0.0}, {2.0, 2.0}, {0.0, 2.0}}) sq.push_back(add_point(p, {x, y, 3}));
  const VertexId m = add_point(p, {1, 0, 3});
  add_facet(p, {sq, {m}});
  const FacetTriangulation ft = triangulate_facets(p);
  EXPECT_EQ(find_sub(ft, 0, 1), nullptr);
  EXPECT_NE(find_sub(ft, 0, m), nullptr);
  EXPECT_NE(find_sub(ft, m, 1), nullptr);
  EXPECT_EQ(ft.triangles[0].size(), 3u);
}

TEST(TriangulateFacets, FreeSegmentsListed) {
  Plc p = unit_cube();
  const VertexId a = add_point(p, {0.5, 0.5, 0.25}), b = add_point(p, {0.5, 0.5, 0.75});
  p.segments.push_back({b, a});
  const FacetTriangulation ft = triangulate_facets(p);
  const Subsegment* s = find_sub(ft, a, b);
  ASSERT_NE(s, nullptr);
  EXPECT_TRUE(s->facets.empty());
}

TEST(TriangulateFacets, HoleOutsideItsFacetNamesTheFacet) {
  Plc p = square_with_hole(false);
  p.facets[0].holes = {{5, 1, 5}};
  try {
    (void)triangulate_facets(p);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidGeometry);
    EXPECT_NE(std::string(e.what()).find("facet 0 (marker 5)"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("hole 0"), std::string::npos) << e.what();
  }
}

TEST(TriangulateFacets, FacetWithoutArea) {
  // Three segments in a plane that close no polygon, and a square whose hole point removes it all.
  Plc p;
  const VertexId a = add_point(p, {0, 0, 0}), b = add_point(p, {1, 0, 0}), c = add_point(p, {0, 1, 0}),
                 d = add_point(p, {1, 1, 0});
  add_facet(p, {{a, b}, {a, c}, {b, d}}, 3);
  try {
    (void)triangulate_facets(p);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidGeometry);
    EXPECT_NE(std::string(e.what()).find("facet 0 (marker 3) has no area"), std::string::npos) << e.what();
  }
  p.facets[0] = {{{a, b, d, c}}, {{0.5, 0.5, 0}}, 3};
  EXPECT_THROW((void)triangulate_facets(p), Error);
}

}  // namespace
}  // namespace fdr::plc
