// Pipeline: read the input, build the spacing f, CDT, FDR refinement, quality report, writers.
#include "pipeline/pipeline.hpp"
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include "base/error.hpp"
#include "base/version.hpp"
#include "cdt/cdt.hpp"
#include "io/writer.hpp"
#include "mesh/check.hpp"
#include "pipeline/gis_stage.hpp"
#include "predicates/predicates.hpp"
#include "pslg/poly_io.hpp"
#include "pslg/resolve.hpp"
#include "pslg/validate.hpp"
#include "quality/rss.hpp"
#include "refine/refine.hpp"
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

// Text report of the constraint repairs of a .poly input: counts per kind, then each fix (the
// first 20). The GIS path prints its own summary line.
void log_repairs(const LogFn& log, const std::vector<io::RepairRow>& reps, bool poly) {
  if (!poly || reps.empty()) return;
  std::map<std::string, std::size_t> kinds;
  for (const auto& r : reps) ++kinds[r.kind];
  std::string s = "repairs: " + std::to_string(reps.size());
  for (const auto& [k, n] : kinds) s += ", " + k + " " + std::to_string(n);
  log_info(log, s + " (--strict refuses conflicting constraints instead)");
  char buf[128];
  for (std::size_t i = 0; i < reps.size() && i < 20; ++i) {
    const auto& r = reps[i];
    std::snprintf(buf, sizeof buf, "  %s at (%.17g, %.17g)", r.kind.c_str(), r.x, r.y);
    std::string line = buf;
    if (!r.ids.empty()) {
      line += " ids";
      for (auto id : r.ids) line += " " + std::to_string(id);
    }
    log_info(log, line + ": " + r.reason);
  }
  if (reps.size() > 20) log_info(log, "  ... " + std::to_string(reps.size() - 20) + " more (see the JSON report)");
}
}  // namespace

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
  if (opt.min_angle_deg < 0 || opt.min_angle_deg >= 60) throw Error(ExitCode::kUsage, "--min-angle must be in [0, 60)");
  // Resolve output formats first: a bad -o fails before any work.
  std::vector<io::Format> formats;
  for (const auto& o : opt.outputs) formats.push_back(io::format_from_path(o, opt.of));
  predicates::reset_counters();

  Result result;
  PreparedInput in;
  report_progress(0.0, "read");
  StageClock clock(&result.stages);  // per-stage timing hooks (Result::stages)
  if (is_poly_input(opt.input)) {
    in.pslg = lower_ext(opt.input) == "node" ? pslg::read_node(opt.input) : pslg::read_poly(opt.input);
    // --strict: today's refusal (exit 5 naming the first conflict) in the input's coordinates.
    if (opt.strict) pslg::validate(in.pslg, opt.input);
    else
      for (std::size_t i = 0; i < in.pslg.points.size(); ++i)  // before the bbox below
        if (!std::isfinite(in.pslg.points[i].x) || !std::isfinite(in.pslg.points[i].y))
          throw Error(ExitCode::kInvalidGeometry, opt.input + ": vertex " + std::to_string(i) + " has a non-finite coordinate");
    const Point2 origin = choose_origin(in.pslg.bbox());
    if (origin.x != 0 || origin.y != 0) {
      for (auto& p : in.pslg.points) p = {p.x - origin.x, p.y - origin.y};
      for (auto& p : in.pslg.holes) p = {p.x - origin.x, p.y - origin.y};
      for (auto& r : in.pslg.regions) r.seed = {r.seed.x - origin.x, r.seed.y - origin.y};
      in.pslg.origin = origin;
    }
    // Conflicting constraints are resolved in the local frame, where the CDT decides.
    if (!opt.strict) {
      std::vector<pslg::Repair> reps;
      pslg::ResolveOptions ro;
      ro.source = opt.input;
      in.pslg = pslg::resolve(in.pslg, ro, &reps);
      for (const auto& r : reps) {
        const Point2 w = in.pslg.origin + r.where;
        in.repairs.push_back({r.kind, w.x, w.y, r.size, r.reason, r.part});
        in.repairs.back().ids = r.ids;
      }
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
  }
  result.repairs = in.repairs.size();
  log_repairs(log, in.repairs, is_poly_input(opt.input));
  if (in.stages.empty()) clock.lap("read");
  else result.stages = in.stages;
  report_progress(0.05, "cdt");
  clock.restart();

  // Constrained Delaunay triangulation.
  const auto t_cdt = Clock::now();
  cdt::CdtStats cstats;
  cdt::CdtOptions copt;
  // .poly: Triangle's semantics (the exterior and hole seeds are removed, nested rings are not
  // holes by themselves); GIS: constraint parity (kAuto).
  copt.regions = opt.convex_hull                 ? cdt::CdtOptions::Regions::kHull
                 : is_poly_input(opt.input) && !in.pslg.segments.empty() ? cdt::CdtOptions::Regions::kSeeds
                                                 : cdt::CdtOptions::Regions::kAuto;
  copt.source = source;
  mesh::Triangulation tri = cdt::build_cdt(in.pslg, copt, &cstats);
  const double cdt_s = since(t_cdt);
  clock.lap("cdt");
  if (tri.num_live_triangles() == 0)
    throw Error(ExitCode::kInvalidGeometry,
                source + ": the domain is empty (no region enclosed by segments)" +
                    (is_poly_input(opt.input) && !opt.convex_hull
                         ? "; give --convex-hull to mesh the convex hull of the vertices (point sets, dangling breaklines)"
                         : ""));

  // Spacing checks: alpha, positivity inside the domain (during the estimate), work estimate.
  const sizing::SizingField& f = *in.f;
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
  ro.min_angle_deg = opt.min_angle_deg;
  ro.max_steiner = opt.max_steiner;
  ro.expected_steiner = expected / 2;
  for (const auto& r : in.pslg.regions) ro.region_max_area.push_back(r.max_area);
  ro.progress = [&](double frac, std::string_view) {
    return !progress || progress(0.05 + 0.75 * frac, "refine");
  };
  refine::Refiner refiner(tri, f, ro);
  refiner.reserve(expected);
  refiner.init();
  refiner.run();
  const double refine_s = since(t_ref);
  clock.lap("refine");
  report_progress(0.8, "report");

  if (opt.check) {
    mesh::CheckResult cr = mesh::check_all(tri);
    const std::size_t bad = refiner.leftovers().r_over_f_bad;
    if (bad) cr.add(std::to_string(bad) + " triangles have R/f(c) > B");
    if (!cr.ok()) {
      std::string msg = "--check failed: " + std::to_string(cr.count) + " violations";
      for (const auto& p : cr.problems) msg += "\n  " + p;
      throw Error(ExitCode::kCheckFailed, msg);
    }
    log_info(log, "check: topology, orientation, constrained Delaunay, segments and R/f(c) <= B hold");
    clock.lap("check");
  }

  result.mesh = tri.to_view();
  auto& m = result.mesh;
  if (in.attach) in.attach(m);  // depths, CRS (GIS runs)
  clock.lap("depths");
  if (m.f.empty()) {
    m.f.resize(m.vertices.size());
    for (std::size_t i = 0; i < m.vertices.size(); ++i) m.f[i] = f(m.vertices[i]);
  }

  quality::RunInfo ri;
  ri.cdt_s = cdt_s;
  ri.refine_s = refine_s;
  ri.predicate_filtered = predicates::counters().filtered;
  ri.predicate_exact = predicates::counters().exact;
  ri.exempt_small_angle_triangles = refiner.leftovers().angle_bad;
  ri.steiner_segment = refiner.stats().segment_splits;
  ri.steiner_interior = refiner.stats().circumcenters;
  ri.input_file = source;
  ri.spacing = f.describe();
  if (opt.min_angle_deg > 0) ri.min_angle_option_deg = opt.min_angle_deg;
  result.report = quality::compute_quality(m, &f, opt.bound, alpha, ri);
  for (const auto& r : in.repairs) result.report.repairs.push_back({r.kind, r.x, r.y, r.ids, r.reason});
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
  {
    std::ostringstream js;
    quality::write_json(result.report, js);
    wo.metadata = {{"software", std::string("fdrmesh ") + kVersion},
                   {"command_line", opt.command_line},
                   {"input", source},
                   {"spacing", f.describe()},
                   {"bound_B", std::to_string(opt.bound)},
                   {"min_angle_deg", std::to_string(opt.min_angle_deg)},
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
    for (std::size_t i = 0; i < opt.outputs.size(); ++i) {
      io::write_mesh(*to_write, opt.outputs[i], formats[i], wo);
      result.written.push_back(opt.outputs[i]);
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
