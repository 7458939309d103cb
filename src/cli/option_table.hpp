// The option table of the fdrmesh command line: one source for parsing, --help and --json-usage.
#pragma once
#include <map>
#include <string>
#include <type_traits>
#include <vector>
#include "pipeline/quality_run.hpp"
#include "pipeline/options.hpp"

namespace fdr::cli {

// What a command line binds to: the options of `mesh` (pipeline::Options) and of `quality`.
struct Request {
  pipeline::Options mesh;
  pipeline::QualityOptions quality;
};

// Stores the values given for one option (none: the option was not given; a flag given: one
// value) into the Request. Raises Error(kUsage) naming the option on a bad value.
using Bind = void (*)(Request& request, const std::string& key, const std::vector<std::string>& values);

// Value types, also read by the QGIS plugin to build its parameters:
//   flag, int, float, string, expr, crs, choice, vector_in, raster_in, mesh_in, file_out, bbox
struct OptSpec {
  std::string command;   // "mesh", "quality" or "" (global)
  std::string names;     // CLI11 names, e.g. "-o,--output"
  std::string key;       // stable key (the long name without dashes)
  Bind bind;             // the field it sets: field<&pipeline::Options::x> or a checking setter
  std::string type;
  std::string metavar;
  std::string def;       // default shown in --help ("" none)
  std::string group;
  std::string help;
  bool repeat = false;
  bool required = false;
  std::vector<std::string> choices = {};
  bool positional = false;
};

const std::vector<OptSpec>& option_table();

// Binds every option of `command` ("mesh" or "quality") from the parsed values (key -> values).
void bind_options(const std::string& command, const std::map<std::string, std::vector<std::string>>& values,
                  Request& request);
// JSON usage document: program, version, commands (name, summary, options), exit codes.
std::string json_usage();

}  // namespace fdr::cli
