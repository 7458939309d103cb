// Running extremes of optional figures and the test for a usable spacing value, shared by the
// report's passes.
#pragma once
#include <cmath>
#include <limits>
#include <optional>

namespace fdr::quality {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

inline void update_min(std::optional<double>& m, double v) {
  if (!m || v < *m) m = v;
}
inline void update_max(std::optional<double>& m, double v) {
  if (!m || v > *m) m = v;
}

// f(p) that a ratio may divide by: finite and positive.
inline bool usable_spacing(double v) { return std::isfinite(v) && v > 0; }

}  // namespace fdr::quality
