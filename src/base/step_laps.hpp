// Step timings on stderr for developers, switched on by an environment variable.
#pragma once
#include <chrono>
#include <cstdio>
#include <cstdlib>

namespace fdr {

// When the environment variable `env` is set, lap("x") prints "<prefix> x <seconds> s" on stderr:
// the time since the previous lap (or since construction). Otherwise it does nothing.
class StepLaps {
 public:
  StepLaps(const char* env, const char* prefix) : on_(std::getenv(env) != nullptr), prefix_(prefix) {}
  bool on() const { return on_; }
  void operator()(const char* what) {
    if (!on_) return;
    const auto now = std::chrono::steady_clock::now();
    std::fprintf(stderr, "%s %s %.3f s\n", prefix_, what, std::chrono::duration<double>(now - t_).count());
    t_ = now;
  }

 private:
  bool on_;
  const char* prefix_;
  std::chrono::steady_clock::time_point t_ = std::chrono::steady_clock::now();
};

}  // namespace fdr
