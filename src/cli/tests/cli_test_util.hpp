// Helpers of the CLI tests that run the built fdrmesh binary: exit code of a command line, JSON of
// a written report, a file's bytes, a fresh output directory.
#pragma once
#include <sys/wait.h>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
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

// A file's bytes.
inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// An empty directory of this process under the system's temp directory.
inline std::filesystem::path fresh_dir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace fdr::cli_test
