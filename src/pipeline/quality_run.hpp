// `fdrmesh quality`: the report of an existing mesh against a spacing f (read -> spacing -> measure).
#pragma once
#include <iosfwd>
#include <string>
#include "quality/report.hpp"

namespace fdr::pipeline {

struct QualityOptions {
  std::string mesh;         // 2DM, fort.14, msh, node/ele or fdrmesh GPKG
  std::string spacing;      // spacing specification (as --spacing), or
  std::string raster;       // size raster (metres); neither: no f, geometric metrics only
  std::string report_json;  // JSON report path ("" none)
  double bound = 1.0;
  bool quiet = false;       // the CLI prints no text report
};

// Reads the mesh, evaluates f and measures; prints the text report on `text` (if not null), then
// writes the JSON report when asked. Throws fdr::Error.
quality::QualityReport run_quality(const QualityOptions& options, std::ostream* text = nullptr);

}  // namespace fdr::pipeline
