// Step timings on stderr for developers, switched on by a developer aid (base/debug.hpp).
#pragma once
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include "base/debug.hpp"

namespace fdr {

// The process's minor page faults so far (every thread; getrusage).
inline long minor_page_faults() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_minflt;
}

// When the developer aid `aid` is on, lap("x") prints "<prefix> x <seconds> s faults <n>"
// on stderr: the time and the process's minor page faults since the previous lap (or since
// construction). Otherwise it does nothing. Why the faults: a 4 KiB page fault costs about as
// much as writing the page, so a step's time is often its fresh memory.
class StepLaps {
 public:
  StepLaps(debug::Aid aid, const char* prefix) : on_(debug::on(aid)), prefix_(prefix) {
    if (on_) faults_ = minor_page_faults();
  }
  bool on() const { return on_; }
  void operator()(const char* what) {
    if (!on_) return;
    const auto now = std::chrono::steady_clock::now();
    const long faults = minor_page_faults();
    std::fprintf(stderr, "%s %s %.3f s faults %ld\n", prefix_, what, std::chrono::duration<double>(now - t_).count(),
                 faults - faults_);
    faults_ = faults;
    t_ = now;
  }

 private:
  bool on_;
  const char* prefix_;
  long faults_ = 0;
  std::chrono::steady_clock::time_point t_ = std::chrono::steady_clock::now();
};

}  // namespace fdr
