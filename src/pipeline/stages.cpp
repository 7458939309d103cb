// The run's plan (usage checks before any I/O), the measure stage and the write stage.
#include "base/path_util.hpp"
#include "pipeline/stages.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include "api/stages.hpp"
#include "base/error.hpp"
#include "base/memory.hpp"
#include "base/redact.hpp"
#include "base/step_laps.hpp"
#include "base/threads.hpp"
#include "base/version.hpp"
#include "io/write_many.hpp"
#include "pipeline/gis_backend.hpp"
#include "predicates/predicates.hpp"
#include "quality/rss.hpp"
#include "quality/tin_error.hpp"

namespace fdr::pipeline {
namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }


// The .cli written beside a Selafin output.
std::string cli_path_of(const std::string& slf) {
  const std::string e = lower_ext(slf);
  return (e == "slf" ? slf.substr(0, slf.size() - 4) : slf) + ".cli";
}

// Per-triangle R/f(c), min angle and area in the metric frame, for outputs written in --output-crs.
void metric_triangle_values(const mesh::MeshView& m, const sizing::SizingField& f, std::vector<double>& r_over_f,
                            std::vector<double>& min_angle, std::vector<double>& area) {
  r_over_f.resize(m.triangles.size());
  min_angle.resize(m.triangles.size());
  area.resize(m.triangles.size());
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const Point2 a = m.vertices[m.triangles[t][0]], b = m.vertices[m.triangles[t][1]], c = m.vertices[m.triangles[t][2]];
    double r2;
    const Point2 cc = predicates::circumcenter(a, b, c, &r2);
    r_over_f[t] = std::sqrt(r2) / f(cc);
    const double la = dist(b, c), lb = dist(c, a), lc = dist(a, b);
    auto ang = [](double x, double y, double z) {  // angle opposite x
      return std::acos(std::clamp((y * y + z * z - x * x) / (2 * y * z), -1.0, 1.0)) * 180.0 / 3.14159265358979323846;
    };
    min_angle[t] = std::min({ang(la, lb, lc), ang(lb, lc, la), ang(lc, la, lb)});
    area[t] = 0.5 * ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
  }
}
}  // namespace

bool is_poly_input(const std::string& path) {
  const std::string e = lower_ext(path);
  return e == "poly" || e == "node";
}

bool stores_triangle_values(const std::vector<io::Format>& formats) {
  return std::any_of(formats.begin(), formats.end(), [](io::Format fm) {
    return fm == io::Format::kGpkg || fm == io::Format::kVtu || fm == io::Format::kUgrid || fm == io::Format::kPostgis;
  });
}

Plan plan_run(const Options& opt) {
  Plan p;
  if (opt.input.empty() && opt.land.empty())
    throw Error(ExitCode::kUsage, "no input given: INPUT (a .poly/.node file or water polygons) or --land with --extent");
  p.source = !opt.input.empty() ? opt.input : opt.land;
  p.gis = !is_poly_input(opt.input);
  if (!(opt.bound > 0) || !std::isfinite(opt.bound)) throw Error(ExitCode::kUsage, "--bound must be a positive number");
  if (opt.min_angle_deg >= 60 || std::isnan(opt.min_angle_deg)) throw Error(ExitCode::kUsage, "--min-angle must be in [0, 60)");
  if (opt.smooth_passes > 100) throw Error(ExitCode::kUsage, "--smooth must be in [0, 100]");
  // Model-ready defaults for GIS inputs: a 30 degree angle bound and smoothing (README).
  TriangulateOptions& t = p.triangulate;
  t.bound = opt.bound;
  t.min_angle_deg = opt.min_angle_deg >= 0 ? opt.min_angle_deg : (p.gis ? 30.0 : 0.0);
  t.angle_split_min_f = p.gis ? 0.5 : 0.0;
  t.smooth_passes = opt.smooth_passes >= 0 ? opt.smooth_passes : (p.gis ? 4 : 0);
  t.max_steiner = opt.max_steiner;
  t.check = opt.check;
  t.source = p.source;
  // Output formats: a bad -o fails before any work.
  for (const auto& o : opt.outputs) p.formats.push_back(io::format_from_path(o, opt.of));
  if (!opt.telemac_open.empty()) p.telemac_codes = io::parse_telemac_codes(opt.telemac_open);
  for (std::size_t i = 0; i < p.formats.size(); ++i)
    if (p.formats[i] == io::Format::kLl && !p.gis)
      throw Error(ExitCode::kUsage, opt.outputs[i] + ": hgrid.ll needs lon/lat, but a .poly/.node input has no CRS; "
                                                     "write .gr3 instead or mesh from GIS layers");
  if (!p.gis) return p;
  // GIS options that need another option (checked again where they are used).
  if (!opt.land.empty() && !opt.extent) throw Error(ExitCode::kUsage, "--land needs --extent XMIN,YMIN,XMAX,YMAX");
  if (opt.open_boundary.empty() && !opt.open_boundary_layer.empty())
    throw Error(ExitCode::kUsage, "--open-boundary-layer needs --open-boundary FILE");
  if (opt.breaklines.empty() && !opt.breaklines_layer.empty())
    throw Error(ExitCode::kUsage, "--breaklines-layer needs --breaklines FILE");
  if (opt.points.empty() && !opt.points_layer.empty())
    throw Error(ExitCode::kUsage, "--points-layer needs --points FILE");
  auto negative = [](const std::optional<double>& v) { return v && !(*v >= 0); };
  if (negative(opt.close_width) || negative(opt.min_feature) || negative(opt.min_island_factor))
    throw Error(ExitCode::kUsage, "--close-width, --min-feature and --min-island must be >= 0");
  if (opt.slope_rule && opt.raster.empty()) throw Error(ExitCode::kUsage, "--slope-rule needs --raster");
  if (opt.wavelength_rule && opt.raster.empty()) throw Error(ExitCode::kUsage, "--wavelength-rule needs --raster");
  if (opt.vertical_tol && opt.raster.empty()) throw Error(ExitCode::kUsage, "--vertical-tol needs --raster (the DEM)");
  const bool any_rule = opt.dist_grade || opt.slope_rule || opt.wavelength_rule || opt.vertical_tol ||
                        !opt.size_raster.empty();
  const bool spacing_grid = !opt.raster.empty() || any_rule || opt.spacing.empty();
  if (spacing_grid && !(opt.gradation > 0)) throw Error(ExitCode::kUsage, "--gradation must be positive");
  if (!(opt.densify_deg >= 0 && opt.densify_deg <= 90))
    throw Error(ExitCode::kUsage, "--densify must be between 0 (off) and 90 degrees");
  if (!opt.keep_coast && !(opt.coast_tol >= 0)) throw Error(ExitCode::kUsage, "--coast-tol must be >= 0");
  if (!opt.write_spacing.empty() && !spacing_grid)
    throw Error(ExitCode::kUsage, "--write-spacing needs a raster-based spacing (give --raster or a rule)");
  return p;
}

namespace {
// True if one of the formats stores the run's metadata, the JSON report among it (GPKG, UGRID,
// D-Flow FM net file).
bool stores_metadata(const std::vector<io::Format>& formats) {
  return std::any_of(formats.begin(), formats.end(), [](io::Format fm) {
    return fm == io::Format::kGpkg || fm == io::Format::kUgrid || fm == io::Format::kDflowfm ||
           fm == io::Format::kPostgis;
  });
}

RunFigures run_figures(const TriangulateFigures& fig) {
  RunFigures rf;
  rf.cdt_s = fig.cdt_s;
  rf.refine_s = fig.refine.refine_s;
  rf.segment_splits = fig.refine.stats.segment_splits;
  rf.circumcenters = fig.refine.stats.circumcenters;
  rf.angle_exempt = fig.refine.angle_exempt;
  rf.alpha = fig.refine.alpha;
  rf.conforming_D = fig.refine.stats.conforming_D;
  rf.conforming_D_at = fig.refine.stats.conforming_D_at;
  return rf;
}

void add_repairs(quality::QualityReport& r, const PreparedInput& in) {
  for (const auto& rp : in.repairs) r.repairs.push_back({rp.kind, rp.x, rp.y, rp.ids, rp.reason});
}
}  // namespace

bool report_is_read(const Options& opt, const Plan& plan) {
  if (!opt.report_only_if_read || !opt.quiet || !opt.report_json.empty()) return true;
  return stores_triangle_values(plan.formats) || stores_metadata(plan.formats);
}

quality::QualityReport unmeasured_report(mesh::MeshView& m, const PreparedInput& in, const Options& opt,
                                         const Plan& plan, const TriangulateFigures& fig) {
  quality::QualityReport r;
  r.vertices = m.num_vertices();
  r.triangles = m.num_triangles();
  r.bound_B = opt.bound;
  r.alpha = fig.refine.alpha;
  const sizing::SizingField* f = in.f.get();
  r.run = run_info(f, plan.triangulate, run_figures(fig));
  r.spacing = r.run.spacing;
  add_repairs(r, in);
  // .node files carry f at the vertices, which the report fills (the same evaluations).
  const bool node_out = std::find(plan.formats.begin(), plan.formats.end(), io::Format::kNode) != plan.formats.end();
  if (f && node_out && m.f.empty()) {
    resize_huge(m.f, m.num_vertices());
    for (std::size_t v = 0; v < m.f.size(); ++v) m.f[v] = (*f)(m.vertices[v]);
  }
  if (!std::any_of(plan.formats.begin(), plan.formats.end(), io::carries_boundaries)) release_huge(m.neighbours);
  return r;
}

quality::QualityReport measure(mesh::MeshView& m, const PreparedInput& in, const Options& opt, const Plan& plan,
                               const TriangulateFigures& fig, quality::TriangleValues* tri_values, const LogFn& log) {
  std::optional<std::pair<double, double>> tin;  // terrain runs: the TIN against the DEM
  if (in.dem && opt.vertical_tol) tin = gis_backend().tin_error(m, *in.dem, log);
  const RunFigures rf = run_figures(fig);
  // Per-triangle R/f(c), angle and area for the writers that store them, measured once here (the
  // writers then never evaluate f, which lets them run concurrently).
  // Model readiness against the input coast (issue 11) first: it reads the mesher's adjacency,
  // which measure_mesh releases unless an output's boundary lists read it.
  StepLaps lap(debug::Aid::kReport, "report");  // developer aid (base/step_laps.hpp)
  std::optional<quality::ModelReadiness> ready;
  if (plan.gis) ready = quality::compute_model_readiness(m, {in.hmin, opt.min_depth_m, &in.input_boundary, &in.coast_figures});
  lap("model readiness");
  const bool boundaries = std::any_of(plan.formats.begin(), plan.formats.end(), io::carries_boundaries);
  quality::QualityReport report = measure_mesh(m, in.f.get(), plan.triangulate, rf, tri_values, boundaries);
  lap("quality");
  report.model_ready = std::move(ready);
  add_repairs(report, in);
  if (tin) {
    report.vertical_error_max_m = tin->first;
    report.vertical_error_rms_m = tin->second;
  }
  return report;
}

std::vector<std::string> write_outputs(Result& result, const PreparedInput& in, const Options& opt, const Plan& plan,
                                       const quality::TriangleValues* tri_values, Clock::time_point t_start,
                                       const ProgressFn& progress) {
  const auto t_write = Clock::now();
  const mesh::MeshView& m = result.mesh;
  const sizing::SizingField& f = *in.f;
  io::WriteOptions wo;
  wo.f = &f;
  wo.bound_B = opt.bound;
  wo.title = redact_passwords(plan.source);  // a PostGIS source names its server, not its password
  wo.postgis = {opt.pg_prefix, opt.pg_schema, opt.pg_overwrite};
  wo.slf_double = opt.slf_double;
  wo.telemac_open_codes = plan.telemac_codes;
  // The writers' metadata, for the formats that store it (GPKG, UGRID, D-Flow FM net file); the
  // report as JSON is large with many repairs (30 MB on the Gulf of Maine).
  if (stores_metadata(plan.formats)) {
    std::ostringstream js;
    quality::write_json(result.report, js);
    wo.metadata = {{"software", std::string("fdrmesh ") + kVersion},
                   {"command_line", redact_passwords(opt.command_line)},
                   {"input", redact_passwords(plan.source)},
                   {"spacing", f.describe()},
                   {"bound_B", std::to_string(opt.bound)},
                   {"min_angle_deg", std::to_string(plan.triangulate.min_angle_deg)},
                   {"alpha", std::to_string(result.alpha)},
                   {"crs", result.crs_name}};
    wo.metadata.emplace_back("quality", std::move(js).str());  // moved, not copied
    for (const auto& kv : in.metadata) wo.metadata.push_back(kv);
  }
  wo.repairs = in.repairs;
  // --output-crs: quality columns are computed in the metric frame, then the copy is reprojected.
  mesh::MeshView projected;
  std::vector<double> r_over_f, min_angle, area;
  const mesh::MeshView* to_write = &m;
  if (plan.gis && !opt.output_crs.empty() && !opt.outputs.empty()) {
    metric_triangle_values(m, f, r_over_f, min_angle, area);
    projected = m;
    gis_backend().reproject_mesh(projected, in, opt.output_crs);
    wo.f = nullptr;
    wo.triangle_r_over_f = &r_over_f;
    wo.triangle_min_angle = &min_angle;
    wo.triangle_area = &area;
    to_write = &projected;
  }
  // All or nothing: if a later output (mesh, spacing GeoTIFF, report) fails or the run is
  // cancelled, the files already written are removed again.
  std::vector<std::string> written, extra_paths;
  if (!opt.write_spacing.empty()) extra_paths.push_back(opt.write_spacing);
  try {
    if (tri_values) {
      wo.f = nullptr;  // m.f holds f at the vertices; the triangles' values come from the report
      wo.triangle_r_over_f = &tri_values->r_over_f;
      wo.triangle_min_angle = &tri_values->min_angle_deg;
      wo.triangle_area = &tri_values->area;
    }
    // Concurrent writers are safe: only GPKG, VTU and UGRID would evaluate f, and they get the
    // report's values instead (or the --output-crs ones, with wo.f null).
    // The writers are on the GIS side (GeoPackage: SQLite, UGRID: netCDF): loaded only when there
    // are outputs.
    if (!opt.outputs.empty()) gis_backend().write_meshes(*to_write, opt.outputs, plan.formats, wo, fdr::max_threads());
    for (std::size_t i = 0; i < opt.outputs.size(); ++i) {
      written.push_back(opt.outputs[i]);
      if (plan.formats[i] == io::Format::kSelafin) extra_paths.push_back(cli_path_of(opt.outputs[i]));
      if (plan.formats[i] == io::Format::kNode) {
        const std::string& o = opt.outputs[i];
        const auto dot = o.find_last_of('.');
        extra_paths.push_back((dot == std::string::npos ? o : o.substr(0, dot)) + ".ele");
      }
    }
    if (plan.gis && !opt.write_spacing.empty()) gis_backend().write_spacing_geotiff(in, opt.write_spacing);
    result.report.run.write_s = since(t_write);
    result.report.run.total_s = since(t_start);
    result.report.run.peak_rss_mb = quality::peak_rss_mb_value();
    if (!opt.report_json.empty()) {
      quality::write_json_file(result.report, opt.report_json);
      written.push_back(opt.report_json);
    }
    if (progress && !progress(1.0, "done")) throw Error(ExitCode::kCancelled, "cancelled during done");
  } catch (...) {
    for (const auto& w : written) std::remove(w.c_str());
    for (const auto& w : extra_paths) std::remove(w.c_str());
    throw;
  }
  return written;
}

}  // namespace fdr::pipeline
