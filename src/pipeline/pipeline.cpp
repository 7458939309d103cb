// Pipeline: read (gis / pslg) -> spacing (sizing) -> CDT + refinement (api core stages) ->
// depths (gis) -> measure (quality) -> write (io). The stages are in plan, measure, write and the
// modules; this file knows their order.
#include "pipeline/pipeline.hpp"
#include <chrono>
#include "api/core_stages.hpp"
#include "base/error.hpp"
#include "mesh/take_view.hpp"
#include "pipeline/gis_backend.hpp"
#include "pipeline/gis_stage.hpp"
#include "pipeline/memory_policy.hpp"
#include "pipeline/plan.hpp"
#include "predicates/predicates.hpp"

namespace fdr::pipeline {
namespace {

// Read stage: the PSLG and f of a GIS or a .poly input, its repairs in `result`.
PreparedInput read_input(const Options& opt, const Plan& plan, StageClock& clock, const ProgressFn& progress,
                         const LogFn& log, Result& result) {
  if (plan.gis) {
    // read (gis), spacing (sizing), clean and resample (pslg): the GIS side (gis_backend.hpp)
    PreparedInput in = gis_backend().prepare_gis(opt, clock, progress, log);
    result.crs_name = in.crs_name;
    return in;
  }
  PreparedInput in = prepare_poly_input(opt, log);  // read, resolve or refuse conflicts, --spacing
  result.repairs = in.repairs.size();
  result.repair_rows = in.repairs;
  clock.lap("read");
  return in;
}

// CDT, refinement, smoothing and checks; the mesh in its compact form (the triangulation freed).
mesh::MeshView triangulate(const Options& opt, const Plan& plan, PreparedInput& in, StageClock& clock,
                           const ProgressFn& progress, const LogFn& log, TriangulateFigures& fig) {
  // .poly: Triangle's semantics (exterior and hole seeds removed; --convex-hull); GIS: parity.
  mesh::Triangulation tri =
      fdr::build_cdt(in.pslg, plan.source, &fig.cdt_s,
                     plan.gis ? cdt::CdtOptions::Regions::kAuto : fdr::poly_regions(in.pslg, opt.convex_hull), !plan.gis);
  clock.lap("cdt");
  TriangulateOptions to = plan.triangulate;
  for (const auto& r : in.pslg.regions) to.region_max_area.push_back(r.max_area);
  to.progress = progress;
  to.log = log;
  to.stage_done = [&](const std::string& stage) {
    clock.lap(stage);
    // GIS runs: the filter's removed-water listing ran beside the CDT and the refinement (single
    // threads); it is waited for before the smoothing, which takes both cores and which it would
    // slow down. A wait shows as the stage "listing".
    if (stage == "refine" && in.complete) {
      complete_input(in);
      clock.lap("listing");
    }
  };
  fig.refine = fdr::refine_stage(tri, *in.f, in.pslg.bbox(), to);  // refine, smooth, check
  if (plan.gis) complete_input(in);  // done after the refinement (above) unless it stopped before
  return mesh::take_view(tri);       // the report and writers read a compact copy; frees tri
}

}  // namespace

Result run(const Options& opt, const ProgressFn& progress, const LogFn& log) {
  const auto t_start = std::chrono::steady_clock::now();
  auto report_progress = [&](double frac, const char* stage) {
    if (progress && !progress(frac, stage)) throw Error(ExitCode::kCancelled, std::string("cancelled during ") + stage);
  };
  const Plan plan = plan_run(opt);  // every usage error, before any I/O
  predicates::reset_counters();

  Result result;
  report_progress(0.0, "read");
  StageClock clock(&result.stages);  // per-stage timing hooks (Result::stages)
  PreparedInput in = read_input(opt, plan, clock, progress, log, result);
  result.f = in.f;
  report_progress(0.05, "cdt");
  const PhaseMemory memory(MemoryPhase::kMesh, plan.gis);
  clock.restart();

  TriangulateFigures fig;
  result.mesh = triangulate(opt, plan, in, clock, progress, log, fig);
  if (plan.gis) {
    result.repairs = in.repairs.size();
    result.repair_rows = in.repairs;
  }
  report_progress(0.8, "report");
  result.alpha = fig.refine.alpha;
  result.min_angle_deg = plan.triangulate.min_angle_deg;

  mesh::MeshView& m = result.mesh;
  if (plan.gis) {
    m.crs_wkt = in.crs_wkt;
    m.z = gis_backend().sample_depths(m, in, log);
  }
  clock.lap("depths");
  if (in.sphere_figures) {  // --global: the mesh measured on the sphere, in the report's figures
    in.sphere_figures(m, in.input_boundary, in.coast_figures);
    clock.lap("sphere");
  }

  quality::TriangleValues tri_values;
  quality::TriangleValues* values = plan.triangle_values ? &tri_values : nullptr;
  if (plan.measure_report) {
    result.report = measure(m, in, plan.measure, fig, values, log);
    clock.lap("report");
  } else {
    result.report = unmeasured_report(m, in, plan.measure, fig);  // what the outputs read of the report
  }

  report_progress(0.9, "write");
  const WriteInput w{m, result.report, in, result.alpha, values};
  result.written = write_outputs(w, plan.write, t_start, progress).paths;  // reports "done"
  clock.lap("write");
  return result;
}

}  // namespace fdr::pipeline
