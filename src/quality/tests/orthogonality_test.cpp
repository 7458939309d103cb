// Orthogonality (D-Flow FM cell centres) and smoothness on hand-checked meshes.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "quality/orthogonality.hpp"
#include "quality/report.hpp"

using namespace fdr;

namespace {
mesh::MeshView two(Point2 a, Point2 b, Point2 c, Point2 d) {  // triangles abc and acd share a-c
  mesh::MeshView m;
  m.vertices = {a, b, c, d};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}
}  // namespace

TEST(Orthogonality, AcuteNeighboursAreOrthogonal) {
  // Equilateral triangles: circumcentres inside, link along the perpendicular bisector.
  const double h = std::sqrt(3.0) / 2;
  quality::OrthogonalityStats s = quality::compute_orthogonality(two({0, 0}, {0.5, -h}, {1, 0}, {0.5, h}));
  EXPECT_EQ(s.interior_edges, 1u);
  EXPECT_NEAR(*s.orthogonality_max, 0.0, 1e-12);
  EXPECT_NEAR(*s.smoothness_max, 1.0, 1e-12);
  EXPECT_EQ(*s.orthogonality_p99, *s.orthogonality_max);
}

TEST(Orthogonality, ObtuseTriangleMovesItsCentreInside) {
  // abc is obtuse at c: its circumcentre (0.5, -1.2) lies below the long edge a-b, so its cell
  // centre is moved to (0.5, 0). That point is off the perpendicular bisector of the shared short
  // edge b-c, so the link to the neighbour bdc leans against b-c.
  mesh::MeshView m;
  m.vertices = {{0, 0}, {1, 0}, {0.5, 0.1}, {1.2, 0.6}};
  m.triangles = {{0, 1, 2}, {1, 3, 2}};
  quality::OrthogonalityStats s = quality::compute_orthogonality(m);
  ASSERT_TRUE(s.orthogonality_max);
  EXPECT_GT(*s.orthogonality_max, 0.1);
  EXPECT_LT(*s.orthogonality_max, 1.0);
  // Areas 0.05 and 0.16: larger over smaller.
  EXPECT_NEAR(*s.smoothness_max, 0.16 / 0.05, 1e-9);
}

TEST(Orthogonality, RightTrianglesShareTheirCentre) {
  // A unit square split on its diagonal: both circumcentres are the diagonal's midpoint, a
  // zero-length link, counted as orthogonal.
  quality::OrthogonalityStats s = quality::compute_orthogonality(two({0, 0}, {1, 0}, {1, 1}, {0, 1}));
  EXPECT_EQ(*s.orthogonality_max, 0.0);
  EXPECT_EQ(*s.smoothness_max, 1.0);
}

TEST(Orthogonality, NoInteriorEdgeIsNull) {
  mesh::MeshView m;
  m.vertices = {{0, 0}, {1, 0}, {0, 1}};
  m.triangles = {{0, 1, 2}};
  quality::OrthogonalityStats s = quality::compute_orthogonality(m);
  EXPECT_EQ(s.interior_edges, 0u);
  EXPECT_FALSE(s.orthogonality_max);
  EXPECT_FALSE(s.smoothness_p99);
}

TEST(Orthogonality, InTheReportTextAndJson) {
  mesh::MeshView m = two({0, 0}, {0.9, -0.05}, {1, 0}, {0.5, std::sqrt(3.0) / 2});
  quality::QualityReport r = quality::compute_quality(m, nullptr, 1.0, -1, {});
  std::ostringstream js, txt;
  quality::write_json(r, js);
  quality::write_text(r, txt);
  EXPECT_NE(js.str().find("\"orthogonality\": {"), std::string::npos) << js.str();
  EXPECT_NE(js.str().find("\"smoothness\": {"), std::string::npos);
  EXPECT_NE(txt.str().find("orthogonality max / p99"), std::string::npos) << txt.str();
  EXPECT_NE(txt.str().find("smoothness max / p99"), std::string::npos);
}
