// The readers' whole-mesh orientation on lon/lat meshes that cross the antimeridian (fort.14 and
// SCHISM hgrid.ll, as a --global run writes them): the majority of the triangles at most 180
// degrees wide decides, so the few across 180 do not flip the mesh; a mesh wholly across 180 is
// taken across it; a plane mesh in metres is not turned over by its wide triangles.
#include <gtest/gtest.h>

#include <unistd.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "io/reader.hpp"
#include "io/tests/tmp_dir.hpp"

namespace fs = std::filesystem;
using namespace fdr;
using fdr::io_testing::TmpDir;

namespace {


// A strip of the equator from 172 E to 172 W in lon/lat, two rows of nodes, two triangles per
// column, counter-clockwise on the sphere; the column between 179.5 E and 179.5 W crosses the
// antimeridian, so its two triangles span 359 degrees in the file. Their area (-897 square
// degrees each) outweighs the other eight (+8.75 each): the total area is negative.
const std::array<double, 6> kLon{172, 176, 179.5, -179.5, -176, -172};

std::vector<std::array<int, 3>> strip_triangles(bool clockwise) {
  std::vector<std::array<int, 3>> t;
  for (int i = 0; i + 1 < 6; ++i) {
    const int b0 = 1 + i, b1 = 2 + i, t0 = 7 + i, t1 = 8 + i;  // bottom row ids 1-6, top row 7-12
    t.push_back({b0, b1, t1});
    t.push_back({b0, t1, t0});
  }
  if (clockwise)
    for (auto& x : t) std::swap(x[1], x[2]);
  return t;
}

// The strip as fort.14 / hgrid.ll text, its outline one land boundary (fort.14 land ring closed;
// an hgrid.ll island not repeated would be, but a land boundary is written whole).
std::string strip_file(bool clockwise) {
  std::ostringstream s;
  s.precision(15);
  const auto tris = strip_triangles(clockwise);
  s << "lonlat strip\n" << tris.size() << " 12\n";
  for (int row = 0; row < 2; ++row)
    for (int i = 0; i < 6; ++i) s << 1 + row * 6 + i << ' ' << kLon[i] << ' ' << 5.0 * row << " 1000\n";
  for (std::size_t k = 0; k < tris.size(); ++k)
    s << k + 1 << " 3 " << tris[k][0] << ' ' << tris[k][1] << ' ' << tris[k][2] << '\n';
  const std::vector<int> ring{1, 2, 3, 4, 5, 6, 12, 11, 10, 9, 8, 7, 1};
  s << "0 = Number of open boundaries\n0 = Total number of open boundary nodes\n"
    << "1 = Number of land boundaries\n" << ring.size() << " = Total number of land boundary nodes\n"
    << ring.size() << " 0 = Number of nodes for land boundary 1\n";
  for (int v : ring) s << v << '\n';
  return s.str();
}

double twice_area_unwrapped(const mesh::MeshView& m, const std::array<Index, 3>& t) {
  Point2 p[3];
  for (int k = 0; k < 3; ++k) {
    p[k] = m.vertices[t[k]];
    if (p[k].x < 0) p[k].x += 360;
  }
  return (p[1].x - p[0].x) * (p[2].y - p[0].y) - (p[1].y - p[0].y) * (p[2].x - p[0].x);
}

void expect_strip(const mesh::MeshView& m, bool clockwise_file, const std::string& what) {
  ASSERT_EQ(m.vertices.size(), 12u) << what;
  const auto tris = strip_triangles(clockwise_file);
  ASSERT_EQ(m.triangles.size(), tris.size()) << what;
  for (std::size_t k = 0; k < tris.size(); ++k) {
    // Read ids are 0-based; a counter-clockwise file is kept as written, a clockwise one flipped.
    std::array<Index, 3> want{static_cast<Index>(tris[k][0] - 1), static_cast<Index>(tris[k][1] - 1),
                              static_cast<Index>(tris[k][2] - 1)};
    if (clockwise_file) std::swap(want[1], want[2]);
    EXPECT_EQ(m.triangles[k], want) << what << ", triangle " << k;
    EXPECT_GT(twice_area_unwrapped(m, m.triangles[k]), 0) << what << ", triangle " << k;
  }
}

TEST(LonLatRead, StripAcrossTheAntimeridianKeepsItsOrientation) {
  TmpDir tmp;
  for (const char* name : {"strip.14", "hgrid.ll"}) {
    std::ofstream(tmp / name) << strip_file(false);
    expect_strip(io::read_mesh(tmp / name), false, name);
  }
}

TEST(LonLatRead, ClockwiseStripAcrossTheAntimeridianIsFlipped) {
  TmpDir tmp;
  for (const char* name : {"cw.14", "cw.ll"}) {
    std::ofstream(tmp / name) << strip_file(true);
    expect_strip(io::read_mesh(tmp / name), true, name);
  }
}

// Every triangle across 180: the unwrapped longitudes still say counter-clockwise.
TEST(LonLatRead, MeshWhollyAcrossTheAntimeridian) {
  TmpDir tmp;
  std::ofstream(tmp / "q.14") << "quad\n2 4\n1 170 -10 1\n2 -170 -10 1\n3 -170 10 1\n4 170 10 1\n"
                                 "1 3 1 2 3\n2 3 1 3 4\n";
  const mesh::MeshView m = io::read_mesh(tmp / "q.14");
  ASSERT_EQ(m.triangles.size(), 2u);
  EXPECT_EQ(m.triangles[0], (std::array<Index, 3>{0, 1, 2}));
  EXPECT_EQ(m.triangles[1], (std::array<Index, 3>{0, 2, 3}));
}

// Coordinates beyond lon/lat (metres): no unwrapping; a wide triangle decides as written.
TEST(LonLatRead, PlaneMeshIsNotUnwrapped) {
  TmpDir tmp;
  std::ofstream(tmp / "p.14") << "plane\n1 3\n1 -100 0 1\n2 500 0 1\n3 -100 300 1\n1 3 1 3 2\n";
  const mesh::MeshView m = io::read_mesh(tmp / "p.14");
  EXPECT_EQ(m.triangles[0], (std::array<Index, 3>{0, 1, 2}));
}

// A mesh in metres within lon/lat bounds: its narrow triangles decide, the two 200 m wide ones
// (clockwise if unwrapped) do not turn it over.
TEST(LonLatRead, NarrowTrianglesOfAPlaneMeshDecide) {
  TmpDir tmp;
  std::ofstream(tmp / "n.14") << "plane\n3 5\n1 -100 -50 1\n2 100 -50 1\n3 100 50 1\n4 -100 50 1\n5 150 0 1\n"
                                 "1 3 1 2 3\n2 3 1 3 4\n3 3 2 5 3\n";
  const mesh::MeshView m = io::read_mesh(tmp / "n.14");
  EXPECT_EQ(m.triangles[0], (std::array<Index, 3>{0, 1, 2}));
  EXPECT_EQ(m.triangles[1], (std::array<Index, 3>{0, 2, 3}));
}

}  // namespace
