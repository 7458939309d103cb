// Closed surfaces: .off, ASCII and binary .stl, ASCII and binary .ply; exact merging; open surfaces.
#include <gtest/gtest.h>
#include <algorithm>
#include <set>
#include "tetio/read_plc.hpp"
#include "tetio/surface.hpp"
#include "tetio/tests/test_util.hpp"

using namespace fdr;
using namespace fdr::tetio;
using namespace fdr::tetio::testing;

namespace {

// A PLC's faces as sets of corner coordinates, independent of the vertex numbering.
std::set<std::vector<std::tuple<double, double, double>>> faces_by_coordinates(const plc::Plc& p) {
  std::set<std::vector<std::tuple<double, double, double>>> out;
  for (const auto& f : p.facets) {
    std::vector<std::tuple<double, double, double>> c;
    for (VertexId v : f.polygons.at(0)) c.emplace_back(p.points[v].x, p.points[v].y, p.points[v].z);
    std::sort(c.begin(), c.end());
    out.insert(c);
  }
  return out;
}

}  // namespace

TEST(TetioReadSurface, OctahedronSameInEveryFormat) {
  const plc::Plc off = read_plc(data("octahedron.off"));
  ASSERT_EQ(off.points.size(), 6u);
  ASSERT_EQ(off.facets.size(), 8u);
  EXPECT_EQ(off.facets[0].polygons[0], (std::vector<VertexId>{0, 2, 4}));
  for (const char* name : {"octahedron.stl", "octahedron_binary.stl", "octahedron.ply", "octahedron_le.ply",
                           "octahedron_be.ply"}) {
    SCOPED_TRACE(name);
    const plc::Plc p = read_plc(data(name));
    EXPECT_EQ(p.points.size(), 6u);  // STL's 24 corners merged to 6
    EXPECT_EQ(faces_by_coordinates(p), faces_by_coordinates(off));
    EXPECT_TRUE(p.holes.empty() && p.regions.empty() && p.segments.empty());
  }
}

TEST(TetioReadSurface, PlyFaceMarkers) {
  for (const char* name : {"octahedron.ply", "octahedron_le.ply", "octahedron_be.ply"}) {
    const plc::Plc p = read_plc(data(name));
    ASSERT_EQ(p.facets.size(), 8u);
    EXPECT_EQ(p.facets[0].marker, 5);
    EXPECT_EQ(p.facets[7].marker, 6);
  }
}

TEST(TetioReadSurface, PolygonFacesOfAnOffCube) {
  TempDir dir;
  const std::string f = dir.file("cube.off");
  write_bytes(f, "OFF 8 6 12\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
                 "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7 255 0 0\n");
  const plc::Plc p = read_plc(f);
  ASSERT_EQ(p.facets.size(), 6u);
  EXPECT_EQ(p.facets[5].polygons[0], (std::vector<VertexId>{3, 0, 4, 7}));
}

TEST(TetioReadSurface, PolygonFacesOfAPlyCube) {
  TempDir dir;
  const std::string f = dir.file("cube.ply");
  write_bytes(f, "ply\nformat ascii 1.0\nelement vertex 8\nproperty double x\nproperty double y\nproperty double z\n"
                 "element face 6\nproperty list uchar uint vertex_index\nend_header\n"
                 "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
                 "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n");
  const plc::Plc p = read_plc(f);
  ASSERT_EQ(p.facets.size(), 6u);
  EXPECT_EQ(p.facets[2].polygons[0], (std::vector<VertexId>{0, 1, 5, 4}));
}

TEST(TetioReadSurface, MergesExactlyEqualPointsOnly) {
  std::vector<Point3> distinct;
  const auto remap = merge_equal_points({{0, 0, 0}, {1, 0, 0}, {-0.0, 0, -0.0}, {1, 0, 1e-300}, {1, 0, 0}}, distinct);
  EXPECT_EQ(remap, (std::vector<VertexId>{0, 1, 0, 2, 1}));
  EXPECT_EQ(distinct.size(), 3u);
}

TEST(TetioReadSurfaceErrors, OpenAndDegenerateSurfaces) {
  expect_error([] { read_plc(data("bad_open.off")); }, ExitCode::kInvalidGeometry, "bad_open.off: the surface is not closed: the edge from");
  expect_error([] { read_plc(data("bad_open.stl")); }, ExitCode::kInvalidGeometry, "belongs to 1 face(s)");
  TempDir dir;
  const std::string f = dir.file("flat.off");
  write_bytes(f, "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 1\n");
  expect_error([&] { read_plc(f); }, ExitCode::kInvalidGeometry, "face 1 uses the point (1, 0, 0) twice");
  write_bytes(f, "OFF\n0 0 0\n");
  expect_error([&] { read_plc(f); }, ExitCode::kInvalidGeometry, "no face");
}

TEST(TetioReadSurfaceErrors, MalformedFiles) {
  expect_error([] { read_plc(data("bad_truncated.ply")); }, ExitCode::kInputMalformed, "binary data");
  expect_error([] { read_plc(data("bad_garbage.stl")); }, ExitCode::kInputMalformed, "not an STL file");
  TempDir dir;
  const std::string off = dir.file("x.off");
  write_bytes(off, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 nan 0\n3 0 1 2\n");
  expect_error([&] { read_plc(off); }, ExitCode::kInputMalformed, "x.off:5: field 2 'nan' is not a finite number");
  write_bytes(off, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n");
  expect_error([&] { read_plc(off); }, ExitCode::kInputMalformed, "x.off:6: vertex 3 out of range (0..2)");
  write_bytes(off, "PLY\n");
  expect_error([&] { read_plc(off); }, ExitCode::kInputMalformed, "not an OFF file");
  const std::string stl = dir.file("x.stl");
  write_bytes(stl, "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid\n");
  expect_error([&] { read_plc(stl); }, ExitCode::kInputMalformed, "x.stl:6: expected 'vertex'");
  const std::string ply = dir.file("x.ply");
  write_bytes(ply, "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n");
  expect_error([&] { read_plc(ply); }, ExitCode::kInputMalformed, "no 'vertex' element with x, y, z");
  write_bytes(ply, "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                   "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 inf\n3 0 1 2\n");
  expect_error([&] { read_plc(ply); }, ExitCode::kInputMalformed, "x.ply:12: 'inf' is not a finite number");
  write_bytes(ply, "ply\nformat binary_middle_endian 1.0\nend_header\n");
  expect_error([&] { read_plc(ply); }, ExitCode::kInputMalformed, "x.ply:2: unknown PLY format");
}

TEST(TetioReadSurfaceErrors, DamagedBytesAreEscapedInMessages) {
  TempDir dir;
  const std::string off = dir.file("x.off");
  write_bytes(off, "OFF\n3 1 0\n0 0 0\n1 \xce\xff 0\n0 1 0\n3 0 1 2\n");
  expect_error([&] { read_plc(off); }, ExitCode::kInputMalformed, "x.off:4: field 2 '\\xce\\xff' is not a finite number");
}
