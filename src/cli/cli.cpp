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
#include "quality/report.hpp"

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

}  // namespace

int run(int argc, char** argv) {
  CLI::App app{"fdrmesh " + std::string(kVersion) +
               ": Functional Delaunay Refinement meshes of coastal and terrain domains\n"
               "Guaranteed R/f(c) <= B for every triangle; exact predicates; GIS in, model meshes out."};
  app.set_help_all_flag("--help-all", "Help for every command");
  bool version = false, json = false;
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
  std::map<std::string, Values> values;
  std::map<std::string, CLI::App*> subs;
  subs["mesh"] = app.add_subcommand("mesh", "Mesh a domain by Functional Delaunay Refinement");
  subs["quality"] = app.add_subcommand("quality", "Report the quality of an existing mesh against a spacing f");
  std::map<std::string, bool> flags;
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
  if (version) {
    std::printf("fdrmesh %s\n", kVersion);
    return 0;
  }
  if (json) {
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
    o.min_island_factor = to_double(v, "min-island", 0.0);
    o.simplify = opt_double(v, "simplify");
    o.bound = to_double(v, "bound", 1.0);
    o.min_angle_deg = to_double(v, "min-angle", 0.0);
    const double ms = to_double(v, "max-steiner", 20e6);
    if (!(ms >= 1) || ms != std::floor(ms)) throw Error(ExitCode::kUsage, "--max-steiner must be a positive integer");
    o.max_steiner = static_cast<std::uint64_t>(ms);
    o.check = flags["mesh:check"];
    o.strict = flags["mesh:strict"];
    o.convex_hull = flags["mesh:convex-hull"];
    o.quiet = flags["mesh:quiet"];
    if (auto it = v.find("output"); it != v.end()) o.outputs = it->second;
    o.of = str(v, "of");
    o.report_json = str(v, "report");

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
      quality::write_text(r.report, std::cout);
      std::cout << "stages (s, peak MiB):";
      for (const auto& st : r.stages) {
        char buf[96];
        std::snprintf(buf, sizeof buf, " %s %.2f (%.0f)", st.name.c_str(), st.seconds, st.peak_rss_mb);
        std::cout << buf;
      }
      std::cout << "\n";
      for (const auto& w : r.written) std::cout << "wrote " << w << "\n";
      std::cout.flush();
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
