// Tests of the facet frame: projection, exact collinearity, the frame of axis-aligned and tilted
// facets, and the in-plane incircle against the 2D one.
#include <gtest/gtest.h>

#include "base/error.hpp"
#include "plc/facet_frame.hpp"
#include "plc/tests/plc_samples.hpp"
#include "predicates/predicates.hpp"
#include "predicates/predicates3d.hpp"

namespace fdr::plc {
namespace {

using namespace samples;

TEST(FacetFrame, ProjectAndCollinear) {
  EXPECT_EQ(project({1, 2, 3}, 2), (Point2{1, 2}));
  EXPECT_EQ(project({1, 2, 3}, 0), (Point2{2, 3}));
  EXPECT_EQ(project({1, 2, 3}, 1), (Point2{3, 1}));
  EXPECT_TRUE(collinear({0, 0, 0}, {1, 2, 3}, {2, 4, 6}));
  EXPECT_TRUE(collinear({0, 0, 0}, {0, 0, 0}, {2, 4, 7}));
  EXPECT_FALSE(collinear({0, 0, 0}, {1, 2, 3}, {2, 4, 6.000000000000001}));
  // 0.1 is not a double: 3 * 0.1 is off the line through 0 and (0.1, 0.1, 0.1) by rounding.
  EXPECT_TRUE(collinear({0, 0, 0}, {0.5, 0.25, 0.125}, {1, 0.5, 0.25}));
}

TEST(FacetFrame, SideInPlane) {
  // In the plane x + y + z = 3 (dyadic points): the line through u, v and points on both sides.
  const Point3 u{3, 0, 0}, v{0, 3, 0}, ref{0, 0, 3}, far{2, 2, -1}, on{1.5, 1.5, 0}, near{1, 1, 1};
  EXPECT_EQ(side_in_plane(u, v, ref, near), 1);
  EXPECT_EQ(side_in_plane(u, v, ref, far), -1);
  EXPECT_EQ(side_in_plane(u, v, ref, on), 0);
  EXPECT_EQ(side_in_plane(u, v, on, ref), 0);  // collinear u, v, on
}

TEST(FacetFrame, AxisAlignedAndTilted) {
  const Plc cube = unit_cube();
  for (std::size_t f = 0; f < cube.facets.size(); ++f) {
    const FacetFrame fr = facet_frame(cube, f);
    EXPECT_FALSE(collinear(cube.points[fr.p0], cube.points[fr.p1], cube.points[fr.p2]));
    EXPECT_NE(predicates::orient3d(cube.points[fr.p0], cube.points[fr.p1], cube.points[fr.p2], fr.off_plane), 0);
  }
  // Facet 0 (z = 0) is projected onto xy; facet 2 (y = 0) onto zx; facet 4 (x = 0) onto yz.
  EXPECT_EQ(facet_frame(cube, 0).drop_axis, 2);
  EXPECT_EQ(facet_frame(cube, 2).drop_axis, 1);
  EXPECT_EQ(facet_frame(cube, 4).drop_axis, 0);
  Plc t;
  // Repeated first vertex and a collinear third: the frame skips them.
  const VertexId a = add_point(t, {0, 0, 0}), b = add_point(t, {4, 0, 1}), c = add_point(t, {8, 0, 2}),
                 d = add_point(t, {0, 1, 8});
  add_facet(t, {{a, b}, {a, c, d}});
  const FacetFrame fr = facet_frame(t, 0);
  EXPECT_EQ(fr.p0, a);
  EXPECT_EQ(fr.p1, b);
  EXPECT_EQ(fr.p2, d);
  EXPECT_EQ(fr.drop_axis, 1);  // normal (-1, -32, 4): largest along y
}

TEST(FacetFrame, DegenerateFacet) {
  Plc t;
  t.source = "line.poly";
  add_facet(t, {{add_point(t, {0, 0, 0}), add_point(t, {1, 1, 1}), add_point(t, {2, 2, 2})}}, 9);
  try {
    (void)facet_frame(t, 0);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidGeometry);
    EXPECT_NE(std::string(e.what()).find("line.poly: facet 0 (marker 9) is degenerate"), std::string::npos)
        << e.what();
  }
}

TEST(FacetFrame, IncircleInPlaneMatches2d) {
  // In the plane z = 0.75 the in-plane incircle is the 2D one, for either orientation of abc.
  const Point2 a{0, 0}, b{4, 0}, c{0, 4};
  auto lift = [](Point2 p) { return Point3{p.x, p.y, 0.75}; };
  for (Point2 d : {Point2{1, 1}, Point2{4, 4}, Point2{5, 5}, Point2{-1, 0.5}, Point2{2, -0.0001}}) {
    const int want = predicates::incircle(a, b, c, d);
    for (Point3 q : {Point3{0, 0, 1}, Point3{3, -2, -5}}) {
      EXPECT_EQ(incircle_in_plane(lift(a), lift(b), lift(c), lift(d), q), want);
      EXPECT_EQ(incircle_in_plane(lift(a), lift(c), lift(b), lift(d), q), want);
    }
  }
}

}  // namespace
}  // namespace fdr::plc
