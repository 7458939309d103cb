// Pipeline: read the input, build the spacing f, CDT, FDR refinement, quality report, writers.
#include "pipeline/pipeline.hpp"
#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <memory>
#include <sstream>
#include "base/error.hpp"
#include "base/version.hpp"
#include "cdt/cdt.hpp"
#include "io/write_many.hpp"
#include "io/writer.hpp"
#include "mesh/check.hpp"
#include "mesh/take_view.hpp"
#include "pipeline/gis_stage.hpp"
#include "predicates/predicates.hpp"
#include "pslg/poly_io.hpp"
#include "pslg/validate.hpp"
#include "quality/rss.hpp"
#include "refine/refine.hpp"
#include "refine/smooth.hpp"
#include "sizing/field_checks.hpp"
#include "sizing/fields.hpp"
#include "sizing/make_spacing.hpp"

namespace fdr::pipeline {
namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

std::string lower_ext(const std::string& path) {
  const auto dot = path.find_last_of('.');
  const auto slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string e = path.substr(dot + 1);
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return e;
}


// Local origin for a .poly input: shift only when the coordinates are far from 0 relative to the
// extent (e.g. projected metres), so that small inputs keep their exact coordinates.
Point2 choose_origin(const Box2& b) {
  const Point2 c = b.center();
  const double size = std::max({b.width(), b.height(), 1e-300});
  if (std::max(std::fabs(c.x), std::fabs(c.y)) < 1e3 * size) return {0, 0};
  const double unit = std::pow(10.0, std::floor(std::log10(size)));
  return {std::round(c.x / unit) * unit, std::round(c.y / unit) * unit};
}

void log_info(const LogFn& log, const std::string& s) {
  if (log) log(LogLevel::kInfo, s);
}
}  // namespace

// The .cli written beside a Selafin output.
static std::string cli_path_of(const std::string& slf) {
  const std::string e = lower_ext(slf);
  return (e == "slf" ? slf.substr(0, slf.size() - 4) : slf) + ".cli";
}

bool is_poly_input(const std::string& path) {
  const std::string e = lower_ext(path);
  return e == "poly" || e == "node";
}

Result run(const Options& opt, const ProgressFn& progress, const LogFn& log) {
  const auto t_start = Clock::now();
  auto report_progress = [&](double frac, const char* stage) {
    if (progress && !progress(frac, stage)) throw Error(ExitCode::kCancelled, std::string("cancelled during ") + stage);
  };
  if (opt.input.empty() && opt.land.empty())
    throw Error(ExitCode::kUsage, "no input given: INPUT (a .poly/.node file or water polygons) or --land with --extent");
  // The name used in messages, titles and metadata.
  const std::string source = !opt.input.empty() ? opt.input : opt.land;
  if (!(opt.bound > 0) || !std::isfinite(opt.bound)) throw Error(ExitCode::kUsage, "--bound must be a positive number");
  if (opt.min_angle_deg >= 60 || std::isnan(opt.min_angle_deg)) throw Error(ExitCode::kUsage, "--min-angle must be in [0, 60)");
  // Model-ready defaults for GIS inputs: a 30 degree angle bound and smoothing (README).
  const bool gis_input = !is_poly_input(opt.input);
  const double min_angle_deg = opt.min_angle_deg >= 0 ? opt.min_angle_deg : (gis_input ? 30.0 : 0.0);
  const int smooth_passes = opt.smooth_passes >= 0 ? opt.smooth_passes : (gis_input ? 4 : 0);
  if (opt.smooth_passes > 100) throw Error(ExitCode::kUsage, "--smooth must be in [0, 100]");
  // Resolve output formats first: a bad -o fails before any work.
  std::vector<io::Format> formats;
  for (const auto& o : opt.outputs) formats.push_back(io::format_from_path(o, opt.of));
  const std::array<int, 3> telemac_codes =
      opt.telemac_open.empty() ? std::array<int, 3>{5, 4, 4} : io::parse_telemac_codes(opt.telemac_open);
  for (std::size_t i = 0; i < formats.size(); ++i)
    if (formats[i] == io::Format::kLl && is_poly_input(opt.input))
      throw Error(ExitCode::kUsage, opt.outputs[i] + ": hgrid.ll needs lon/lat, but a .poly/.node input has no CRS; "
                                                     "write .gr3 instead or mesh from GIS layers");
  predicates::reset_counters();

  Result result;
  PreparedInput in;
  report_progress(0.0, "read");
  StageClock clock(&result.stages);  // per-stage timing hooks (Result::stages)
  if (is_poly_input(opt.input)) {
    in.pslg = lower_ext(opt.input) == "node" ? pslg::read_node(opt.input) : pslg::read_poly(opt.input);
    pslg::validate(in.pslg, opt.input);
    const Point2 origin = choose_origin(in.pslg.bbox());
    if (origin.x != 0 || origin.y != 0) {
      for (auto& p : in.pslg.points) p = {p.x - origin.x, p.y - origin.y};
      for (auto& p : in.pslg.holes) p = {p.x - origin.x, p.y - origin.y};
      for (auto& r : in.pslg.regions) r.seed = {r.seed.x - origin.x, r.seed.y - origin.y};
      in.pslg.origin = origin;
    }
    // Default spacing for a bare PSLG: a twentieth of the bounding-box diagonal.
    std::string spec = opt.spacing;
    if (spec.empty()) {
      const Box2 b = in.pslg.bbox();
      std::ostringstream s;
      s.precision(17);
      s << std::hypot(b.width(), b.height()) / 20.0;
      spec = s.str();
    }
    in.f = std::make_shared<sizing::ShiftedField>(sizing::make_spacing(spec), in.pslg.origin);
  } else {
    in = prepare_gis_input(opt, progress, log);
    result.crs_name = in.crs_name;
    result.repairs = in.repairs.size();
    result.repair_rows = in.repairs;
  }
  if (in.stages.empty()) clock.lap("read");
  else result.stages = in.stages;
  report_progress(0.05, "cdt");
  clock.restart();

  // Constrained Delaunay triangulation.
  const auto t_cdt = Clock::now();
  cdt::CdtStats cstats;
  mesh::Triangulation tri = cdt::build_cdt(in.pslg, {cdt::CdtOptions::Regions::kAuto, source}, &cstats);
  const double cdt_s = since(t_cdt);
  clock.lap("cdt");
  if (tri.num_live_triangles() == 0)
    throw Error(ExitCode::kInvalidGeometry, source + ": the domain is empty (no region enclosed by segments)");

  // Spacing checks: alpha, positivity inside the domain (during the estimate), work estimate.
  const sizing::SizingField& f = *in.f;
  result.f = in.f;
  Box2 box = in.pslg.bbox();
  double alpha = f.lipschitz();
  if (!(alpha >= 0)) alpha = sizing::estimate_lipschitz(f, box, 64);
  if (alpha * opt.bound >= 1)
    log(LogLevel::kWarning, "alpha*B = " + std::to_string(alpha * opt.bound) +
                                " >= 1: the spacing varies too fast for the FDR guarantees (termination still "
                                "bounded by --max-steiner); lower --bound or smooth the spacing");
  const double expected = refine::estimate_triangles(tri, f, opt.bound);
  log_info(log, "expected about " + std::to_string(static_cast<long long>(expected)) + " triangles");
  if (expected > 2.5 * static_cast<double>(opt.max_steiner))
    throw Error(ExitCode::kWorkLimit, "the spacing asks for about " + std::to_string(static_cast<long long>(expected)) +
                                          " triangles, more than --max-steiner " + std::to_string(opt.max_steiner) +
                                          " allows; coarsen the spacing or raise --max-steiner");

  // Functional Delaunay Refinement.
  const auto t_ref = Clock::now();
  refine::RefineOptions ro;
  ro.bound = opt.bound;
  ro.min_angle_deg = min_angle_deg;
  ro.max_steiner = opt.max_steiner;
  ro.expected_steiner = expected / 2;
  ro.progress = [&](double frac, std::string_view) {
    return !progress || progress(0.05 + 0.75 * frac, "refine");
  };
  auto refiner = std::make_unique<refine::Refiner>(tri, f, ro);  // freed once the mesh is copied out
  refiner->reserve(expected);
  refiner->init();
  refiner->run();
  const double refine_s = since(t_ref);
  clock.lap("refine");
  if (smooth_passes > 0) {
    refine::SmoothOptions so;
    so.passes = smooth_passes;
    so.bound = opt.bound;
    so.min_angle_deg = min_angle_deg;
    const refine::SmoothStats ss = refine::smooth(tri, f, so);
    log_info(log, "smoothing: " + std::to_string(ss.moves) + " moves (" + std::to_string(ss.segment_moves) +
                      " along segments) of " + std::to_string(ss.candidates) + " Steiner vertices in " +
                      std::to_string(ss.passes) + " passes");
    clock.lap("smooth");
  }
  report_progress(0.8, "report");

  if (opt.check) {
    mesh::CheckResult cr = mesh::check_all(tri);
    const std::size_t bad = refiner->leftovers().r_over_f_bad;
    if (bad) cr.add(std::to_string(bad) + " triangles have R/f(c) > B");
    if (!cr.ok()) {
      std::string msg = "--check failed: " + std::to_string(cr.count) + " violations";
      for (const auto& p : cr.problems) msg += "\n  " + p;
      throw Error(ExitCode::kCheckFailed, msg);
    }
    log_info(log, "check: topology, orientation, constrained Delaunay, segments and R/f(c) <= B hold");
    clock.lap("check");
  }

  // The report and the writers read a compact copy: free the refiner before copying and the
  // triangulation after (the peak is then the triangulation plus the copy, not more).
  const refine::RefineStats refine_stats = refiner->stats();
  // leftovers() re-measures every triangle; without --min-angle its angle count is 0 by definition.
  const refine::RefineLeftovers refine_left =
      min_angle_deg > 0 ? refiner->leftovers() : refine::RefineLeftovers{};
  refiner.reset();
  result.mesh = mesh::take_view(tri);  // same as tri.to_view(), releasing tri on the way
  auto& m = result.mesh;
  if (in.attach) in.attach(m);  // depths, CRS (GIS runs)
  clock.lap("depths");
  const bool f_from_field = m.f.empty();  // then m.f holds f at the vertices, which the report reuses
  if (m.f.empty()) {
    m.f.resize(m.vertices.size());
    for (std::size_t i = 0; i < m.vertices.size(); ++i) m.f[i] = f(m.vertices[i]);
  }

  quality::RunInfo ri;
  ri.cdt_s = cdt_s;
  ri.refine_s = refine_s;
  ri.predicate_filtered = predicates::counters().filtered;
  ri.predicate_exact = predicates::counters().exact;
  ri.exempt_small_angle_triangles = refine_left.angle_bad;
  ri.steiner_segment = refine_stats.segment_splits;
  ri.steiner_interior = refine_stats.circumcenters;
  ri.input_file = source;
  ri.spacing = f.describe();
  if (min_angle_deg > 0) ri.min_angle_option_deg = min_angle_deg;
  // Per-triangle R/f(c), angle and area for the writers that store them, measured once here (the
  // writers then never evaluate f, which lets them run concurrently).
  quality::TriangleValues tri_values;
  const bool want_tri_values = !in.to_output_crs && std::any_of(formats.begin(), formats.end(), [](io::Format fm) {
    return fm == io::Format::kGpkg || fm == io::Format::kVtu || fm == io::Format::kUgrid;
  });
  result.report = quality::compute_quality(m, &f, opt.bound, alpha, ri, want_tri_values ? &tri_values : nullptr,
                                           f_from_field ? &m.f : nullptr);
  if (!is_poly_input(opt.input)) {  // GIS runs: model readiness against the input coast (issue 11)
    result.report.model_ready = quality::compute_model_readiness(
        m, {in.hmin, opt.min_depth_m, &in.input_boundary, &in.coast_figures});
  }
  if (in.tin_error && *in.tin_error) {
    result.report.vertical_error_max_m = (*in.tin_error)->first;
    result.report.vertical_error_rms_m = (*in.tin_error)->second;
  }
  clock.lap("report");
  report_progress(0.9, "write");

  // Writers.
  const auto t_write = Clock::now();
  io::WriteOptions wo;
  wo.f = &f;
  wo.bound_B = opt.bound;
  wo.title = source;
  wo.slf_double = opt.slf_double;
  wo.telemac_open_codes = telemac_codes;
  {
    std::ostringstream js;
    quality::write_json(result.report, js);
    wo.metadata = {{"software", std::string("fdrmesh ") + kVersion},
                   {"command_line", opt.command_line},
                   {"input", source},
                   {"spacing", f.describe()},
                   {"bound_B", std::to_string(opt.bound)},
                   {"min_angle_deg", std::to_string(min_angle_deg)},
                   {"alpha", std::to_string(alpha)},
                   {"crs", result.crs_name},
                   {"quality", js.str()}};
    for (const auto& kv : in.metadata) wo.metadata.push_back(kv);
  }
  wo.repairs = in.repairs;
  // --output-crs: quality columns are computed in the metric frame, then the copy is reprojected.
  mesh::MeshView projected;
  std::vector<double> r_over_f, min_angle, area;
  const mesh::MeshView* to_write = &m;
  if (in.to_output_crs && !opt.outputs.empty()) {
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
    projected = m;
    in.to_output_crs(projected);
    wo.f = nullptr;
    wo.triangle_r_over_f = &r_over_f;
    wo.triangle_min_angle = &min_angle;
    wo.triangle_area = &area;
    to_write = &projected;
  }
  // All or nothing: if a later output (mesh, spacing GeoTIFF, report) fails or the run is
  // cancelled, the files already written are removed again.
  std::vector<std::string> extra_paths;
  if (!opt.write_spacing.empty()) extra_paths.push_back(opt.write_spacing);
  try {
    if (want_tri_values) {
      wo.f = nullptr;  // m.f holds f at the vertices; the triangles' values come from the report
      wo.triangle_r_over_f = &tri_values.r_over_f;
      wo.triangle_min_angle = &tri_values.min_angle_deg;
      wo.triangle_area = &tri_values.area;
    }
    // Concurrent writers are safe: only GPKG, VTU and UGRID would evaluate f, and they get the
    // report's values instead (or the --output-crs ones, with wo.f null).
    io::write_meshes(*to_write, opt.outputs, formats, wo, io::max_threads());
    for (std::size_t i = 0; i < opt.outputs.size(); ++i) {
      result.written.push_back(opt.outputs[i]);
      if (formats[i] == io::Format::kSelafin) extra_paths.push_back(cli_path_of(opt.outputs[i]));
      if (formats[i] == io::Format::kNode) {
        const std::string& o = opt.outputs[i];
        const auto dot = o.find_last_of('.');
        extra_paths.push_back((dot == std::string::npos ? o : o.substr(0, dot)) + ".ele");
      }
    }
    for (const auto& extra : in.extra_outputs) extra();
    clock.lap("write");
    result.report.run.write_s = since(t_write);
    result.report.run.total_s = since(t_start);
    result.report.run.peak_rss_mb = quality::peak_rss_mb_value();
    if (!opt.report_json.empty()) {
      quality::write_json_file(result.report, opt.report_json);
      result.written.push_back(opt.report_json);
    }
    report_progress(1.0, "done");
  } catch (...) {
    for (const auto& w : result.written) std::remove(w.c_str());
    for (const auto& w : extra_paths) std::remove(w.c_str());
    throw;
  }
  return result;
}

}  // namespace fdr::pipeline
