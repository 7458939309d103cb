// What the coast generalisation's steps share for their reports: numbers in repair messages and
// step timings under the kFilter developer aid.
#pragma once
#include <cstdio>
#include <string>

#include "base/step_laps.hpp"

namespace fdr::coast {

// A figure in a repair's message ("%.6g").
inline std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// A step's timings (debug::Aid::kFilter; base/step_laps.hpp).
class FilterLaps : public StepLaps {
 public:
  explicit FilterLaps(const char* prefix) : StepLaps(debug::Aid::kFilter, prefix) {}
};

}  // namespace fdr::coast
