// Peak resident memory from /proc/self/status (VmHWM line, in kB).
#include "quality/rss.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>

namespace fdr::quality {

std::optional<double> peak_rss_mb_value(const std::string& status_path) {
  std::ifstream in(status_path);
  if (!in) return std::nullopt;
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("VmHWM:", 0) != 0) continue;
    std::istringstream ss(line.substr(6));
    double kb = 0;
    std::string unit;
    if (!(ss >> kb)) return std::nullopt;
    ss >> unit;
    if (!unit.empty() && unit != "kB") return std::nullopt;
    return kb / 1024.0;
  }
  return std::nullopt;
}

std::string peak_rss_mb() {
  const auto v = peak_rss_mb_value();
  if (!v) return "n/a";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.1f", *v);
  return buf;
}

}  // namespace fdr::quality
