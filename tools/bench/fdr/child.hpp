// A measured child process for the benchmarks: whole wall clock, CPU time and peak RSS.
#pragma once
#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <string>
#include <vector>
#include "base/error.hpp"

struct ChildRun {
  double wall = 0;       // seconds from spawn to exit
  double cpu = 0;        // user + system seconds of the child
  double maxrss_mb = 0;  // its ru_maxrss
  int status = 0;        // as from wait4
};

// Spawns `args` with stdout+stderr to `log`, waits with wait4 for its own rusage. posix_spawn
// (vfork-like) keeps the bench process's pages out of the child's peak.
inline ChildRun spawn_and_wait(const std::vector<std::string>& args, const std::string& log) {
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
  pid_t pid;
  const auto t0 = std::chrono::steady_clock::now();
  const int rc = posix_spawnp(&pid, argv[0], &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0)
    throw fdr::Error(fdr::ExitCode::kInputUnreadable, "bench_fdr: cannot start " + args[0] + ": " + std::strerror(rc));
  int st = 0;
  rusage ru{};
  if (wait4(pid, &st, 0, &ru) < 0)
    throw fdr::Error(fdr::ExitCode::kInternal, std::string("bench_fdr: wait4 failed: ") + std::strerror(errno));
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const double cpu = static_cast<double>(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
                     1e-6 * static_cast<double>(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
  return {wall, cpu, ru.ru_maxrss / 1024.0, st};
}
