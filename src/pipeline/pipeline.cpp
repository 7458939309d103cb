// Pipeline: read (gis / pslg) -> spacing (sizing) -> CDT + refinement (api core stages) ->
// depths (gis) -> measure (quality) -> write (io). The stages are in stages.cpp and the modules.
#include "pipeline/pipeline.hpp"
#include <chrono>
#include <optional>
#include "api/stages.hpp"
#include "base/error.hpp"
#include "base/memory.hpp"
#include "mesh/take_view.hpp"
#include "pipeline/gis_backend.hpp"
#include "pipeline/gis_stage.hpp"
#include "pipeline/stages.hpp"
#include "predicates/predicates.hpp"

namespace fdr::pipeline {

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
  PreparedInput in;
  if (plan.gis) {
    // read (gis), spacing (sizing), clean and resample (pslg): the GIS side (gis_backend.hpp)
    in = gis_backend().prepare_gis(opt, clock, progress, log);
    const predicates::Counters gis_calls = gis_backend().take_predicate_counters();  // a module counts apart
    predicates::counters().filtered += gis_calls.filtered;
    predicates::counters().exact += gis_calls.exact;
    result.crs_name = in.crs_name;
  } else {
    in = prepare_poly_input(opt, log);  // read, resolve or refuse conflicts (pslg), spacing from --spacing
    result.repairs = in.repairs.size();
    result.repair_rows = in.repairs;
    clock.lap("read");
  }
  result.f = in.f;
  report_progress(0.05, "cdt");
  // The mesh stages of .poly runs give freed pages back at once (few large arrays; base/memory.hpp).
  // GIS runs keep them (each stage's end still gives them back: StageClock::lap): the filter's
  // removed-water listing runs beside the CDT and the refinement on another thread, and every
  // page given back (madvise) interrupts that thread too (a TLB shootdown, costly in a virtual
  // machine). Gulf of Maine at hmin 120: madvise calls in the CDT and the refinement 6 100 -> 300,
  // CDT 0.12-0.19 -> 0.09-0.15 s, system time 1.38 -> 0.96 s, the whole process 0.37 s faster at
  // the median of ten interleaved rounds (tools/bench/ab.py), peak unchanged. Kept pages also let
  // the report's and the writers' temporary arrays reuse the pages freed before them (report
  // 0.53-0.59 -> 0.42-0.44 s, write 1.26-1.68 -> 1.10-1.32 s when first kept from the compaction
  // on). README "Allocator". Not for .poly runs: no thread beside their refinement, and kept pages
  // would add to their peak where the compaction frees the triangulation (60 -> 69 MiB at 1 M
  // triangles; issue 7's 64 bytes/triangle).
  std::optional<EagerMemoryRelease> eager;
  std::optional<KeepFreedPages> keep;
  if (plan.gis) keep.emplace();
  else eager.emplace();
  clock.restart();

  TriangulateFigures fig;
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
    // threads); it is waited for before the smoothing, which takes both cores (beside it the
    // listing slowed it by half on a GSHHG-h basin). Its repairs and figures now
    // (pipeline/gis_stage.cpp); a wait shows as the stage "listing".
    if (stage == "refine" && in.complete) {
      complete_input(in);
      clock.lap("listing");
    }
  };
  fig.refine = fdr::refine_stage(tri, *in.f, in.pslg.bbox(), to);  // refine, smooth, check
  if (plan.gis) {
    complete_input(in);  // done after the refinement (above) unless it stopped before
    result.repairs = in.repairs.size();
    result.repair_rows = in.repairs;
  }
  report_progress(0.8, "report");
  result.alpha = fig.refine.alpha;
  result.min_angle_deg = to.min_angle_deg;

  result.mesh = mesh::take_view(tri);  // the report and writers read a compact copy; frees tri
  mesh::MeshView& m = result.mesh;
  if (plan.gis) {
    m.crs_wkt = in.crs_wkt;
    m.z = gis_backend().sample_depths(m, in, log);
  }
  clock.lap("depths");

  quality::TriangleValues tri_values;
  const bool want_tri_values = opt.output_crs.empty() && stores_triangle_values(plan.formats);
  if (report_is_read(opt, plan)) {
    result.report = measure(m, in, opt, plan, fig, want_tri_values ? &tri_values : nullptr, log);
    clock.lap("report");
  } else {
    result.report = unmeasured_report(m, in, opt, plan, fig);  // what the outputs read of the report
  }

  report_progress(0.9, "write");
  result.written = write_outputs(result, in, opt, plan, want_tri_values ? &tri_values : nullptr, t_start,
                                 progress);  // reports "done"
  clock.lap("write");
  return result;
}

}  // namespace fdr::pipeline
