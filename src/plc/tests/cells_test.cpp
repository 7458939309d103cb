// Tests of the cells cut out by facets: inside and outside points of boxes, nested and separate
// boxes, layers, internal facets, and the sides of the facets.
#include <gtest/gtest.h>

#include "base/error.hpp"
#include "plc/cells.hpp"
#include "plc/tests/plc_samples.hpp"

namespace fdr::plc {
namespace {

using namespace samples;

TEST(SurfaceCells, CubeInsideOutside) {
  const Plc p = unit_cube();
  const FacetTriangulation ft = triangulate_facets(p);
  SurfaceCells cells(p, ft);
  EXPECT_FALSE(cells.outside({0.5, 0.5, 0.5}, "p"));
  EXPECT_FALSE(cells.outside({0.001, 0.999, 0.5}, "p"));
  EXPECT_TRUE(cells.outside({1.5, 0.5, 0.5}, "p"));
  EXPECT_TRUE(cells.outside({-100, 3, 7}, "p"));
  EXPECT_TRUE(cells.outside({0.5, 0.5, 1.0000000000000002}, "p"));
  EXPECT_THROW(cells.outside({0.5, 0.5, 0}, "p"), Error);
  EXPECT_THROW(cells.outside({1, 1, 0.25}, "p"), Error);  // on an edge
  // Each facet has its inside and its outside: two classes for the twelve triangles.
  const std::size_t unb = cells.unbounded_class();
  int outer = 0;
  for (std::size_t k = 0; k < 12; ++k) {
    EXPECT_NE(cells.side_class(k, true), cells.side_class(k, false));
    outer += (cells.side_class(k, true) == unb) + (cells.side_class(k, false) == unb);
  }
  EXPECT_EQ(outer, 12);
  EXPECT_NO_THROW(cells.check_closed());
}

TEST(SurfaceCells, NestedAndSeparateBoxes) {
  Plc p;
  add_box_faces(p, add_box_corners(p, {0, 0, 0}, {10, 10, 10}));
  add_box_faces(p, add_box_corners(p, {4, 4, 4}, {6, 6, 6}));     // a cavity or island inside
  add_box_faces(p, add_box_corners(p, {20, 0, 0}, {21, 1, 1}));  // a separate body
  const FacetTriangulation ft = triangulate_facets(p);
  SurfaceCells cells(p, ft);
  EXPECT_FALSE(cells.outside({1, 1, 1}, "p"));
  EXPECT_FALSE(cells.outside({5, 5, 5}, "p"));     // inside the inner box: a bounded cell
  EXPECT_FALSE(cells.outside({20.5, 0.5, 0.5}, "p"));
  EXPECT_TRUE(cells.outside({15, 0.5, 0.5}, "p"));
  EXPECT_TRUE(cells.outside({20.5, 0.5, 2}, "p"));
  // The shell between the boxes and the inner box are different cells.
  const std::size_t inner_out = cells.side_class(12, true), inner_in = cells.side_class(12, false);
  EXPECT_NE(inner_out, inner_in);
  EXPECT_NE(inner_out, cells.unbounded_class());
  EXPECT_NE(inner_in, cells.unbounded_class());
  EXPECT_NO_THROW(cells.check_closed());
}

TEST(SurfaceCells, LayersAreSeparateCells) {
  const Plc p = stacked_layers(3);
  const FacetTriangulation ft = triangulate_facets(p);
  SurfaceCells cells(p, ft);
  // The two sides of the internal facet 1 (z = 1) are the cells of layers 0 and 1.
  const std::size_t first_of_facet1 = ft.triangles[0].size();
  const std::size_t a = cells.side_class(first_of_facet1, true), b = cells.side_class(first_of_facet1, false);
  EXPECT_NE(a, b);
  EXPECT_NE(a, cells.unbounded_class());
  EXPECT_NE(b, cells.unbounded_class());
  for (double z : {0.5, 1.5, 2.5}) EXPECT_FALSE(cells.outside({1, 0.5, z}, "p"));
  EXPECT_TRUE(cells.outside({1, 0.5, 3.5}, "p"));
  EXPECT_NO_THROW(cells.check_closed());
  EXPECT_NO_THROW(cells.check_volume_points());
}

TEST(SurfaceCells, InternalFacetsInsideTheVolume) {
  const Plc p = box_with_internal_facets();
  const FacetTriangulation ft = triangulate_facets(p);
  SurfaceCells cells(p, ft);
  // Both sides of the floating square and of the wall face the box's inside.
  std::size_t k = 0;
  for (std::size_t f = 0; f < 6; ++f) k += ft.triangles[f].size();
  const std::size_t inside = cells.side_class(0, true) == cells.unbounded_class() ? cells.side_class(0, false)
                                                                                  : cells.side_class(0, true);
  for (std::size_t f = 6; f < 8; ++f)
    for (std::size_t i = 0; i < ft.triangles[f].size(); ++i, ++k) {
      EXPECT_EQ(cells.side_class(k, true), inside) << f;
      EXPECT_EQ(cells.side_class(k, false), inside) << f;
    }
  EXPECT_FALSE(cells.outside({2, 2, 3}, "p"));
  EXPECT_NO_THROW(cells.check_closed());
}

}  // namespace
}  // namespace fdr::plc
