// Runs every line of cli_specs.txt against the fdrmesh binary: exit code, message, and the exact
// set of files left in the output folder (nothing half-written on failure).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace {
struct Spec {
  int line = 0;
  int exit_code = 0;
  std::string expect;
  std::string args;
  std::set<std::string> files;
};

// Readable test names in ctest output instead of gtest's byte dump.
void PrintTo(const Spec& s, std::ostream* os) { *os << "spec line " << s.line << ": " << s.args; }

std::string trim(std::string s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
  std::size_t i = 0;
  while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
  return s.substr(i);
}

std::vector<Spec> load() {
  std::ifstream in(FDR_CLI_SPECS);
  std::vector<Spec> out;
  std::string l;
  int n = 0;
  while (std::getline(in, l)) {
    ++n;
    if (trim(l).empty() || trim(l)[0] == '#') continue;
    Spec s;
    s.line = n;
    const auto p1 = l.find(" | "), p2 = l.find(" | ", p1 + 3);
    s.exit_code = std::stoi(l.substr(0, p1));
    s.expect = trim(l.substr(p1 + 3, p2 - p1 - 3));
    std::string rest = l.substr(p2 + 3);
    const auto arrow = rest.find(" => ");
    if (arrow != std::string::npos) {
      std::istringstream fs_(rest.substr(arrow + 4));
      std::string f;
      while (fs_ >> f) s.files.insert(f);
      rest = rest.substr(0, arrow);
    }
    s.args = trim(rest);
    out.push_back(s);
  }
  return out;
}

std::string replace_all(std::string s, const std::string& a, const std::string& b) {
  for (std::size_t p = s.find(a); p != std::string::npos; p = s.find(a, p + b.size())) s.replace(p, a.size(), b);
  return s;
}
}  // namespace

class CliSpec : public ::testing::TestWithParam<Spec> {};

TEST_P(CliSpec, Runs) {
  const Spec& s = GetParam();
  const fs::path dir = fs::temp_directory_path() / ("fdrmesh_cli_" + std::to_string(s.line) + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::string args = replace_all(replace_all(s.args, "{T}", FDR_TESTDATA_DIR), "{O}", dir.string());
  const std::string cmd = std::string(FDR_BINARY) + " " + args + " > " + (dir / ".stdout").string() + " 2> " +
                          (dir / ".stderr").string();
  const int st = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(st)) << cmd;
  std::ifstream o(dir / ".stdout"), e(dir / ".stderr");
  std::stringstream out, err;
  out << o.rdbuf();
  err << e.rdbuf();
  EXPECT_EQ(WEXITSTATUS(st), s.exit_code) << "spec line " << s.line << ": " << args << "\nstderr: " << err.str();
  if (s.expect != "-") {
    EXPECT_TRUE(out.str().find(s.expect) != std::string::npos || err.str().find(s.expect) != std::string::npos)
        << "spec line " << s.line << ": expected '" << s.expect << "'\nstdout: " << out.str().substr(0, 2000)
        << "\nstderr: " << err.str();
  }
  std::set<std::string> left;
  for (const auto& de : fs::directory_iterator(dir)) {
    const std::string name = de.path().filename().string();
    if (name != ".stdout" && name != ".stderr") left.insert(name);
  }
  EXPECT_EQ(left, s.files) << "spec line " << s.line << ": files left in the output folder";
  fs::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(Specs, CliSpec, ::testing::ValuesIn(load()),
                         [](const ::testing::TestParamInfo<Spec>& i) { return "line" + std::to_string(i.param.line); });
