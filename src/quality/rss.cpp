// Peak resident memory from /proc/self/status (VmHWM line, in kB; base/memory.hpp reads it).
#include "quality/rss.hpp"

#include <cstdio>

#include "base/memory.hpp"

namespace fdr::quality {

std::optional<double> peak_rss_mb_value(const std::string& status_path) {
  const std::optional<ProcessMemory> m = process_memory(status_path);
  if (!m) return std::nullopt;
  return static_cast<double>(m->peak) / (1024.0 * 1024.0);
}

std::string peak_rss_mb() {
  const auto v = peak_rss_mb_value();
  if (!v) return "n/a";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.1f", *v);
  return buf;
}

}  // namespace fdr::quality
