// Per-stage wall time and peak memory of one pipeline run (filled by pipeline::run and the GIS stage).
#pragma once
#include <chrono>
#include <string>
#include <vector>

namespace fdr::pipeline {

struct StageTime {
  std::string name;        // "read", "repair", "sizing", "limit", "cdt", "refine", "report", "write"
  double seconds = 0;      // wall-clock time of the stage
  double peak_rss_mb = 0;  // VmHWM of the process at the end of the stage (0 if unknown)
  long minor_faults = 0;   // the process's minor page faults during the stage (every thread)
};

// Appends one StageTime per call to `out`, timing from the previous call (or construction).
class StageClock {
 public:
  explicit StageClock(std::vector<StageTime>* out);
  // Closes the stage `name` and starts the next one; returns its duration in seconds.
  double lap(const std::string& name);
  // Restarts the clock without recording (time spent outside any stage).
  void restart();

 private:
  std::vector<StageTime>* out_;
  std::chrono::steady_clock::time_point t_;
  long faults_ = 0;  // the process's minor faults at t_
};

}  // namespace fdr::pipeline
