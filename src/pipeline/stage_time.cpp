// StageClock: wall time and VmHWM per pipeline stage.
#include "pipeline/stage_time.hpp"
#include "base/memory.hpp"
#include "quality/rss.hpp"

namespace fdr::pipeline {

double StageClock::lap(const std::string& name) {
  const auto now = std::chrono::steady_clock::now();
  const double s = std::chrono::duration<double>(now - t_).count();
  if (out_) out_->push_back({name, s, quality::peak_rss_mb_value().value_or(0.0)});
  release_free_memory();  // the stage's garbage does not stay resident beside the next stage
  t_ = std::chrono::steady_clock::now();
  return s;
}

}  // namespace fdr::pipeline
