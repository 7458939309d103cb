// A temporary folder that removes itself, and a whole file read as text: shared by the io tests.
#pragma once

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

namespace fdr::io_testing {

struct TmpDir {
  std::filesystem::path dir;
  TmpDir() {
    std::string t = (std::filesystem::temp_directory_path() / "fdr_io_test_XXXXXX").string();
    dir = ::mkdtemp(t.data());
  }
  ~TmpDir() {
    std::error_code ec;
    // A test may have made the folder read-only to provoke a write error.
    std::filesystem::permissions(dir, std::filesystem::perms::owner_all, std::filesystem::perm_options::add, ec);
    std::filesystem::remove_all(dir, ec);
  }
  TmpDir(const TmpDir&) = delete;
  TmpDir& operator=(const TmpDir&) = delete;
  std::string operator/(const std::string& name) const { return (dir / name).string(); }
  std::vector<std::string> entries() const {
    std::vector<std::string> r;
    for (auto& e : std::filesystem::directory_iterator(dir)) r.push_back(e.path().filename().string());
    std::sort(r.begin(), r.end());
    return r;
  }
};

inline std::string slurp(const std::string& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace fdr::io_testing
