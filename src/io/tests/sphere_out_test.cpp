// The VTU and msh writers on the sphere (WriteOptions::sphere_xyz): Earth-centred node coordinates
// written exactly, lon/lat and the radius beside them, the elevation as node data, the plane
// output unchanged without them, and a size mismatch refused without a file left.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "base/error.hpp"
#include "gis/global_sphere.hpp"
#include "io/reader.hpp"
#include "io/writer.hpp"
#include "io/tests/tmp_dir.hpp"

namespace fs = std::filesystem;
using namespace fdr;
using fdr::io_testing::TmpDir;
using fdr::io_testing::slurp;
using fdr::io::Format;

namespace {

std::int32_t mk(mesh::EdgeKind k) { return static_cast<std::int32_t>(k); }

// Two triangles of a lon/lat quad across the antimeridian (node coordinates in degrees, as a
// global mesh is written), its outline a land ring, with elevations.
struct SphereMesh {
  mesh::MeshView m;
  std::vector<Point3> xyz;
  SphereMesh() {
    m.vertices = {{170, -10}, {-170, -10}, {-170, 10}, {170, 10}};
    m.triangles = {{0, 1, 2}, {0, 2, 3}};
    m.edges = {{0, 1, mk(mesh::EdgeKind::kLand), 0}, {1, 2, mk(mesh::EdgeKind::kLand), 0},
               {2, 3, mk(mesh::EdgeKind::kLand), 0}, {3, 0, mk(mesh::EdgeKind::kLand), 0}};
    m.z = {-4000.5, -3000.25, -10, -1.0 / 3.0};
    for (const Point2& p : m.vertices) xyz.push_back(gis::sphere_xyz({p.x, p.y}));
  }
  io::WriteOptions options() const {
    io::WriteOptions o;
    o.title = "sphere test";
    o.sphere_xyz = &xyz;
    o.sphere_radius = gis::kEarthRadius;
    return o;
  }
};



// The numbers on the lines after the first line containing `key` in `text`, up to a line starting
// with '<' or '$'.
std::vector<double> numbers_after(const std::string& text, const std::string& key) {
  const auto at = text.find(key);
  EXPECT_NE(at, std::string::npos) << key;
  std::vector<double> out;
  if (at == std::string::npos) return out;
  std::istringstream in(text.substr(text.find('\n', at) + 1));
  std::string line;
  while (std::getline(in, line) && !line.empty() && line[0] != '<' && line[0] != '$') {
    std::istringstream ls(line);
    for (double v; ls >> v;) out.push_back(v);
  }
  return out;
}

TEST(SphereOut, VtuPointsAreEarthCentred) {
  SphereMesh s;
  TmpDir tmp;
  const std::string p = tmp / "m.vtu";
  io::write_mesh(s.m, p, Format::kVtu, s.options());
  const std::string text = slurp(p);
  const std::vector<double> pts = numbers_after(text, "NumberOfComponents=\"3\"");
  ASSERT_EQ(pts.size(), 12u);
  for (std::size_t v = 0; v < 4; ++v) {
    EXPECT_EQ(pts[3 * v], s.xyz[v].x);
    EXPECT_EQ(pts[3 * v + 1], s.xyz[v].y);
    EXPECT_EQ(pts[3 * v + 2], s.xyz[v].z);
  }
  const std::vector<double> lon = numbers_after(text, "Name=\"lon\""), lat = numbers_after(text, "Name=\"lat\"");
  const std::vector<double> z = numbers_after(text, "Name=\"z\"");
  ASSERT_EQ(lon.size(), 4u);
  ASSERT_EQ(lat.size(), 4u);
  ASSERT_EQ(z.size(), 4u);
  for (std::size_t v = 0; v < 4; ++v) {
    EXPECT_NEAR(lon[v], s.m.vertices[v].x, 1e-12);
    EXPECT_NEAR(lat[v], s.m.vertices[v].y, 1e-12);
    EXPECT_EQ(z[v], s.m.z[v]);
  }
  EXPECT_EQ(numbers_after(text, "Name=\"sphere_radius_m\""), std::vector<double>{gis::kEarthRadius});
}

TEST(SphereOut, MshNodesAreEarthCentredWithElevationAsNodeData) {
  SphereMesh s;
  TmpDir tmp;
  const std::string p = tmp / "m.msh";
  io::write_mesh(s.m, p, Format::kMsh, s.options());
  const std::string text = slurp(p);
  EXPECT_NE(text.find("1 1 \"land\""), std::string::npos);
  // $Nodes: the block header, four tags, then x y z per node.
  std::vector<double> nodes = numbers_after(text, "$Nodes");
  ASSERT_EQ(nodes.size(), 4u + 4u + 4u + 12u);
  for (std::size_t v = 0; v < 4; ++v) {
    EXPECT_EQ(nodes[12 + 3 * v], s.xyz[v].x);
    EXPECT_EQ(nodes[12 + 3 * v + 1], s.xyz[v].y);
    EXPECT_EQ(nodes[12 + 3 * v + 2], s.xyz[v].z);
  }
  // $NodeData "z": tag value per node after the three integer tags (step 0, 1 component, 4 nodes).
  ASSERT_NE(text.find("$NodeData\n1\n\"z\"\n1\n0\n3\n0\n1\n4\n"), std::string::npos);
  const std::vector<double> z = numbers_after(text, "$NodeData");  // the seven header numbers first
  ASSERT_EQ(z.size(), 7u + 8u);
  for (std::size_t v = 0; v < 4; ++v) {
    EXPECT_EQ(z[7 + 2 * v], static_cast<double>(v + 1));
    EXPECT_EQ(z[7 + 2 * v + 1], s.m.z[v]);
  }
  // The entities' boxes are boxes in x, y, z: the curve's (after the four counts and its tag)
  // spans the four nodes.
  const std::vector<double> ent = numbers_after(text, "$Entities");
  ASSERT_GE(ent.size(), 11u);
  EXPECT_EQ(ent[7], std::min({s.xyz[0].z, s.xyz[1].z, s.xyz[2].z, s.xyz[3].z}));
  EXPECT_EQ(ent[10], std::max({s.xyz[0].z, s.xyz[1].z, s.xyz[2].z, s.xyz[3].z}));
}

TEST(SphereOut, MshOnTheSphereReadsBackInLonLat) {
  SphereMesh s;
  TmpDir tmp;
  const std::string p = tmp / "m.msh";
  io::write_mesh(s.m, p, Format::kMsh, s.options());
  EXPECT_NE(slurp(p).find("$Comments\nsphere test\nfdrmesh sphere_radius_m 6371008.8\n$EndComments\n"),
            std::string::npos);
  const mesh::MeshView r = io::read_mesh(p);
  ASSERT_EQ(r.vertices.size(), 4u);
  for (std::size_t v = 0; v < 4; ++v) {
    EXPECT_NEAR(r.vertices[v].x, s.m.vertices[v].x, 1e-12);
    EXPECT_NEAR(r.vertices[v].y, s.m.vertices[v].y, 1e-12);
    EXPECT_EQ(r.z[v], s.m.z[v]);
  }
  EXPECT_EQ(r.triangles.size(), 2u);
  ASSERT_EQ(r.edges.size(), 4u);
  for (const auto& e : r.edges) EXPECT_EQ(e.marker, mk(mesh::EdgeKind::kLand));
  // Without elevations there is no node data: z reads back 0.
  s.m.z.clear();
  io::write_mesh(s.m, p, Format::kMsh, s.options());
  EXPECT_EQ(slurp(p).find("$NodeData"), std::string::npos);
  EXPECT_EQ(io::read_mesh(p).z, std::vector<double>(4, 0.0));
}

TEST(SphereOut, PlaneOutputIsUnchangedWithoutThePoints) {
  SphereMesh s;
  TmpDir tmp;
  io::WriteOptions o = s.options();
  o.sphere_xyz = nullptr;
  io::write_mesh(s.m, tmp / "m.vtu", Format::kVtu, o);
  io::write_mesh(s.m, tmp / "m.msh", Format::kMsh, o);
  const std::string vtu = slurp(tmp / "m.vtu"), msh = slurp(tmp / "m.msh");
  EXPECT_EQ(vtu.find("Name=\"lon\""), std::string::npos);
  EXPECT_EQ(vtu.find("FieldData"), std::string::npos);
  EXPECT_EQ(msh.find("$NodeData"), std::string::npos);
  const std::vector<double> pts = numbers_after(vtu, "NumberOfComponents=\"3\"");
  ASSERT_EQ(pts.size(), 12u);
  EXPECT_EQ(pts[3], -170.0);
  EXPECT_EQ(pts[5], 0.0);
  const std::vector<double> nodes = numbers_after(msh, "$Nodes");
  ASSERT_EQ(nodes.size(), 24u);
  EXPECT_EQ(nodes[12 + 3], -170.0);
  EXPECT_EQ(nodes[12 + 5], s.m.z[1]);
}

TEST(SphereOut, PointCountMismatchIsAnOutputErrorWithoutFile) {
  SphereMesh s;
  TmpDir tmp;
  s.xyz.pop_back();
  for (const char* name : {"m.vtu", "m.msh"}) {
    const std::string p = tmp / name;
    try {
      io::write_mesh(s.m, p, io::format_from_path(p), s.options());
      FAIL() << "no error for " << name;
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ExitCode::kOutputError);
      EXPECT_NE(std::string(e.what()).find("3 points on the sphere for 4 vertices"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(p));
  }
  EXPECT_TRUE(fs::is_empty(tmp.dir));
}

TEST(SphereOut, GmshLoadsTheMeshOnTheSphere) {
  if (::access("/usr/bin/gmsh", X_OK) != 0) GTEST_SKIP() << "gmsh binary not installed";
  SphereMesh s;
  TmpDir tmp;
  const std::string p = tmp / "m.msh", out = tmp / "out.msh", log = tmp / "gmsh.log";
  io::write_mesh(s.m, p, Format::kMsh, s.options());
  const std::string cmd = "/usr/bin/gmsh " + p + " -0 -format msh41 -o " + out + " > " + log + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << slurp(log);
  EXPECT_EQ(slurp(log).find("Error"), std::string::npos) << slurp(log);
  // Gmsh's re-export keeps the nodes where they are: every one at the sphere's radius.
  const std::vector<double> nodes = numbers_after(slurp(out), "$Nodes");
  ASSERT_GE(nodes.size(), 12u);
  std::size_t on_sphere = 0;
  for (std::size_t i = 0; i + 2 < nodes.size(); ++i) {
    const double r = std::sqrt(nodes[i] * nodes[i] + nodes[i + 1] * nodes[i + 1] + nodes[i + 2] * nodes[i + 2]);
    if (std::abs(r - gis::kEarthRadius) < 1e-6) ++on_sphere, i += 2;
  }
  EXPECT_EQ(on_sphere, 4u);
}

}  // namespace
