// Failures leave nothing behind (no temporary file, the old target kept), and readers name the
// file and line of malformed content.
#include "io/tests/io_fixture.hpp"

using namespace fdr;
using namespace fdr::io_testing;

namespace {
void expect_output_error(const std::function<void()>& fn, const std::string& path_in_message) {
  try {
    fn();
    ADD_FAILURE() << "no error for " << path_in_message;
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kOutputError) << e.what();
    EXPECT_EQ(std::string(e.what()).rfind(path_in_message + ": ", 0), 0u) << e.what();
  }
}
}  // namespace

TEST_F(IoRoundTrip, MissingFolderIsOutputError) {
  for (Format f : kEvery) {
    std::string p = tmp / ("no_such_dir/mesh" + ext_of(f));
    expect_output_error([&] { io::write_mesh(m, p, f, opts); }, f == Format::kNode ? tmp / "no_such_dir/mesh.node" : p);
  }
  EXPECT_TRUE(tmp.entries().empty());
}

TEST_F(IoRoundTrip, ReadOnlyLocationIsOutputError) {
  std::string dir;
  if (::geteuid() == 0) {
    dir = "/proc";  // root ignores permission bits; /proc refuses new files for everyone
  } else {
    dir = tmp / "ro";
    fs::create_directory(dir);
    fs::permissions(dir, fs::perms::owner_read | fs::perms::owner_exec);
  }
  for (Format f : kEvery) {
    std::string p = dir + "/fdr_io_test_mesh" + ext_of(f);
    expect_output_error([&] { io::write_mesh(m, p, f, opts); }, p);
    EXPECT_FALSE(fs::exists(p));
  }
  for (auto& e : fs::directory_iterator(dir)) EXPECT_EQ(e.path().filename().string().find("fdr_io_test"), std::string::npos);
}

TEST_F(IoRoundTrip, FailureAfterWritingRemovesTempFile) {
  // The target is an existing folder: everything is written, then the final rename fails.
  for (Format f : kEvery) {
    std::string p = tmp / ("blocked" + ext_of(f));
    fs::create_directory(p);
    expect_output_error([&] { io::write_mesh(m, p, f, opts); }, p);
    EXPECT_TRUE(fs::is_directory(p));
    EXPECT_FALSE(has_temp_leftover(tmp)) << io::format_name(f);
    fs::remove(p);
  }
  // .node/.ele: the .node rename succeeds, the .ele one fails -> the new .node is removed again.
  fs::create_directory(tmp / "pair.ele");
  expect_output_error([&] { io::write_mesh(m, tmp / "pair.node", Format::kNode, opts); }, tmp / "pair.ele");
  EXPECT_FALSE(fs::exists(tmp / "pair.node"));
  EXPECT_FALSE(has_temp_leftover(tmp));
}

TEST_F(IoRoundTrip, FailureMidWriteRemovesTempFileAndKeepsOldTarget) {
  std::string p = tmp / "kept.2dm";
  { std::ofstream(p) << "previous mesh\n"; }
  // A sizing field that throws half-way through the triangles (e.g. a raster read error).
  struct Throwing : sizing::SizingField {
    mutable int calls = 0;
    double operator()(Point2) const override {
      if (++calls > 4) throw std::runtime_error("raster read failed");
      return 1.0;
    }
    std::string describe() const override { return "throwing"; }
  } bad;
  io::WriteOptions o = opts;
  o.f = &bad;
  for (Format f : {Format::kGpkg, Format::kVtu, Format::kUgrid}) {
    std::string q = tmp / ("mid" + ext_of(f));
    bad.calls = 0;
    expect_output_error([&] { io::write_mesh(m, q, f, o); }, q);
    EXPECT_FALSE(fs::exists(q)) << io::format_name(f);
  }
  // Directly through the temp-file helper: bytes written, then an exception.
  try {
    io::detail::TempFile tf(p);
    io::detail::TextOut out(tf.stream(), p);
    out.str("MESH2D\nND 1 0 0 0\n").flush();
    throw std::runtime_error("simulated failure");
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(slurp(p), "previous mesh\n");
  EXPECT_EQ(tmp.entries(), std::vector<std::string>{"kept.2dm"});
}

TEST_F(IoRoundTrip, InvalidMeshIsRejectedBeforeWriting) {
  m.triangles.push_back({0, 1, 99});
  std::string p = tmp / "bad.gpkg";
  expect_output_error([&] { io::write_mesh(m, p, Format::kGpkg, opts); }, p);
  EXPECT_TRUE(tmp.entries().empty());
  m = sample_mesh();
  m.z.pop_back();
  expect_output_error([&] { io::write_mesh(m, p, Format::k2dm, opts); }, p);
}

// ---------------------------------------------------------------- reader errors

namespace {
void expect_read_error(const std::string& path, ExitCode code, const std::string& fragment) {
  try {
    io::read_mesh(path);
    ADD_FAILURE() << "no error reading " << path;
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), code) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}
}  // namespace

TEST(IoReaders, MissingFileIsUnreadable) {
  expect_read_error("/nonexistent/mesh.2dm", ExitCode::kInputUnreadable, "/nonexistent/mesh.2dm");
  expect_read_error("/nonexistent/mesh.gpkg", ExitCode::kInputUnreadable, "/nonexistent/mesh.gpkg");
  expect_read_error("/nonexistent/mesh.ele", ExitCode::kInputUnreadable, "/nonexistent/mesh.node");
}

TEST(IoReaders, MalformedContentNamesFileAndLine) {
  TmpDir tmp;
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(tmp / name) << text;
    return tmp / name;
  };
  expect_read_error(write("a.2dm", "MESH2D\nND 1 0 0 0\nND 2 1 zero 0\n"), ExitCode::kInputMalformed, "a.2dm:3: 'zero' is not a number");
  expect_read_error(write("b.2dm", "MESH2D\nND 1 0 0 0\nE3T 1 1 2 3 1\n"), ExitCode::kInputMalformed, "b.2dm:3: node id 2 is not defined");
  expect_read_error(write("c.2dm", "hello\n"), ExitCode::kInputMalformed, "c.2dm:1: expected the MESH2D card");
  expect_read_error(write("d.2dm", "MESH2D\nE4Q 1 1 2 3 4 1\n"), ExitCode::kInputMalformed, "d.2dm:2: element card E4Q");
  expect_read_error(write("e.14", "t\n1 3\n1 0 0 1\n2 1 0 1\n3 0 1 1\n1 3 1 2 4\n"), ExitCode::kInputMalformed, "e.14:6: node id 4 is not defined");
  expect_read_error(write("f.14", "t\n1 3\n1 0 0 1\n"), ExitCode::kInputMalformed, "f.14:3: unexpected end of file");
  expect_read_error(write("g.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"), ExitCode::kInputMalformed, "g.msh:2: msh version 2.2");
  expect_read_error(write("h.node", "3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n"), ExitCode::kInputUnreadable, "h.ele");
  write("h.ele", "1 6 0\n1 1 2 3 4 5 6\n");
  expect_read_error(tmp / "h.node", ExitCode::kInputMalformed, "h.ele:1: 6 nodes per triangle");
  expect_read_error(write("i.gpkg", "not a database"), ExitCode::kInputUnreadable, "i.gpkg");
  expect_read_error(write("j.vtu", "<VTKFile/>"), ExitCode::kInputUnreadable, "j.vtu");
}

TEST(IoReaders, Fort14WithoutBoundariesAndFortranExponents) {
  TmpDir tmp;
  std::ofstream(tmp / "fort.14") << "grid\n 1 3\n 10 0.0 0.0 1.5D+00\n 20, 1.0, 0.0, 2.0\n 30 0.0 1.0 -1.0E+00\n 1 3 10 20 30\n";
  mesh::MeshView r = io::read_mesh(tmp / "fort.14");
  ASSERT_EQ(r.num_vertices(), 3u);
  EXPECT_EQ(r.z, (std::vector<double>{-1.5, -2.0, 1.0}));
  EXPECT_EQ(r.triangles[0], (std::array<Index, 3>{0, 1, 2}));
  EXPECT_TRUE(r.edges.empty());
}

TEST(IoReaders, ClockwiseFileIsReorientedAsAWhole) {
  TmpDir tmp;
  std::ofstream(tmp / "cw.2dm") << "MESH2D\nE3T 1 1 3 2 1\nND 1 0 0 0\nND 2 1 0 0\nND 3 0 1 0\n";
  mesh::MeshView r = io::read_mesh(tmp / "cw.2dm");
  ASSERT_EQ(r.num_triangles(), 1u);
  EXPECT_EQ(r.triangles[0], (std::array<Index, 3>{0, 1, 2}));
}
