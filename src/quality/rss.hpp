// Peak resident memory of this process (Linux /proc/self/status VmHWM), for reports.
#pragma once
#include <optional>
#include <string>

namespace fdr::quality {

// VmHWM in MiB parsed from `status_path` (default /proc/self/status); nullopt if unavailable.
std::optional<double> peak_rss_mb_value(const std::string& status_path = "/proc/self/status");

// The same, formatted with one decimal ("123.4"), or "n/a" when unavailable.
std::string peak_rss_mb();

}  // namespace fdr::quality
