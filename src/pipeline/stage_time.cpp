// StageClock: wall time and VmHWM per pipeline stage.
#include "pipeline/stage_time.hpp"

#include <cstdio>
#include <cstdlib>

#include "base/step_laps.hpp"
#include "pipeline/memory_policy.hpp"
#include "quality/rss.hpp"

namespace fdr::pipeline {

StageClock::StageClock(std::vector<StageTime>* out) : out_(out) { restart(); }

void StageClock::restart() {
  t_ = std::chrono::steady_clock::now();
  faults_ = minor_page_faults();
}

double StageClock::lap(const std::string& name) {
  const auto now = std::chrono::steady_clock::now();
  const double s = std::chrono::duration<double>(now - t_).count();
  const long faults = minor_page_faults() - faults_;
  if (out_) out_->push_back({name, s, quality::peak_rss_mb_value().value_or(0.0), faults});
  static const bool print = debug::on(debug::Aid::kStages);  // developer aid: every stage on stderr
  if (print)
    std::fprintf(stderr, "stage %-8s %.3f s faults %ld peak %.1f MB\n", name.c_str(), s, faults,
                 quality::peak_rss_mb_value().value_or(0.0));
  stage_ended();
  restart();
  return s;
}

}  // namespace fdr::pipeline
