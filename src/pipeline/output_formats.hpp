// The output formats the writers offer, for the option table (--help, --json-usage, QGIS plugin):
// cli sees pipeline only (src/modules.txt), so pipeline passes io's table on.
#pragma once
#include <string>
#include <vector>
#include "io/writer.hpp"

namespace fdr::pipeline {

struct OutputFormat {
  std::string name;        // --of value
  std::string extensions;  // blank-separated, e.g. ".14 .grd fort.14"
  std::string label;       // short description
  std::string carries;     // depth sign, boundaries, CRS
};

inline std::vector<OutputFormat> output_formats() {
  std::vector<OutputFormat> out;
  for (const auto& f : io::format_infos()) out.push_back({f.name, f.extensions, f.label, f.carries});
  return out;
}

}  // namespace fdr::pipeline
