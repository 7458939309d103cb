// fdrmesh command line: parses arguments with the option table and runs the pipeline.
#pragma once
#include <string>
#include <vector>
#include "pipeline/options.hpp"

namespace fdr::cli {
// Returns the process exit code (base/error.hpp).
int run(int argc, char** argv);

// Parses the arguments of `fdrmesh mesh` (without the program and subcommand names) with the
// option table exactly as the command line does and binds them to pipeline::Options; a bad
// option throws Error(kUsage) with the command line's message. Used by the Python module.
pipeline::Options parse_mesh_args(const std::vector<std::string>& args);
}  // namespace fdr::cli
