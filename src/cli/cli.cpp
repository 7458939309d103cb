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
#include "base/version.hpp"
#include "cli/option_table.hpp"
#include "cli/quality_command.hpp"
#include "pipeline/pipeline.hpp"
#include "pipeline/summary.hpp"

namespace fdr::cli {
namespace {

using Values = std::map<std::string, std::vector<std::string>>;

double to_double(const Values& v, const std::string& key, double def) {
  auto it = v.find(key);
  if (it == v.end() || it->second.empty()) return def;
  const std::string& s = it->second.back();
  char* end = nullptr;
  const double x = std::strtod(s.c_str(), &end);
  if (end == s.c_str() || *end != '\0' || !std::isfinite(x))
    throw Error(ExitCode::kUsage, "--" + key + ": '" + s + "' is not a number");
  return x;
}
std::optional<double> opt_double(const Values& v, const std::string& key) {
  auto it = v.find(key);
  if (it == v.end() || it->second.empty()) return std::nullopt;
  return to_double(v, key, 0);
}
std::string str(const Values& v, const std::string& key) {
  auto it = v.find(key);
  return it == v.end() || it->second.empty() ? std::string() : it->second.back();
}

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
  std::fprintf(stderr, "ERROR %d: %s\n", e.exit_code(), e.what());
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
    auto& slot = values[o.command][o.key];
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

// Binds the parsed `mesh` values to pipeline::Options (phase 2 of issue 8 replaces these lines by
// a typed option table bound to the fields).
pipeline::Options bind_mesh(std::map<std::string, Values>& values, std::map<std::string, bool>& flags,
                            const std::string& cmdline) {
  {
    const Values& v = values["mesh"];
    pipeline::Options o;
    o.command_line = cmdline;
    o.input = str(v, "input");
    o.layer = str(v, "layer");
    o.where = str(v, "where");
    o.land = str(v, "land");
    if (const std::string e = str(v, "extent"); !e.empty()) {
      std::array<double, 4> box{};
      std::stringstream ss(e);
      std::string tok;
      int k = 0;
      while (std::getline(ss, tok, ',')) {
        char* end = nullptr;
        if (k >= 4) throw Error(ExitCode::kUsage, "--extent takes XMIN,YMIN,XMAX,YMAX");
        box[k] = std::strtod(tok.c_str(), &end);
        if (end == tok.c_str() || *end) throw Error(ExitCode::kUsage, "--extent: '" + tok + "' is not a number");
        ++k;
      }
      if (k != 4 || !(box[0] < box[2]) || !(box[1] < box[3]))
        throw Error(ExitCode::kUsage, "--extent takes XMIN,YMIN,XMAX,YMAX with XMIN < XMAX and YMIN < YMAX");
      o.extent = box;
    }
    o.breaklines = str(v, "breaklines");
    o.points = str(v, "points");
    o.open_boundary = str(v, "open-boundary");
    o.breaklines_layer = str(v, "breaklines-layer");
    o.points_layer = str(v, "points-layer");
    o.open_boundary_layer = str(v, "open-boundary-layer");
    o.s_srs = str(v, "s_srs");
    o.t_srs = str(v, "t_srs");
    o.output_crs = str(v, "output-crs");
    o.spacing = str(v, "spacing");
    o.raster = str(v, "raster");
    o.size_raster = str(v, "size-raster");
    o.hmin = opt_double(v, "hmin");
    o.hmax = opt_double(v, "hmax");
    o.dist_grade = opt_double(v, "dist-grade");
    o.slope_rule = opt_double(v, "slope-rule");
    o.wavelength_rule = opt_double(v, "wavelength-rule");
    o.wave_period_s = to_double(v, "wave-period", o.wave_period_s);
    o.vertical_tol = opt_double(v, "vertical-tol");
    o.gradation = to_double(v, "gradation", o.gradation);
    o.cell_size = opt_double(v, "cell-size");
    o.write_spacing = str(v, "write-spacing");
    o.snap = opt_double(v, "snap");
    o.min_island_factor = opt_double(v, "min-island");
    o.keep_coast = flags["mesh:keep-coast"];
    o.coast_tol = to_double(v, "coast-tol", o.coast_tol);
    o.close_width = opt_double(v, "close-width");
    o.min_feature = opt_double(v, "min-feature");
    o.min_depth_m = to_double(v, "min-depth", o.min_depth_m);
    o.simplify = opt_double(v, "simplify");
    o.bound = to_double(v, "bound", 1.0);
    o.min_angle_deg = to_double(v, "min-angle", -1.0);
    if (opt_double(v, "min-angle") && o.min_angle_deg < 0) throw Error(ExitCode::kUsage, "--min-angle must be in [0, 60)");
    if (const auto sm_opt = opt_double(v, "smooth")) {
      const double sm = *sm_opt;
      if (!(sm >= 0 && sm <= 100) || sm != std::floor(sm)) throw Error(ExitCode::kUsage, "--smooth must be an integer in [0, 100]");
      o.smooth_passes = static_cast<int>(sm);
    }
    const double ms = to_double(v, "max-steiner", 20e6);
    if (!(ms >= 1) || ms != std::floor(ms)) throw Error(ExitCode::kUsage, "--max-steiner must be a positive integer");
    o.max_steiner = static_cast<std::uint64_t>(ms);
    o.check = flags["mesh:check"];
    o.quiet = flags["mesh:quiet"];
    if (auto it = v.find("output"); it != v.end()) o.outputs = it->second;
    o.of = str(v, "of");
    o.slf_double = flags["mesh:slf-double"];
    o.telemac_open = str(v, "telemac-open");
    o.report_json = str(v, "report");
    return o;
  }
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
  return bind_mesh(p.values, p.flags, cmdline);
}

int run(int argc, char** argv) {
  Parser p;
  CLI::App& app = p.app;
  auto& values = p.values;
  auto& subs = p.subs;
  auto& flags = p.flags;
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
    if (subs["quality"]->parsed()) {
      const Values& v = values["quality"];
      QualityArgs q;
      q.mesh = str(v, "mesh");
      q.spacing = str(v, "spacing");
      q.raster = str(v, "raster");
      q.bound = to_double(v, "bound", 1.0);
      q.report_json = str(v, "report");
      q.quiet = flags["quality:quiet"];
      return run_quality(q);
    }
    if (!subs["mesh"]->parsed()) {
      std::printf("%s", app.help().c_str());
      return static_cast<int>(ExitCode::kUsage);
    }
    pipeline::Options o = bind_mesh(values, flags, cmdline);

    DelayedProgress progress(o.quiet);
    auto log = [&](LogLevel lvl, std::string_view msg) {
      if (lvl == LogLevel::kWarning || lvl == LogLevel::kError) {
        std::fprintf(stderr, "Warning: %.*s\n", static_cast<int>(msg.size()), msg.data());
      } else if (lvl == LogLevel::kInfo && !o.quiet) {
        std::fprintf(stdout, "%.*s\n", static_cast<int>(msg.size()), msg.data());
        std::fflush(stdout);
      }
    };
    pipeline::Result r = pipeline::run(o, [&](double f, std::string_view s) { return progress(f, s); }, log);
    progress.finish();
    if (!o.quiet) {
      pipeline::write_summary(r, std::cout);
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
