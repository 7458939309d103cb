// The text report's formatting of a value and of a labelled line, shared by its sections.
#pragma once
#include <cmath>
#include <cstdio>
#include <optional>
#include <ostream>
#include <string>

namespace fdr::quality {

// v with a printf spec; "n/a" when unset, "inf", "-inf" or "nan" when not finite.
inline std::string fmt(std::optional<double> v, const char* spec = "%.6g") {
  if (!v) return "n/a";
  if (std::isinf(*v)) return *v > 0 ? "inf" : "-inf";
  if (std::isnan(*v)) return "nan";
  char buf[64];
  std::snprintf(buf, sizeof buf, spec, *v);
  return buf;
}

// "  label (padded to 30): value" and a newline.
inline void line(std::ostream& out, const char* label, const std::string& value) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "  %-30s: ", label);
  out << buf << value << '\n';
}

}  // namespace fdr::quality
