// The option table of the fdrmesh command line: one source for parsing, --help and --json-usage.
#pragma once
#include <string>
#include <vector>

namespace fdr::cli {

// Value types, also read by the QGIS plugin to build its parameters:
//   flag, int, float, string, expr, crs, choice, vector_in, raster_in, mesh_in, file_out, bbox
struct OptSpec {
  std::string command;   // "mesh", "quality" or "" (global)
  std::string names;     // CLI11 names, e.g. "-o,--output"
  std::string key;       // stable key (the long name without dashes)
  std::string type;
  std::string metavar;
  std::string def;       // default shown in --help ("" none)
  std::string group;
  std::string help;
  bool repeat = false;
  bool required = false;
  std::vector<std::string> choices;
  bool positional = false;
};

const std::vector<OptSpec>& option_table();
// JSON usage document: program, version, commands (name, summary, options), exit codes.
std::string json_usage();

}  // namespace fdr::cli
