// Helpers of the tetio tests: test data paths, a private temporary folder, error expectations.
#pragma once
#include <gtest/gtest.h>
#include <filesystem>
#include <fstream>
#include <string>
#include "base/error.hpp"

namespace fdr::tetio::testing {

inline std::string data(const std::string& name) { return std::string(FDR_TESTDATA_DIR) + "/3d/" + name; }

// A fresh folder, removed with its content at the end: in /dev/shm when there is one (the
// robustness test writes thousands of small files), else in the system's temporary folder.
class TempDir {
 public:
  TempDir() {
    std::filesystem::path root = std::filesystem::is_directory("/dev/shm") ? std::filesystem::path("/dev/shm")
                                                                            : std::filesystem::temp_directory_path();
    std::string tmpl = (root / "tetio-test-XXXXXX").string();
    if (!::mkdtemp(tmpl.data())) throw std::runtime_error("mkdtemp failed");
    path_ = tmpl;
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  std::size_t count() const {
    return static_cast<std::size_t>(std::distance(std::filesystem::directory_iterator(path_), {}));
  }

 private:
  std::filesystem::path path_;
};

inline void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

// Runs f, expecting an fdr::Error with `code` whose message contains `part`.
template <class F>
void expect_error(F&& f, ExitCode code, const std::string& part) {
  try {
    f();
    ADD_FAILURE() << "no error; expected one containing '" << part << "'";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), code) << e.what();
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

}  // namespace fdr::tetio::testing
