// The 3D writers: TetGen files read back bit for bit, VTU and MSH structure, all-or-nothing output.
#include <gtest/gtest.h>
#include "tetio/read_tetgen.hpp"
#include "tetio/text_lines.hpp"
#include "tetio/write_tets.hpp"
#include "tetio/tests/cube_mesh.hpp"
#include "tetio/tests/test_util.hpp"

using namespace fdr;
using namespace fdr::tetio;
using namespace fdr::tetio::testing;

namespace {

std::size_t count_of(const std::string& text, const std::string& part) {
  std::size_t n = 0;
  for (std::size_t p = text.find(part); p != std::string::npos; p = text.find(part, p + 1)) ++n;
  return n;
}

}  // namespace

TEST(TetioCubeMesh, SixPositiveTetrahedraTwelveFaces) {
  const tet::TetMesh m = cube_mesh();
  ASSERT_EQ(m.tets.size(), 6u);
  double vol6 = 0;
  for (const auto& t : m.tets) {
    EXPECT_GT(volume6(m, t), 0);
    vol6 += volume6(m, t);
  }
  EXPECT_EQ(vol6, 6.0);
  EXPECT_EQ(m.faces.size(), 12u);
}

TEST(TetioWriteTetgen, ReadsBackBitForBit) {
  TempDir dir;
  tet::TetMesh m = cube_mesh();
  m.points[3] = {1, 1, -0.0};  // signed zero must survive the text
  m.points.push_back({0.1, 1.0 / 3, -1e-300});  // an unused point, still written
  write_tetgen(dir.file("cube"), m);
  EXPECT_EQ(dir.count(), 4u);  // .node .ele .face .edge
  const tet::TetMesh r = read_tetgen_mesh(dir.file("cube.ele"));
  ASSERT_EQ(r.points.size(), m.points.size());
  for (std::size_t i = 0; i < m.points.size(); ++i) EXPECT_EQ(r.points[i], m.points[i]);
  EXPECT_EQ(r.tets, m.tets);
  EXPECT_EQ(r.tet_material, m.tet_material);
  EXPECT_EQ(r.faces, m.faces);
  EXPECT_EQ(r.face_marker, m.face_marker);
  const std::string ele = read_file_bytes(dir.file("cube.ele"));
  EXPECT_EQ(ele.substr(0, ele.find('\n')), "6 4 1");
}

TEST(TetioReadTetgenMesh, ZeroVolumeAndMissingFiles) {
  TempDir dir;
  write_bytes(dir.file("flat.node"), "4 3 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 1 1 0\n");
  write_bytes(dir.file("flat.ele"), "1 4 0\n1 1 2 3 4\n");
  expect_error([&] { read_tetgen_mesh(dir.file("flat")); }, ExitCode::kInvalidGeometry, "flat.ele:2: tetrahedron 1 has zero volume");
  write_bytes(dir.file("flat.ele"), "1 4 0\n1 1 2 3 5\n");
  expect_error([&] { read_tetgen_mesh(dir.file("flat.node")); }, ExitCode::kInputMalformed, "vertex 5 out of range (points 1..4)");
  expect_error([&] { read_tetgen_mesh(dir.file("none")); }, ExitCode::kInputUnreadable, "none.node: cannot open");
}

TEST(TetioWriteTetgen, EleListsThePositiveVolumeOrderAsTetgenDoes) {
  TempDir dir;
  const tet::TetMesh m = cube_mesh();
  write_tetgen(dir.file("c.node"), m);
  TextLines ele(dir.file("c.ele"), read_file_bytes(dir.file("c.ele")));
  ele.next();
  for (const auto& t : m.tets) {
    ele.next();
    std::array<VertexId, 4> listed{};
    for (int k = 0; k < 4; ++k) listed[k] = static_cast<VertexId>(ele.integer(1 + k) - 1);
    EXPECT_EQ(listed, t);
  }
}

TEST(TetioWriteVtu, AppendedAndBase64Headers) {
  TempDir dir;
  const tet::TetMesh m = cube_mesh();
  write_vtu(dir.file("raw.vtu"), m);
  write_vtu(dir.file("b64.vtu"), m, VtuEncoding::kBase64);
  EXPECT_EQ(dir.count(), 2u);
  const std::string raw = read_file_bytes(dir.file("raw.vtu"));
  EXPECT_EQ(count_of(raw, "format=\"appended\""), 7u);  // points, 3 cell arrays, material, 2 fields
  EXPECT_EQ(count_of(raw, "NumberOfPoints=\"8\" NumberOfCells=\"6\""), 1u);
  EXPECT_EQ(count_of(raw, "Name=\"r_over_f\""), 1u);
  // The appended block: '_' then, per array, a UInt64 byte count and the data.
  const std::size_t start = raw.find('_', raw.find("<AppendedData")) + 1;
  const std::size_t expected = 7 * 8 + 8 * 3 * 8 + 6 * 4 * 8 + 6 * 8 + 6 + 6 * 4 + 2 * 6 * 8;
  EXPECT_EQ(raw.find("\n  </AppendedData>"), start + expected);
  const std::string b64 = read_file_bytes(dir.file("b64.vtu"));
  EXPECT_EQ(count_of(b64, "format=\"binary\""), 7u);
  EXPECT_EQ(b64.find("AppendedData"), std::string::npos);
}

TEST(TetioWriteMsh, SectionsAndPhysicalGroups) {
  TempDir dir;
  const tet::TetMesh m = cube_mesh();
  write_msh(dir.file("cube.msh"), m);
  const std::string s = read_file_bytes(dir.file("cube.msh"));
  EXPECT_EQ(s.substr(0, 34), std::string("$MeshFormat\n4.1 0 8\n$EndMeshFormat"));
  // 1 edge marker + 6 face markers + 2 materials; names from the mesh where given.
  EXPECT_NE(s.find("$PhysicalNames\n9\n1 9 \"marker_9\"\n2 1 \"west\"\n2 2 \"east\"\n2 3 \"marker_3\"\n"), std::string::npos);
  EXPECT_NE(s.find("3 1 \"upper\"\n3 2 \"lower\"\n$EndPhysicalNames"), std::string::npos);
  EXPECT_NE(s.find("$Entities\n0 1 6 2\n"), std::string::npos);
  EXPECT_NE(s.find("$Elements\n9 19 1 19\n"), std::string::npos);
  EXPECT_NE(s.find("$Nodes\n1 8 1 8\n3 1 0 8\n"), std::string::npos);
}

TEST(TetioWriteMsh, NonPositiveMarkersAreShifted) {
  TempDir dir;
  tet::TetMesh m = cube_mesh();
  m.tet_material.assign(6, 0);
  m.material_names.clear();
  write_msh(dir.file("m.msh"), m);
  const std::string s = read_file_bytes(dir.file("m.msh"));
  EXPECT_NE(s.find("3 1 \"material_0\"\n"), std::string::npos);
}

TEST(TetioWriteAll, NothingLeftOnFailure) {
  TempDir dir;
  tet::TetMesh m = cube_mesh();
  expect_error([&] { write_vtu(dir.file("no/such/folder/x.vtu"), m); }, ExitCode::kOutputError, "x.vtu");
  expect_error([&] { write_tetgen(dir.file("missing/x"), m); }, ExitCode::kOutputError, "x.node");
  m.cell_fields[0].second.pop_back();
  for (const char* name : {"bad.vtu", "bad.msh", "bad.node"}) {
    expect_error([&] { write_tets(dir.file(name), m); }, ExitCode::kInternal, "cell field 'r_over_f' has 5 values");
  }
  m = cube_mesh();
  m.tets[2][3] = 8;
  expect_error([&] { write_tets(dir.file("bad.msh"), m); }, ExitCode::kInternal, "tetrahedron 2 has vertex 8 of 8");
  expect_error([&] { write_tets(dir.file("bad.xyz"), m); }, ExitCode::kUsage, "unknown 3D output format '.xyz'");
  EXPECT_EQ(dir.count(), 0u);
}

TEST(TetioWriteAll, SeveralOutputsAsOne) {
  TempDir dir;
  const tet::TetMesh m = cube_mesh();
  expect_error([&] { write_tets_all({dir.file("a.vtu"), dir.file("a.msh"), dir.file("gone/a.node")}, m); },
               ExitCode::kOutputError, "gone/a.node");
  expect_error([&] { write_tets_all({dir.file("a.vtu"), dir.file("a.obj")}, m); }, ExitCode::kUsage, "a.obj");
  EXPECT_EQ(dir.count(), 0u);
  write_tets_all({dir.file("a.vtu"), dir.file("a.msh"), dir.file("a.ele")}, m, VtuEncoding::kBase64);
  EXPECT_EQ(dir.count(), 6u);  // vtu, msh, node, ele, face, edge
  EXPECT_NE(read_file_bytes(dir.file("a.vtu")).find("format=\"binary\""), std::string::npos);
}

TEST(TetioWriteAll, ReplacesAnExistingFileWhole) {
  TempDir dir;
  write_bytes(dir.file("m.msh"), "old content");
  write_tets(dir.file("m.msh"), cube_mesh());
  EXPECT_EQ(read_file_bytes(dir.file("m.msh")).substr(0, 11), "$MeshFormat");
  EXPECT_EQ(dir.count(), 1u);
}
