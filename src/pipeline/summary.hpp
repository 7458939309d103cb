// What the command line prints after a run (quality report text, stage times, written files).
#pragma once
#include <iosfwd>
#include "pipeline/pipeline.hpp"

namespace fdr::pipeline {

// `fdrmesh mesh`: the report, the per-stage times and memory, one "wrote PATH" line per output.
void write_summary(const Result& r, std::ostream& out);

}  // namespace fdr::pipeline
