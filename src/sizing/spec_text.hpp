// The small text steps shared by the 2D and 3D spacing specifications (`--spacing` values).
#pragma once
#include <charconv>
#include <cmath>
#include <optional>
#include <string>
#include "base/error.hpp"
#include "sizing/fields.hpp"

namespace fdr::sizing::spec_text {

inline std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return {};
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

// The whole of s as a number, or nothing.
inline std::optional<double> parse_number(const std::string& s) {
  if (s.empty()) return std::nullopt;
  double v = 0;
  const char* first = s.data();
  if (*first == '+') ++first;  // from_chars rejects a leading '+'
  auto r = std::from_chars(first, s.data() + s.size(), v);
  if (r.ec != std::errc() || r.ptr != s.data() + s.size()) return std::nullopt;
  return v;
}

inline void require_positive(double v, const std::string& spec) {
  if (!(v > 0) || !std::isfinite(v))
    throw Error(ExitCode::kInvalidSpacing,
                "spacing '" + spec + "': " + format_number(v) + " is not a positive finite number");
}

}  // namespace fdr::sizing::spec_text
