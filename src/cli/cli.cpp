// fdrmesh command line: option table -> CLI11, GDAL-style progress and errors, exit codes.
#include "cli/cli.hpp"
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include "base/error.hpp"
#include "base/progress.hpp"
#include "base/redact.hpp"
#include "base/version.hpp"
#include "cli/option_table.hpp"
#include "pipeline/quality_run.hpp"
#include "pipeline/pipeline.hpp"
#include "pipeline/run3d.hpp"
#include "pipeline/summary.hpp"

namespace fdr::cli {
namespace {

using Values = std::map<std::string, std::vector<std::string>>;

// GDAL-style progress on stderr, shown only once the run has taken more than a second.
class DelayedProgress {
 public:
  explicit DelayedProgress(bool quiet) : quiet_(quiet), start_(std::chrono::steady_clock::now()), term_(stderr) {}
  bool operator()(double frac, std::string_view) {
    if (quiet_) return true;
    if (!shown_) {
      if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count() < 1.0) return true;
      shown_ = true;
    }
    return term_(frac);
  }
  void finish() {
    if (shown_) term_.finish();
  }

 private:
  bool quiet_, shown_ = false;
  std::chrono::steady_clock::time_point start_;
  TermProgress term_;
};

int fail(const Error& e) {
  std::fflush(stdout);
  std::fprintf(stderr, "ERROR %d: %s\n", e.exit_code(), redact_passwords(e.what()).c_str());
  return e.exit_code();
}

// The CLI11 application built from the option table (shared by run() and parse_mesh_args()).
struct Parser {
  CLI::App app;
  bool version = false, json = false;
  std::map<std::string, Values> values;
  std::map<std::string, CLI::App*> subs;
  std::map<std::string, bool> flags;
  Parser();
};

Parser::Parser()
    : app{"fdrmesh " + std::string(kVersion) +
          ": Functional Delaunay Refinement meshes of coastal and terrain domains\n"
          "Guaranteed R/f(c) <= B for every triangle; exact predicates; GIS in, model meshes out."} {
  app.set_help_all_flag("--help-all", "Help for every command");
  app.add_flag("--version", version, "Print the version and exit");
  app.add_flag("--json-usage", json, "Print the option table as JSON (used by the QGIS plugin) and exit");
  app.require_subcommand(0, 1);
  app.footer(
      "Exit codes: 0 ok, 1 internal, 2 usage, 3 input unreadable, 4 input malformed, 5 invalid geometry,\n"
      "  6 invalid spacing, 7 work limit, 8 output error, 9 CRS error, 10 check failed, 11 cancelled.\n"
      "Examples:\n"
      "  fdrmesh mesh square.poly --spacing paper-f1 -o square.2dm --report square.json\n"
      "  fdrmesh mesh water.gpkg --open-boundary open.geojson --raster etopo.tif -o mesh.gpkg -o fort.14\n"
      "  fdrmesh quality mesh.2dm --spacing 500");
  subs["mesh"] = app.add_subcommand("mesh", "Mesh a domain by Functional Delaunay Refinement");
  subs["quality"] = app.add_subcommand("quality", "Report the quality of an existing mesh against a spacing f");
  for (const auto& o : option_table()) {
    CLI::App* sub = subs.at(o.command);
    auto& slot = values[o.command][o.key];  // strings; typed by OptSpec::bind
    std::string help = o.help;
    if (!o.def.empty()) help += " [default: " + o.def + "]";
    CLI::Option* opt;
    if (o.type == "flag") {
      opt = sub->add_flag(o.names, flags[o.command + ":" + o.key], help);
    } else {
      opt = sub->add_option(o.names, slot, help);
      opt->type_name(o.metavar);
      if (o.repeat) opt->expected(1)->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)->allow_extra_args(false);
      else opt->expected(1)->multi_option_policy(CLI::MultiOptionPolicy::TakeLast)->allow_extra_args(false);
      if (o.required) opt->required();
      if (!o.choices.empty()) opt->check(CLI::IsMember(o.choices, CLI::ignore_case));
    }
    opt->group(o.group);
  }
}

// The parsed values of `command` bound to the Request through the option table (flags given
// count as one value).
Request bind_parsed(Parser& p, const std::string& command, const std::string& cmdline) {
  Values v = p.values[command];
  for (const auto& o : option_table())
    if (o.command == command && o.type == "flag" && p.flags[command + ":" + o.key]) v[o.key] = {"true"};
  Request r;
  r.mesh.command_line = cmdline;
  bind_options(command, v, r);
  return r;
}

}  // namespace

pipeline::Options parse_mesh_args(const std::vector<std::string>& args) {
  Parser p;
  std::vector<std::string> argv{"fdrmesh", "mesh"};
  argv.insert(argv.end(), args.begin(), args.end());
  // CLI11 parses a reversed vector of arguments (without the program name).
  std::vector<std::string> rev(argv.rbegin(), argv.rend() - 1);
  try {
    p.app.parse(rev);
  } catch (const CLI::ParseError& e) {
    throw Error(ExitCode::kUsage, e.what());
  }
  std::string cmdline;
  for (std::size_t i = 0; i < argv.size(); ++i) cmdline += (i ? " " : "") + argv[i];
  return bind_parsed(p, "mesh", cmdline).mesh;
}

int run(int argc, char** argv) {
  Parser p;
  CLI::App& app = p.app;
  auto& subs = p.subs;
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "ERROR %d: %s (see fdrmesh --help)\n", static_cast<int>(ExitCode::kUsage), e.what());
    return static_cast<int>(ExitCode::kUsage);
  }
  if (p.version) {
    std::printf("fdrmesh %s\n", kVersion);
    return 0;
  }
  if (p.json) {
    std::printf("%s\n", json_usage().c_str());
    return 0;
  }
  std::string cmdline;
  for (int i = 0; i < argc; ++i) cmdline += (i ? " " : "") + std::string(argv[i]);
  try {
    if (subs["quality"]->parsed()) {  // read -> spacing -> measure (pipeline::run_quality)
      const pipeline::QualityOptions q = bind_parsed(p, "quality", cmdline).quality;
      pipeline::run_quality(q, q.quiet ? nullptr : &std::cout);
      return 0;
    }
    if (!subs["mesh"]->parsed()) {
      std::printf("%s", app.help().c_str());
      return static_cast<int>(ExitCode::kUsage);
    }
    pipeline::Options o = bind_parsed(p, "mesh", cmdline).mesh;  // usage errors before any I/O
    o.report_only_if_read = true;  // -q without --report: no quality report nobody reads

    DelayedProgress progress(o.quiet);
    auto log = [&](LogLevel lvl, std::string_view raw) {
      const std::string msg = redact_passwords(raw);  // a PostGIS source's password is never printed
      if (lvl == LogLevel::kWarning || lvl == LogLevel::kError) {
        std::fprintf(stderr, "Warning: %.*s\n", static_cast<int>(msg.size()), msg.data());
      } else if (lvl == LogLevel::kInfo && !o.quiet) {
        std::fprintf(stdout, "%.*s\n", static_cast<int>(msg.size()), msg.data());
        std::fflush(stdout);
      }
    };
    if (pipeline::is_3d_run(o)) {  // a 3D input: the tetrahedral mesher
      pipeline::Result3 r3 = pipeline::run3d(o, [&](double f, std::string_view s) { return progress(f, s); }, log);
      progress.finish();
      if (!o.quiet) pipeline::write_summary3(r3, std::cout);
      return 0;
    }
    pipeline::Result r = pipeline::run(o, [&](double f, std::string_view s) { return progress(f, s); }, log);
    progress.finish();
    if (!o.quiet) {
      std::ostringstream summary;
      pipeline::write_summary(r, summary);
      std::cout << redact_passwords(summary.str());
    }
    return 0;
  } catch (const Error& e) {
    return fail(e);
  } catch (const std::bad_alloc&) {
    return fail(Error(ExitCode::kWorkLimit, "out of memory; coarsen the spacing or lower --max-steiner"));
  } catch (const std::exception& e) {
    return fail(Error(ExitCode::kInternal, e.what()));
  }
}

}  // namespace fdr::cli
