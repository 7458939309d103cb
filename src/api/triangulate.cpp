// fdrmesh core API: the CLI's .poly path (pipeline.cpp) as a library function, step by step.
#include "base/memory.hpp"
#include "base/path_util.hpp"
#include "api/triangulate.hpp"
#include "api/core_stages.hpp"
#include <optional>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include "cdt/cdt.hpp"
#include "mesh/check.hpp"
#include "predicates/predicates.hpp"
#include "pslg/poly_io.hpp"
#include "pslg/resolve.hpp"
#include "pslg/validate.hpp"
#include "quality/rss.hpp"
#include "refine/refine.hpp"
#include "refine/smooth.hpp"
#include "sizing/field_checks.hpp"
#include "sizing/fields.hpp"
#include "sizing/grid_field.hpp"
#include "sizing/make_spacing.hpp"

namespace fdr {
namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }


// Local origin (same rule as pipeline.cpp): shift only when the coordinates are far from 0
// relative to the extent, so that small inputs keep their exact coordinates.
Point2 choose_origin(const Box2& b) {
  const Point2 c = b.center();
  const double size = std::max({b.width(), b.height(), 1e-300});
  if (std::max(std::fabs(c.x), std::fabs(c.y)) < 1e3 * size) return {0, 0};
  const double unit = std::pow(10.0, std::floor(std::log10(size)));
  return {std::round(c.x / unit) * unit, std::round(c.y / unit) * unit};
}

void info(const LogFn& log, const std::string& s) {
  if (log) log(LogLevel::kInfo, s);
}
}  // namespace

Pslg read_pslg(const std::string& path) {
  // Conflicting constraints are resolved (or refused with --strict) by prepare_pslg.
  return lower_ext(path) == "node" ? pslg::read_node(path) : pslg::read_poly(path);
}

Pslg prepare_pslg(Pslg p, const std::string& source, bool strict, std::vector<pslg::Repair>* repairs) {
  if (strict) {
    pslg::validate(p, source);  // today's refusal, in the input's coordinates
  } else {
    for (std::size_t i = 0; i < p.points.size(); ++i)
      if (!std::isfinite(p.points[i].x) || !std::isfinite(p.points[i].y))
        throw Error(ExitCode::kInvalidGeometry, source + ": vertex " + std::to_string(i) + " has a non-finite coordinate");
  }
  p = to_local_frame(std::move(p));
  if (!strict) {  // resolved in the local frame, where the CDT decides
    pslg::ResolveOptions ro;
    ro.source = source;
    p = pslg::resolve(p, ro, repairs);
  }
  return p;
}

cdt::CdtOptions::Regions poly_regions(const Pslg& p, bool convex_hull) {
  if (convex_hull) return cdt::CdtOptions::Regions::kHull;
  return p.segments.empty() ? cdt::CdtOptions::Regions::kAuto : cdt::CdtOptions::Regions::kSeeds;
}

SizingPtr make_spacing(const std::string& spec) { return sizing::make_spacing(spec); }

std::string default_spacing_spec(const Pslg& pslg) {
  // Computed on the shifted PSLG in the CLI; the extent is the same in both frames.
  Pslg shifted = pslg;
  const Box2 b0 = pslg.bbox();
  const Point2 origin = choose_origin(b0);
  for (auto& p : shifted.points) p = {p.x - origin.x, p.y - origin.y};
  const Box2 b = shifted.bbox();
  std::ostringstream s;
  s.precision(17);
  s << std::hypot(b.width(), b.height()) / 20.0;
  return s.str();
}

SizingPtr grid_spacing(sizing::Grid grid, const std::string& label) {
  return std::make_shared<sizing::GridField>(std::move(grid), label);
}

Pslg to_local_frame(Pslg p) {
  const Point2 origin = choose_origin(p.bbox());
  if (origin.x != 0 || origin.y != 0) {
    for (auto& q : p.points) q = {q.x - origin.x, q.y - origin.y};
    for (auto& q : p.holes) q = {q.x - origin.x, q.y - origin.y};
    for (auto& r : p.regions) r.seed = {r.seed.x - origin.x, r.seed.y - origin.y};
    p.origin = p.origin + origin;
  }
  return p;
}

mesh::Triangulation build_cdt(const Pslg& local, const std::string& source, double* seconds,
                              cdt::CdtOptions::Regions regions, bool suggest_hull) {
  const auto t = Clock::now();
  cdt::CdtOptions co;
  co.regions = regions;
  co.source = source;
  mesh::Triangulation tri = cdt::build_cdt(local, co, nullptr);
  if (seconds) *seconds = since(t);
  if (tri.num_live_triangles() == 0)
    throw Error(ExitCode::kInvalidGeometry,
                source + ": the domain is empty (no region enclosed by segments)" +
                    (suggest_hull && regions != cdt::CdtOptions::Regions::kHull
                         ? "; give --convex-hull to mesh the convex hull of the vertices (point sets, dangling breaklines)"
                         : ""));
  return tri;
}

SizingPtr spacing_in_frame(const std::string& spec, Point2 origin) {
  return std::make_shared<sizing::ShiftedField>(sizing::make_spacing(spec), origin);
}

double lipschitz_of(const SizingField& f, const Box2& box) {
  const double alpha = f.lipschitz();
  return alpha >= 0 ? alpha : sizing::estimate_lipschitz(f, box, 64);
}

RefineOutcome refine_stage(mesh::Triangulation& tri, const SizingField& f, const Box2& box,
                           const TriangulateOptions& opt) {
  auto done = [&opt](const char* stage) {
    if (opt.stage_done) opt.stage_done(stage);
  };
  RefineOutcome out;
  const double alpha = lipschitz_of(f, box);
  out.alpha = alpha;
  if (alpha * opt.bound >= 1 && opt.log)
    opt.log(LogLevel::kWarning, "alpha*B = " + std::to_string(alpha * opt.bound) +
                                    " >= 1: the spacing varies too fast for the FDR guarantees (termination still "
                                    "bounded by --max-steiner); lower --bound or smooth the spacing");
  const double expected = refine::estimate_triangles(tri, f, opt.bound);
  info(opt.log, "expected about " + std::to_string(static_cast<long long>(expected)) + " triangles");
  if (expected > 2.5 * static_cast<double>(opt.max_steiner))
    throw Error(ExitCode::kWorkLimit, "the spacing asks for about " + std::to_string(static_cast<long long>(expected)) +
                                          " triangles, more than --max-steiner " + std::to_string(opt.max_steiner) +
                                          " allows; coarsen the spacing or raise --max-steiner");

  // Functional Delaunay Refinement.
  const auto t = Clock::now();
  refine::RefineOptions ro;
  ro.bound = opt.bound;
  ro.min_angle_deg = opt.min_angle_deg;
  ro.angle_split_min_f = opt.angle_split_min_f;
  ro.frontal = opt.frontal_radius > 0;
  if (ro.frontal) ro.frontal_radius = opt.frontal_radius;
  ro.max_steiner = opt.max_steiner;
  ro.region_max_area = opt.region_max_area;
  ro.expected_steiner = expected / 2;
  const ProgressFn& progress = opt.progress;
  ro.progress = [&progress](double frac, std::string_view) { return !progress || progress(0.05 + 0.75 * frac, "refine"); };
  refine::Refiner refiner(tri, f, ro);  // freed on return, before the caller copies the mesh out
  refiner.reserve(expected);
  refiner.init();
  refiner.run();
  out.refine_s = since(t);
  done("refine");
  if (opt.smooth_passes > 0) {
    refine::SmoothOptions so;
    so.passes = opt.smooth_passes;
    so.bound = opt.bound;
    so.min_angle_deg = opt.min_angle_deg;
    const refine::SmoothStats ss = refine::smooth(tri, f, so);
    info(opt.log, "smoothing: " + std::to_string(ss.moves) + " moves (" + std::to_string(ss.segment_moves) +
                      " along segments) of " + std::to_string(ss.candidates) + " Steiner vertices in " +
                      std::to_string(ss.passes) + " passes (" + std::to_string(ss.shifted) +
                      " tries across blocks, in the second blocking; " + std::to_string(ss.deferred) +
                      " across blocks of both, on one thread)");
    done("smooth");
  }

  std::optional<refine::RefineLeftovers> left;  // counted once
  if (opt.check) {
    mesh::CheckResult cr = mesh::check_all(tri);
    left = refiner.leftovers();
    const std::size_t bad = left->r_over_f_bad;
    if (bad) cr.add(std::to_string(bad) + " triangles have R/f(c) > B");
    if (!cr.ok()) {
      std::string msg = "--check failed: " + std::to_string(cr.count) + " violations";
      for (const auto& p : cr.problems) msg += "\n  " + p;
      throw Error(ExitCode::kCheckFailed, msg);
    }
    info(opt.log, "check: topology, orientation, constrained Delaunay, segments and R/f(c) <= B hold");
    done("check");
  }
  out.stats = refiner.stats();
  // leftovers() re-measures every triangle; without a min angle its angle count is 0 by definition.
  if (opt.min_angle_deg > 0) out.angle_exempt = left ? left->angle_bad : refiner.leftovers(false).angle_bad;
  return out;
}

Triangulator::Triangulator(const Pslg& in, const TriangulateOptions& opt) : opt_(opt) {
  if (!(opt_.bound > 0) || !std::isfinite(opt_.bound)) throw Error(ExitCode::kUsage, "--bound must be a positive number");
  if (opt_.min_angle_deg < 0 || opt_.min_angle_deg >= 60) throw Error(ExitCode::kUsage, "--min-angle must be in [0, 60)");
  if (opt_.smooth_passes < 0 || opt_.smooth_passes > 100) throw Error(ExitCode::kUsage, "--smooth must be in [0, 100]");
  if (!(opt_.frontal_radius >= 0 && opt_.frontal_radius < 1)) throw Error(ExitCode::kUsage, "--frontal must be in [0, 1)");
  predicates::reset_counters();
  std::vector<pslg::Repair> reps;
  pslg_ = prepare_pslg(in, opt_.source, opt_.strict, &reps);
  for (const auto& r : reps) {
    const Point2 w = pslg_.origin + r.where;
    repairs_.push_back({r.kind, w.x, w.y, r.ids, r.reason});
  }
  if (opt_.region_max_area.empty())
    for (const auto& r : pslg_.regions) opt_.region_max_area.push_back(r.max_area);
  if (opt_.progress && !opt_.progress(0.05, "cdt")) throw Error(ExitCode::kCancelled, "cancelled during cdt");
  double s = 0;
  tri_ = fdr::build_cdt(pslg_, opt_.source, &s, poly_regions(pslg_, opt_.convex_hull), true);
  cdt_s_ = s;
}

Triangulator& Triangulator::refine(const SizingField& f) {
  // Non-owning: the caller keeps `f` alive while this Triangulator uses it.
  return refine(SizingPtr(SizingPtr(), &f));
}

Triangulator& Triangulator::refine(SizingPtr world_f) {
  f_ = std::make_shared<sizing::ShiftedField>(std::move(world_f), pslg_.origin);
  const RefineOutcome r = refine_stage(tri_, *f_, pslg_.bbox(), opt_);
  alpha_ = r.alpha;
  refine_s_ = refine_s_.value_or(0) + r.refine_s;
  seg_splits_ += r.stats.segment_splits;
  circumcenters_ += r.stats.circumcenters;
  angle_exempt_ = r.angle_exempt;
  conforming_D_ = r.stats.conforming_D;  // of this refinement's f
  conforming_D_at_ = r.stats.conforming_D_at;
  return *this;
}

MeshView Triangulator::view() const { return tri_.to_view(); }

quality::RunInfo run_info(const SizingField* f, const TriangulateOptions& opt, const RunFigures& fig) {
  quality::RunInfo ri;
  ri.cdt_s = fig.cdt_s;
  ri.refine_s = fig.refine_s;
  ri.predicate_filtered = predicates::counters().filtered;
  ri.predicate_exact = predicates::counters().exact;
  ri.exempt_small_angle_triangles = fig.angle_exempt;
  if (std::isfinite(fig.conforming_D)) {
    ri.conforming_D = fig.conforming_D;
    ri.conforming_D_at = fig.conforming_D_at;
  }
  ri.steiner_segment = fig.segment_splits;
  ri.steiner_interior = fig.circumcenters;
  ri.input_file = opt.source;
  ri.spacing = f ? f->describe() : "none";
  if (opt.min_angle_deg > 0) ri.min_angle_option_deg = opt.min_angle_deg;
  return ri;
}

QualityReport measure_mesh(MeshView& m, const SizingField* f, const TriangulateOptions& opt, const RunFigures& fig,
                           quality::TriangleValues* per_triangle, bool keep_adjacency) {
  const bool f_filled = f && m.f.empty();  // then m.f gets f at the vertices (by the report, which uses them)
  QualityReport r = quality::compute_quality(m, f, opt.bound, fig.alpha, run_info(f, opt, fig), per_triangle, nullptr,
                                             f_filled ? &m.f : nullptr);
  // The report was the adjacency's last reader, but for the boundary lists: with it they take one
  // array read per half-edge, without it temporary arrays several times its size (and more time).
  if (!keep_adjacency) release_huge(m.neighbours);
  return r;
}

Mesh Triangulator::mesh() const {
  if (opt_.progress && !opt_.progress(0.8, "report")) throw Error(ExitCode::kCancelled, "cancelled during report");
  Mesh out;
  out.view = tri_.to_view();
  out.f = f_;
  out.bound = opt_.bound;
  out.min_angle_deg = opt_.min_angle_deg;
  out.alpha = alpha_;
  out.source = opt_.source;
  RunFigures fig;
  fig.cdt_s = cdt_s_;
  fig.refine_s = refine_s_;
  fig.segment_splits = seg_splits_;
  fig.circumcenters = circumcenters_;
  fig.angle_exempt = angle_exempt_;
  fig.alpha = alpha_;
  fig.conforming_D = conforming_D_;
  fig.conforming_D_at = conforming_D_at_;
  out.report = measure_mesh(out.view, f_.get(), opt_, fig);
  out.report.repairs = repairs_;
  out.report.run.peak_rss_mb = quality::peak_rss_mb_value();
  return out;
}

Mesh triangulate(const Pslg& pslg, SizingPtr f, const TriangulateOptions& options) {
  Triangulator t(pslg, options);
  t.refine(std::move(f));
  return t.mesh();
}

Mesh triangulate(const Pslg& pslg, const SizingField& f, const TriangulateOptions& options) {
  Triangulator t(pslg, options);
  t.refine(f);
  Mesh m = t.mesh();
  m.f.reset();  // `f` belongs to the caller: keep no dangling reference in the result
  return m;
}

std::string report_json(const QualityReport& report) {
  std::ostringstream js;
  quality::write_json(report, js);
  return js.str();
}

}  // namespace fdr
