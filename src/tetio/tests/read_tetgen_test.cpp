// TetGen input formats: .poly, .smesh, .node, the dimension probe, and bad or damaged files.
#include <gtest/gtest.h>
#include <random>
#include "tetio/read_plc.hpp"
#include "tetio/read_tetgen.hpp"
#include "tetio/write_poly.hpp"
#include "tetio/text_lines.hpp"
#include "tetio/tests/test_util.hpp"

using namespace fdr;
using namespace fdr::tetio;
using namespace fdr::tetio::testing;

TEST(TetioReadPoly, UnitCubeOneBased) {
  const plc::Plc p = read_plc(data("cube.poly"));
  ASSERT_EQ(p.points.size(), 8u);
  EXPECT_EQ(p.points[6], (Point3{1, 1, 1}));
  ASSERT_EQ(p.facets.size(), 6u);
  EXPECT_EQ(p.facets[0].polygons, (std::vector<std::vector<VertexId>>{{0, 1, 2, 3}}));
  for (int i = 0; i < 6; ++i) EXPECT_EQ(p.facets[i].marker, i + 1);
  EXPECT_TRUE(p.holes.empty());
  EXPECT_TRUE(p.regions.empty());
  EXPECT_TRUE(p.point_markers.empty());
  EXPECT_EQ(p.source, data("cube.poly"));
}

TEST(TetioReadPoly, CavityZeroBasedWithVolumeHoleAndPointMarkers) {
  const plc::Plc p = read_poly(data("box_cavity.poly"));
  ASSERT_EQ(p.points.size(), 16u);
  EXPECT_EQ(p.points[0], (Point3{0, 0, 0}));
  EXPECT_EQ(p.point_markers, (std::vector<std::int32_t>{1, 1, 1, 1, 1, 1, 1, 1, 2, 2, 2, 2, 2, 2, 2, 2}));
  ASSERT_EQ(p.facets.size(), 12u);
  EXPECT_EQ(p.facets[6].polygons[0], (std::vector<VertexId>{8, 9, 10, 11}));
  EXPECT_EQ(p.facets[6].marker, 2);
  ASSERT_EQ(p.holes.size(), 1u);
  EXPECT_EQ(p.holes[0], (Point3{1.5, 1.5, 1.5}));
}

TEST(TetioReadPoly, LayersRegionsWithAttributesAndVolumes) {
  const plc::Plc p = read_poly(data("layers.poly"));
  EXPECT_EQ(p.points.size(), 12u);
  EXPECT_EQ(p.facets.size(), 11u);
  EXPECT_EQ(p.facets[1].marker, 3);  // the internal facet
  ASSERT_EQ(p.regions.size(), 2u);
  EXPECT_EQ(p.regions[0].point, (Point3{0.5, 0.5, 0.5}));
  EXPECT_EQ(p.regions[0].attribute, 1);
  EXPECT_EQ(p.regions[0].max_volume, 0.01);
  EXPECT_EQ(p.regions[1].attribute, 2);
  EXPECT_EQ(p.regions[1].max_volume, 0.05);
}

TEST(TetioReadPoly, FacetWithHolePolygonAndHolePoint) {
  const plc::Plc p = read_poly(data("facet_hole.poly"));
  ASSERT_EQ(p.facets.size(), 7u);
  const plc::Facet& top = p.facets[1];
  ASSERT_EQ(top.polygons.size(), 2u);
  EXPECT_EQ(top.polygons[1], (std::vector<VertexId>{8, 9, 10, 11}));
  ASSERT_EQ(top.holes.size(), 1u);
  EXPECT_EQ(top.holes[0], (Point3{1, 1, 2}));
  EXPECT_EQ(p.facets[2].marker, 7);
}

TEST(TetioReadPoly, SmallDihedralWedgeAndTheExperimentCube) {
  const plc::Plc w = read_poly(data("dihedral10.poly"));
  EXPECT_EQ(w.points.size(), 6u);
  ASSERT_EQ(w.facets.size(), 5u);
  EXPECT_EQ(w.facets[3].polygons[0].size(), 3u);
  EXPECT_EQ(w.points[2].z, 0.17364817766693033);
  const plc::Plc c = read_poly(data("cube10.poly"));
  EXPECT_EQ(c.points[6], (Point3{10, 10, 10}));
}

TEST(TetioReadPoly, SegmentOnlyFacetsBecomeFreeSegments) {
  TempDir dir;
  const std::string f = dir.file("well.poly");
  write_bytes(f, "3 3 0 0\n1 0 0 0\n2 0 0 1\n3 0 0 2\n2 0\n1\n2 1 2\n1\n2 2 3\n0\n");
  const plc::Plc p = read_poly(f);
  EXPECT_TRUE(p.facets.empty());
  EXPECT_EQ(p.segments, (std::vector<std::array<VertexId, 2>>{{0, 1}, {1, 2}}));
}

TEST(TetioReadSmesh, PointsFromTheSiblingNodeFile) {
  const plc::Plc p = read_plc(data("cube.smesh"));
  ASSERT_EQ(p.points.size(), 8u);
  EXPECT_EQ(p.point_markers.size(), 8u);
  ASSERT_EQ(p.facets.size(), 6u);
  EXPECT_EQ(p.facets[5].polygons[0], (std::vector<VertexId>{3, 0, 4, 7}));
  EXPECT_EQ(p.facets[5].marker, 6);
}

TEST(TetioReadPoly, EndingAfterTheFacetsMeansNoHolesNoRegions) {
  TempDir dir;
  write_bytes(dir.file("short.poly"), "3 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n1 0\n1\n3 1 2 3\n");
  const plc::Plc p = read_poly(dir.file("short.poly"));
  EXPECT_EQ(p.facets.size(), 1u);
  EXPECT_TRUE(p.holes.empty() && p.regions.empty());
}

TEST(TetioReadSmesh, MissingSiblingNodeFile) {
  TempDir dir;
  write_bytes(dir.file("lone.smesh"), "0 3 0 0\n1 0\n3 1 2 3\n0\n");
  expect_error([&] { read_smesh(dir.file("lone.smesh")); }, ExitCode::kInputUnreadable, "lone.node: cannot open");
  write_bytes(dir.file("lone.node"), "3 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n");
  EXPECT_EQ(read_smesh(dir.file("lone.smesh")).facets.size(), 1u);
  // The same file read as a .poly: its facet line "3 1 2 3" is 3 polygons with 1 hole.
  expect_error([&] { read_poly(dir.file("lone.smesh")); }, ExitCode::kInputMalformed,
               "lone.smesh:4: a polygon needs at least one corner");
}

TEST(TetioReadNode, PointSetOnly) {
  const plc::Plc p = read_plc(data("cube.node"));
  EXPECT_EQ(p.points.size(), 8u);
  EXPECT_TRUE(p.facets.empty());
  EXPECT_EQ(p.point_markers[7], 2);
}

TEST(TetioPolyDimension, TellsTwoFromThree) {
  EXPECT_EQ(poly_dimension(data("cube.poly")), 3);
  EXPECT_EQ(poly_dimension(data("box_cavity.poly")), 3);
  EXPECT_EQ(poly_dimension(data("square2d.poly")), 2);
  expect_error([] { read_poly(data("square2d.poly")); }, ExitCode::kInputMalformed, "dimension 2");
  expect_error([] { poly_dimension(data("missing.poly")); }, ExitCode::kInputUnreadable, "missing.poly");
  TempDir dir;
  write_bytes(dir.file("empty.poly"), "# only a comment\n\n");
  expect_error([&] { poly_dimension(dir.file("empty.poly")); }, ExitCode::kInputMalformed, "empty file");
}

TEST(TetioReadPolyErrors, NameFileAndLine) {
  expect_error([] { read_plc(data("bad_nan.poly")); }, ExitCode::kInputMalformed, "bad_nan.poly:9: field 4 'nan' is not a finite number");
  expect_error([] { read_plc(data("bad_truncated.poly")); }, ExitCode::kInputMalformed, "unexpected end of file, expected facet 3");
  expect_error([] { read_plc(data("bad_index.poly")); }, ExitCode::kInputMalformed, "bad_index.poly:13: vertex 9 out of range (points 1..8)");
  expect_error([] { read_plc(data("bad_garbage.poly")); }, ExitCode::kInputMalformed, "bad_garbage.poly:4: field 3 'zero'");
  expect_error([] { read_plc(data("nothing_here.poly")); }, ExitCode::kInputUnreadable, "nothing_here.poly: cannot open");
  expect_error([] { read_plc(data("cube.obj")); }, ExitCode::kInputUnreadable, "unknown 3D input format '.obj'");
}

TEST(TetioReadPolyErrors, GeometricFaultsAreLeftToThePlcChecks) {
  // The reader parses these; plc::check rejects them (non-planar facet, hole outside, crossing facets).
  EXPECT_EQ(read_plc(data("bad_nonplanar.poly")).points[6].z, 1.25);
  EXPECT_EQ(read_plc(data("bad_hole_outside.poly")).holes.size(), 1u);
  EXPECT_EQ(read_plc(data("bad_intersecting.poly")).facets.size(), 7u);
}

TEST(TetioReadPolyErrors, OddHeadersAndOutOfSequencePoints) {
  TempDir dir;
  const std::string f = dir.file("x.poly");
  write_bytes(f, "2 3 0 0\n1 0 0 0\n3 1 0 0\n");
  expect_error([&] { read_poly(f); }, ExitCode::kInputMalformed, "x.poly:3: point number 3 out of sequence");
  write_bytes(f, "1 3 0 0\n5 0 0 0\n");
  expect_error([&] { read_poly(f); }, ExitCode::kInputMalformed, "first point's number must be 0 or 1");
  write_bytes(f, "-4 3 0 0\n");
  expect_error([&] { read_poly(f); }, ExitCode::kInputMalformed, "negative number of points");
  write_bytes(f, "1 3 0 0\n1 0 0\n");
  expect_error([&] { read_poly(f); }, ExitCode::kInputMalformed, "x.poly:2: expected point number, x, y, z (4 fields), found 3");
  write_bytes(f, "99999999999 3 0 0\n1 0 0 0\n");
  expect_error([&] { read_poly(f); }, ExitCode::kInputMalformed, "unexpected end of file, expected point 2");
  write_bytes(f, "1 3 0 0\n1 1e999 0 0\n");
  expect_error([&] { read_poly(f); }, ExitCode::kInputMalformed, "not a finite number");
}

// Every prefix and many byte-damaged copies of the valid inputs either read or fail with an
// fdr::Error: nothing crashes, nothing else is thrown.
TEST(TetioReadRobustness, TruncatedAndDamagedFilesFailCleanly) {
  TempDir dir;
  std::mt19937 rng(48);
  for (const char* name : {"cube.poly", "facet_hole.poly", "layers.poly", "octahedron.off", "octahedron.stl",
                           "octahedron_binary.stl", "octahedron.ply", "octahedron_le.ply", "octahedron_be.ply"}) {
    const std::string bytes = read_file_bytes(data(name));
    const std::string ext = std::string(name).substr(std::string(name).find('.'));
    const std::string f = dir.file("damaged" + ext);
    auto attempt = [&](const std::string& content) {
      write_bytes(f, content);
      try {
        read_plc(f);
      } catch (const Error&) {
      }
    };
    for (std::size_t n = 0; n < bytes.size(); n += 1 + bytes.size() / 97) attempt(bytes.substr(0, n));
    for (int k = 0; k < 200; ++k) {
      std::string b = bytes;
      for (int j = 0; j < 3; ++j) b[rng() % b.size()] = static_cast<char>(rng() % 256);
      attempt(b);
    }
  }
}

namespace {

void expect_same_plc(const plc::Plc& a, const plc::Plc& b) {
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.point_markers, b.point_markers);
  ASSERT_EQ(a.facets.size(), b.facets.size());
  for (std::size_t i = 0; i < a.facets.size(); ++i) {
    EXPECT_EQ(a.facets[i].polygons, b.facets[i].polygons);
    EXPECT_EQ(a.facets[i].holes, b.facets[i].holes);
    EXPECT_EQ(a.facets[i].marker, b.facets[i].marker);
  }
  EXPECT_EQ(a.segments, b.segments);
  EXPECT_EQ(a.holes, b.holes);
  ASSERT_EQ(a.regions.size(), b.regions.size());
  for (std::size_t i = 0; i < a.regions.size(); ++i) {
    EXPECT_EQ(a.regions[i].point, b.regions[i].point);
    EXPECT_EQ(a.regions[i].attribute, b.regions[i].attribute);
    EXPECT_EQ(a.regions[i].max_volume, b.regions[i].max_volume);
  }
}

}  // namespace

TEST(TetioWritePoly, EveryTestPlcReadsBackTheSame) {
  TempDir dir;
  for (const char* name : {"cube.poly", "cube10.poly", "box_cavity.poly", "layers.poly", "dihedral10.poly",
                           "facet_hole.poly", "cube.smesh", "octahedron_be.ply", "octahedron_binary.stl"}) {
    SCOPED_TRACE(name);
    const plc::Plc a = read_plc(data(name));
    write_poly(dir.file("copy.poly"), a);
    expect_same_plc(read_poly(dir.file("copy.poly")), a);
  }
  plc::Plc w;
  w.points = {{0, 0, 0}, {0, 0, 1}, {0.1, 1.0 / 3, -0.0}};
  w.segments = {{0, 1}, {1, 2}};
  w.regions = {{{0.5, 0.5, 0.5}, 3, -1}};
  write_poly(dir.file("w.poly"), w);
  expect_same_plc(read_poly(dir.file("w.poly")), w);
  w.segments.push_back({2, 3});
  expect_error([&] { write_poly(dir.file("bad.poly"), w); }, ExitCode::kInternal, "segment 2");
  EXPECT_EQ(dir.count(), 2u);
}
