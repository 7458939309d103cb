// A number in messages: 6 significant digits, the way every error and log line prints them.
#pragma once
#include <sstream>
#include <string>

namespace fdr {

inline std::string num6(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

}  // namespace fdr
