// fdrmesh command line: parses arguments with the option table and runs the pipeline.
#pragma once

namespace fdr::cli {
// Returns the process exit code (see base/error.hpp and README "Exit codes").
int run(int argc, char** argv);
}  // namespace fdr::cli
