// Small path helpers shared by the readers and the pipeline.
#pragma once
#include <algorithm>
#include <cctype>
#include <string>

namespace fdr {

// The extension of `path` in lower case, without the dot ("" when there is none).
inline std::string lower_ext(const std::string& path) {
  const auto dot = path.find_last_of('.');
  const auto slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string e = path.substr(dot + 1);
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return e;
}

}  // namespace fdr
