// Helpers of the CLI tests that run the built fdrmesh binary: exit code of a command line, JSON of
// a written report.
#pragma once
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

namespace fdr::cli_test {

// Runs `fdrmesh ARGS` (FDR_BINARY) with its output discarded; returns its exit code (-1 if killed).
inline int run(const std::string& args) {
  const int st = std::system((std::string(FDR_BINARY) + " " + args + " > /dev/null 2>&1").c_str());
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

inline nlohmann::json load(const std::filesystem::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

}  // namespace fdr::cli_test
