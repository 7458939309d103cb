// The 3D run: read (tetio via api) -> spacing (sizing) -> tetrahedralize (api/tet) -> measure and
// check (quality) -> write (tetio, all or nothing).
#include "pipeline/run3d.hpp"
#include "pipeline/summary.hpp"
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>
#include "api/tetrahedralize.hpp"
#include "base/error.hpp"
#include "pipeline/gis_backend.hpp"
#include "quality/check3d.hpp"
#include "quality/rss.hpp"
#include "sizing/spacing3d_make.hpp"
#include "base/out_file.hpp"
#include "tetio/write_tets.hpp"

namespace fdr::pipeline {
namespace {

// The 2D-only options: (name on the command line, whether the run's options differ from the
// defaults there).
std::vector<std::pair<const char*, bool>> options_2d_only(const Options& o) {
  const Options d;
  return {{"--layer", o.layer != d.layer}, {"--where", o.where != d.where}, {"--land", o.land != d.land},
          {"--extent", o.extent.has_value()}, {"--breaklines", o.breaklines != d.breaklines},
          {"--points", o.points != d.points}, {"--open-boundary", o.open_boundary != d.open_boundary},
          {"--breaklines-layer", o.breaklines_layer != d.breaklines_layer},
          {"--points-layer", o.points_layer != d.points_layer},
          {"--open-boundary-layer", o.open_boundary_layer != d.open_boundary_layer},
          {"--s_srs", o.s_srs != d.s_srs}, {"--t_srs", o.t_srs != d.t_srs}, {"--output-crs", o.output_crs != d.output_crs},
          {"--densify", o.densify_deg != d.densify_deg}, {"--of", o.of != d.of},
          {"--write-spacing", o.write_spacing != d.write_spacing}, {"--slf-double", o.slf_double != d.slf_double},
          {"--telemac-open", o.telemac_open != d.telemac_open}, {"--pg-prefix", o.pg_prefix != d.pg_prefix},
          {"--pg-schema", o.pg_schema != d.pg_schema}, {"--overwrite", o.pg_overwrite != d.pg_overwrite},
          {"--raster", o.raster != d.raster}, {"--size-raster", o.size_raster != d.size_raster},
          {"--hmin", o.hmin.has_value()}, {"--hmax", o.hmax.has_value()}, {"--dist-grade", o.dist_grade.has_value()},
          {"--slope-rule", o.slope_rule.has_value()}, {"--wavelength-rule", o.wavelength_rule.has_value()},
          {"--wave-period", o.wave_period_s != d.wave_period_s}, {"--vertical-tol", o.vertical_tol.has_value()},
          {"--gradation", o.gradation != d.gradation}, {"--cell-size", o.cell_size.has_value()},
          {"--keep-coast", o.keep_coast != d.keep_coast}, {"--coast-tol", o.coast_tol != d.coast_tol},
          {"--close-width", o.close_width.has_value()}, {"--widen-width", o.widen_width.has_value()},
          {"--min-feature", o.min_feature.has_value()}, {"--min-island", o.min_island_factor.has_value()},
          {"--min-depth", o.min_depth_m != d.min_depth_m}, {"--channel-elements", o.channel_elements != d.channel_elements},
          {"--simplify", o.simplify.has_value()}, {"--snap", o.snap.has_value()}, {"--strict", o.strict != d.strict},
          {"--convex-hull", o.convex_hull != d.convex_hull}, {"--min-angle", o.min_angle_deg != d.min_angle_deg},
          {"--smooth", o.smooth_passes != d.smooth_passes}, {"--frontal", o.frontal_radius != d.frontal_radius}};
}

bool is_poly_path(const std::string& p) {
  return p.size() >= 5 && (p.compare(p.size() - 5, 5, ".poly") == 0 || p.compare(p.size() - 5, 5, ".POLY") == 0);
}

bool has_vtu(const std::vector<std::string>& outs) {
  return std::any_of(outs.begin(), outs.end(), [](const std::string& p) {
    return p.size() >= 4 && (p.compare(p.size() - 4, 4, ".vtu") == 0 || p.compare(p.size() - 4, 4, ".VTU") == 0);
  });
}

void add_cell_fields(tet::TetMesh& m, quality::TetValues&& v) {
  auto put = [&](const char* name, std::vector<double>&& vals) {
    for (const auto& [n, _] : m.cell_fields)
      if (n == name) return;  // the mesher's own values stay
    m.cell_fields.emplace_back(name, std::move(vals));
  };
  put("r_over_f", std::move(v.r_over_f));
  put("radius_edge", std::move(v.radius_edge));
  put("min_dihedral_deg", std::move(v.min_dihedral_deg));
}

}  // namespace

bool is_gpkg_path(const std::string& path) {
  if (path.size() < 5) return false;
  std::string ext = path.substr(path.size() - 5);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".gpkg";
}

bool is_3d_run(const Options& opt) { return !opt.dem.empty() || fdr::is_3d_input(opt.input); }

void check_no_terrain_options(const Options& opt) {
  const Options d;
  const std::pair<const char*, bool> given[] = {{"--base", opt.base != d.base}, {"--horizon", opt.horizons != d.horizons},
                                                {"--depth-grade", opt.depth_grade.has_value()},
                                                {"--min-thickness", opt.min_thickness.has_value()},
                                                {"--wells", !opt.wells.empty()},
                                                {"--wells-layer", !opt.wells_layer.empty()},
                                                {"--well-spacing", opt.well_spacing.has_value()}};
  for (const auto& [name, g] : given)
    if (g) throw Error(ExitCode::kUsage, std::string(name) + " needs --dem (a terrain volume)");
}

void check_tet_options(const Options& opt) {
  if (opt.bound_given && (!(opt.bound > 0) || !std::isfinite(opt.bound)))
    throw Error(ExitCode::kUsage, "--bound must be a positive number");
  // Above 30 degrees most of a good mesh would count as slivers.
  if (opt.sliver_angle_deg && !(*opt.sliver_angle_deg > 0 && *opt.sliver_angle_deg <= 30))
    throw Error(ExitCode::kUsage, "--sliver-angle must be in (0, 30] degrees");
  if (opt.sliver_angle_deg && opt.no_sliver_removal)
    throw Error(ExitCode::kUsage, "--sliver-angle and --no-sliver-removal contradict each other");
}

tet::TetOptions tet_options(const Options& opt, std::size_t plc_points) {
  tet::TetOptions to;
  to.bound = opt.bound_given ? opt.bound : 0.0;
  to.max_vertices = static_cast<std::size_t>(opt.max_steiner) + plc_points;
  to.remove_slivers = !opt.no_sliver_removal;
  if (opt.sliver_angle_deg) to.sliver_angle_deg = *opt.sliver_angle_deg;
  to.cell_fields = false;  // quality::measure_tets computes them for the report and the VTU
  return to;
}

void check_terrain_options(const Options& opt) {
  if (opt.dem.empty()) throw Error(ExitCode::kUsage, "a terrain volume needs --dem");
  if (!opt.raster.empty()) throw Error(ExitCode::kUsage, "--raster and --dem: the DEM is the terrain run's raster, give it once");
  if (opt.base.empty()) throw Error(ExitCode::kUsage, "--dem needs --base (an elevation in metres or a raster)");
  if (!opt.wells.empty() && !opt.points.empty())
    throw Error(ExitCode::kUsage, "--points and --wells: the wells are the terrain TIN's fixed points; give one of them");
  if (opt.wells.empty() && (!opt.wells_layer.empty() || opt.well_spacing))
    throw Error(ExitCode::kUsage, "--wells-layer and --well-spacing need --wells");
  if (opt.well_spacing && !(*opt.well_spacing > 0)) throw Error(ExitCode::kUsage, "--well-spacing must be > 0");
  if (opt.depth_grade && !(*opt.depth_grade >= 0)) throw Error(ExitCode::kUsage, "--depth-grade must be >= 0");
  if (opt.min_thickness && !(*opt.min_thickness >= 0)) throw Error(ExitCode::kUsage, "--min-thickness must be >= 0");
  if (opt.hmin && opt.hmax && *opt.hmin > *opt.hmax) throw Error(ExitCode::kUsage, "--hmin must not exceed --hmax");
  check_tet_options(opt);
  for (const auto& o : opt.outputs)
    if (!tetio::is_tets_output_path(o) && !is_poly_path(o) && !is_gpkg_path(o))
      throw Error(ExitCode::kUsage, "-o " + o + ": a terrain volume is written as .vtu, .msh, TetGen .node/.ele, its PLC as .poly "
                                                 "or its top surface as .gpkg");
}

void check_3d_options(const Options& opt) {
  check_no_terrain_options(opt);
  for (const auto& [name, given] : options_2d_only(opt))
    if (given) throw Error(ExitCode::kUsage, std::string(name) + " applies to 2D runs only; " + opt.input + " is a 3D input");
  check_tet_options(opt);
  for (const auto& o : opt.outputs)
    if (!tetio::is_tets_output_path(o))
      throw Error(ExitCode::kUsage, "-o " + o + ": a 3D mesh is written as .vtu, .msh or TetGen .node/.ele");
}

void time_report3(Result3& r, std::chrono::steady_clock::time_point t_start) {
  r.report.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
  r.report.peak_rss_mb = quality::peak_rss_mb_value().value_or(0);
  for (const auto& s : r.stages) {
    r.report.stage_seconds.emplace_back(s.name, s.seconds);
    r.report.stage_peak_mb.emplace_back(s.name, s.peak_rss_mb);
  }
}

Result3 run3d(const Options& opt, const ProgressFn& progress, const LogFn& log) {
  if (!opt.dem.empty()) {
    check_terrain_options(opt);  // usage errors before the GIS library is loaded
    return gis_backend().run_terrain(opt, progress, log);
  }
  const auto t_start = std::chrono::steady_clock::now();
  check_3d_options(opt);
  auto report_progress = [&](double frac, const char* stage) {
    if (progress && !progress(frac, stage)) throw Error(ExitCode::kCancelled, std::string("cancelled during ") + stage);
  };
  Result3 r;
  StageClock clock(&r.stages);
  report_progress(0.0, "read");
  const plc::Plc plc = fdr::read_plc(opt.input);
  const sizing::SizingPtr3 f = sizing::make_spacing3(opt.spacing.empty() ? fdr::default_spacing3(plc) : opt.spacing);
  clock.lap("read");
  if (log) log(LogLevel::kInfo, "3D input: " + std::to_string(plc.points.size()) + " vertices, " +
                                    std::to_string(plc.facets.size()) + " facets; spacing " + f->describe());

  tet::TetOptions to = tet_options(opt, plc.points.size());
  to.progress = [&](double x) { report_progress(0.05 + 0.75 * std::clamp(x, 0.0, 1.0), "refine"); };
  report_progress(0.05, "refine");
  TetResult tr = fdr::tetrahedralize(plc, *f, to);
  clock.lap("tetrahedralize");
  r.mesh = std::move(tr.mesh);

  report_progress(0.8, "report");
  r.measured = !opt.quiet || !opt.report_json.empty() || has_vtu(opt.outputs) || !opt.report_only_if_read;
  if (r.measured) {
    quality::TetValues values;
    r.report = quality::measure_tets(r.mesh, *f, tr.stats, has_vtu(opt.outputs) ? &values : nullptr);
    if (has_vtu(opt.outputs)) add_cell_fields(r.mesh, std::move(values));
    clock.lap("report");
  } else {
    r.report.stats = tr.stats;
    r.report.bound_B = tr.stats.bound;
    r.report.vertices = r.mesh.points.size();
    r.report.tets = r.mesh.tets.size();
  }
  r.report.input_file = opt.input;
  if (opt.check) {
    quality::check_tets(r.mesh, plc, *f, tr.stats.bound);  // Error(kCheckFailed) before anything is written
    r.report.check_passed = true;
    clock.lap("check");
  }

  report_progress(0.9, "write");
  tetio::write_tets_all(opt.outputs, r.mesh);
  r.written = opt.outputs;
  clock.lap("write");
  time_report3(r, t_start);
  if (!opt.report_json.empty()) {
    OutFile out(opt.report_json);
    std::ostringstream s;
    quality::write_json3(r.report, s);
    out.write(s.str());
    out.commit();
    r.written.push_back(opt.report_json);
  }
  report_progress(1.0, "done");
  return r;
}

void write_summary3(const Result3& r, std::ostream& out) {
  if (r.measured) quality::write_text3(r.report, out);
  else out << "3D mesh: " << r.report.vertices << " vertices, " << r.report.tets << " tetrahedra\n";
  if (!r.layers.empty()) out << "Layers (volume against the volume between their surfaces as triangulated):\n";
  for (const LayerFigures& l : r.layers) {
    char line[256];
    const double rel = l.expected > 0 ? (l.volume - l.expected) / l.expected : 0.0;
    std::snprintf(line, sizeof line, "  %3d %-24s %10zu tets  %.6g m3  expected %.6g m3  (%+.2e)\n",
                  static_cast<int>(l.material), l.name.c_str(), l.tets, l.volume, l.expected, rel);
    out << line;
  }
  write_stages_and_outputs(r.stages, r.written, out);
}

}  // namespace fdr::pipeline
