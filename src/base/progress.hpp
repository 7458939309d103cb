// Progress and log callbacks passed through the pipeline (no global state).
#pragma once
#include <cstdio>
#include <functional>
#include <string_view>

namespace fdr {

// Called with a fraction in [0,1]; returns false to ask for cancellation.
using ProgressFn = std::function<bool(double fraction, std::string_view stage)>;

enum class LogLevel { kDebug, kInfo, kWarning, kError };
using LogFn = std::function<void(LogLevel, std::string_view message)>;

// GDAL-style terminal progress "0...10...20...30...40...50...60...70...80...90...100 - done."
// Thread-compatible, writes to the given FILE*.
class TermProgress {
 public:
  explicit TermProgress(std::FILE* out) : out_(out) {}
  bool operator()(double fraction);
  void finish();

 private:
  std::FILE* out_;
  int last_ = -1;  // last printed tick (0..40, each tick = 2.5 %)
};

}  // namespace fdr
