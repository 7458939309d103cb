// Error names and GDAL-style terminal progress.
#include <cstdio>
#include "base/error.hpp"
#include "base/progress.hpp"

namespace fdr {

const char* exit_code_name(ExitCode c) {
  switch (c) {
    case ExitCode::kOk: return "ok";
    case ExitCode::kInternal: return "internal error";
    case ExitCode::kUsage: return "usage error";
    case ExitCode::kInputUnreadable: return "input unreadable";
    case ExitCode::kInputMalformed: return "input malformed";
    case ExitCode::kInvalidGeometry: return "invalid geometry";
    case ExitCode::kInvalidSpacing: return "invalid spacing";
    case ExitCode::kWorkLimit: return "work limit exceeded";
    case ExitCode::kOutputError: return "output error";
    case ExitCode::kCrsError: return "CRS error";
    case ExitCode::kCheckFailed: return "check failed";
    case ExitCode::kCancelled: return "cancelled";
  }
  return "unknown";
}

// Prints the GDAL tick pattern: a number every 10 %, a dot every 2.5 %.
bool TermProgress::operator()(double fraction) {
  if (!(fraction >= 0)) fraction = 0;
  if (fraction > 1) fraction = 1;
  const int tick = static_cast<int>(fraction * 40.0 + 1e-9);
  while (last_ < tick) {
    ++last_;
    if (last_ % 4 == 0) std::fprintf(out_, "%d", last_ / 4 * 10);
    else std::fputc('.', out_);
  }
  std::fflush(out_);
  return true;
}

void TermProgress::finish() {
  (*this)(1.0);
  std::fputs(" - done.\n", out_);
  std::fflush(out_);
}

}  // namespace fdr
