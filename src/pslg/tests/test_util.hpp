// Shared helpers for the pslg tests: temp files and expected-error assertions.
#pragma once
#include <gtest/gtest.h>
#include <filesystem>
#include <fstream>
#include <string>
#include "base/error.hpp"

namespace fdr::pslg::test {

inline std::string temp_path(const std::string& name) {
  const auto dir = std::filesystem::path(::testing::TempDir()) / "fdr_pslg_tests";
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

inline std::string write_temp(const std::string& name, const std::string& text) {
  const std::string p = temp_path(name);
  std::ofstream(p) << text;
  return p;
}

inline std::string testdata(const std::string& rel) { return std::string(FDR_TESTDATA_DIR) + "/" + rel; }

// Runs f, expects an fdr::Error with the given code whose message contains every needle.
template <class F>
void expect_error(F&& f, ExitCode code, std::initializer_list<std::string> needles) {
  try {
    f();
    ADD_FAILURE() << "no error thrown";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), code) << e.what();
    for (const auto& n : needles) EXPECT_NE(std::string(e.what()).find(n), std::string::npos) << "'" << n << "' not in: " << e.what();
  }
}

}  // namespace fdr::pslg::test
