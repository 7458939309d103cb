// What the command line prints after a run (quality report text, stage times, written files).
#pragma once
#include <iosfwd>
#include <string>
#include <vector>
#include "pipeline/pipeline.hpp"

namespace fdr::pipeline {

// `fdrmesh mesh`: the report, the per-stage times and memory, one "wrote PATH" line per output.
void write_summary(const Result& r, std::ostream& out);

// The lines after the report, for 2D and 3D runs alike: stage times and memory, written files.
void write_stages_and_outputs(const std::vector<StageTime>& stages, const std::vector<std::string>& written,
                              std::ostream& out);

}  // namespace fdr::pipeline
