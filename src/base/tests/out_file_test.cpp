// Tests for the all-or-nothing file output: nothing at the target until commit, no temporary
// left behind on failure, sets of files committed as one, numbers that read back bit for bit.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include "base/error.hpp"
#include "base/out_file.hpp"

namespace fs = std::filesystem;
using namespace fdr;

namespace {

class OutFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string tmpl = (fs::temp_directory_path() / "fdr_out_file_XXXXXX").string();
    ASSERT_NE(::mkdtemp(tmpl.data()), nullptr);
    dir_ = tmpl;
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const char* name) const { return (dir_ / name).string(); }
  std::size_t entries() const { return std::distance(fs::directory_iterator(dir_), fs::directory_iterator{}); }
  static std::string read(const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  fs::path dir_;
};

TEST_F(OutFileTest, NothingAtTheTargetUntilCommit) {
  const std::string p = path("a.txt");
  OutFile out(p);
  out.str("x ").num(std::int64_t{42}).nl();
  EXPECT_FALSE(fs::exists(p));
  EXPECT_TRUE(fs::exists(out.temp_path()));
  out.commit();
  EXPECT_EQ(read(p), "x 42\n");
  EXPECT_EQ(entries(), 1u);
}

TEST_F(OutFileTest, UncommittedFileLeavesNothingAndKeepsTheOldTarget) {
  const std::string p = path("b.txt");
  { std::ofstream(p) << "old"; }
  {
    OutFile out(p);
    out.str("new");
  }
  EXPECT_EQ(read(p), "old");
  EXPECT_EQ(entries(), 1u);
}

TEST_F(OutFileTest, MissingFolderIsAnOutputErrorNamingTheTarget) {
  const std::string p = path("no/such/folder/c.txt");
  try {
    OutFile out(p);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kOutputError);
    EXPECT_NE(std::string(e.what()).find(p), std::string::npos);
  }
}

TEST_F(OutFileTest, NumbersReadBackBitForBit) {
  const std::string p = path("d.txt");
  const double values[] = {0.1, 1.0 / 3.0, -2.5e-300, std::numeric_limits<double>::max(), 6.02214076e23};
  OutFile out(p);
  for (double v : values) out.num(v).nl();
  out.commit();
  std::istringstream in(read(p));
  for (double v : values) {
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(std::strtod(line.c_str(), nullptr), v) << line;
  }
}

TEST_F(OutFileTest, LargeBlocksAndSmallTextKeepTheirOrder) {
  const std::string p = path("e.bin");
  const std::string big(3 << 20, 'z');
  OutFile out(p);
  out.str("head");
  out.write(big);
  out.str("tail");
  out.commit();
  EXPECT_EQ(read(p), "head" + big + "tail");
}

TEST_F(OutFileTest, AFailedRenameInASetRemovesTheFilesAlreadyCommitted) {
  OutFile a(path("f.node"));
  OutFile b(path("f.ele"));
  a.str("a");
  b.str("b");
  fs::create_directory(path("f.ele/"));  // a folder in the way: b's rename fails
  { std::ofstream(path("f.ele/keep")) << "x"; }
  EXPECT_THROW(commit_outputs({&a, &b}), Error);
  EXPECT_FALSE(fs::exists(path("f.node")));
}

TEST_F(OutFileTest, TempFileReleasedForALibraryIsNotLeftBehind) {
  const std::string p = path("g.gpkg");
  {
    TempFile t(p);
    t.release_for_library();
    { std::ofstream(t.path()) << "db"; }
    { std::ofstream(t.path() + "-journal") << "j"; }
  }
  EXPECT_EQ(entries(), 0u);
}

}  // namespace
