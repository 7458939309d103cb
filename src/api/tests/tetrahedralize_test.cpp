// fdr::tetrahedralize and the 3D input detection of the facade.
#include <gtest/gtest.h>
#include <string>
#include "api/tetrahedralize.hpp"
#include "base/error.hpp"

namespace fdr {
namespace {

const std::string kData = FDR_TESTDATA_DIR;

TEST(Tetrahedralize, DetectsThreeDimensionalInputs) {
  EXPECT_TRUE(is_3d_input(kData + "/3d/cube.poly"));
  EXPECT_TRUE(is_3d_input(kData + "/3d/cube.node"));
  EXPECT_TRUE(is_3d_input(kData + "/3d/cube.smesh"));
  EXPECT_TRUE(is_3d_input(kData + "/3d/octahedron.off"));
  EXPECT_TRUE(is_3d_input(kData + "/3d/octahedron.STL"));  // the extension without case
  EXPECT_TRUE(is_3d_input(kData + "/3d/octahedron.ply"));
  EXPECT_FALSE(is_3d_input(kData + "/3d/square2d.poly"));
  EXPECT_FALSE(is_3d_input(kData + "/3d/missing.poly"));  // the 2D reader names the problem
  EXPECT_FALSE(is_3d_input("water.gpkg"));
}

TEST(Tetrahedralize, CubeFromFileWithSpacingSpec) {
  const plc::Plc p = read_plc(kData + "/3d/cube.poly");
  const TetResult r = tetrahedralize(p, "0.5");
  ASSERT_FALSE(r.mesh.tets.empty());
  EXPECT_EQ(r.mesh.tet_material.size(), r.mesh.tets.size());
  EXPECT_EQ(r.mesh.face_marker.size(), r.mesh.faces.size());
  double volume = 0;
  for (const auto& t : r.mesh.tets) {
    const Point3 a = r.mesh.points[t[0]], b = r.mesh.points[t[1]], c = r.mesh.points[t[2]], d = r.mesh.points[t[3]];
    const double v = dot(b - a, cross(c - a, d - a)) / 6;
    EXPECT_GT(v, 0);
    volume += v;
  }
  EXPECT_NEAR(volume, 1.0, 1e-12);
  EXPECT_EQ(r.stats.input_vertices, 8u);
}

TEST(Tetrahedralize, BadSpacingAndBadInput) {
  const plc::Plc p = read_plc(kData + "/3d/cube.poly");
  try {
    (void)tetrahedralize(p, "-1");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.exit_code(), static_cast<int>(ExitCode::kInvalidSpacing));
  }
  try {
    (void)read_plc(kData + "/3d/bad_nan.poly");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.exit_code(), static_cast<int>(ExitCode::kInputMalformed));
  }
}

TEST(Tetrahedralize, DefaultSpacingIsATwentiethOfTheDiagonal) {
  plc::Plc p;
  p.points = {{0, 0, 0}, {2, 3, 6}};  // diagonal 7
  EXPECT_EQ(std::stod(default_spacing3(p)), 7.0 / 20.0);  // 17 digits: the same double back
  EXPECT_EQ(default_spacing3(plc::Plc{}), "1");
}

}  // namespace
}  // namespace fdr
