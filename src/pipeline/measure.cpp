// Measure stage (measure.hpp).
#include "pipeline/measure.hpp"
#include <optional>
#include <utility>
#include "base/memory.hpp"
#include "base/step_laps.hpp"
#include "pipeline/gis_backend.hpp"

namespace fdr::pipeline {
namespace {

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

quality::QualityReport unmeasured_report(mesh::MeshView& m, const PreparedInput& in, const MeasureParams& p,
                                         const TriangulateFigures& fig) {
  quality::QualityReport r;
  r.vertices = m.num_vertices();
  r.triangles = m.num_triangles();
  r.bound_B = p.triangulate.bound;
  r.alpha = fig.refine.alpha;
  const sizing::SizingField* f = in.f.get();
  r.run = run_info(f, p.triangulate, run_figures(fig));
  r.spacing = r.run.spacing;
  add_repairs(r, in);
  // .node files carry f at the vertices, which the report fills (the same evaluations).
  if (f && p.vertex_f && m.f.empty()) {
    resize_huge(m.f, m.num_vertices());
    for (std::size_t v = 0; v < m.f.size(); ++v) m.f[v] = (*f)(m.vertices[v]);
  }
  if (!p.keep_adjacency) release_huge(m.neighbours);
  return r;
}

quality::QualityReport measure(mesh::MeshView& m, const PreparedInput& in, const MeasureParams& p,
                               const TriangulateFigures& fig, quality::TriangleValues* tri_values, const LogFn& log) {
  std::optional<std::pair<double, double>> tin;  // terrain runs: the TIN against the DEM
  if (in.dem && p.tin_error) tin = gis_backend().tin_error(m, *in.dem, log);
  const RunFigures rf = run_figures(fig);
  // Per-triangle R/f(c), angle and area for the writers that store them, measured once here (the
  // writers then never evaluate f, which lets them run concurrently).
  // Model readiness against the input coast first: it reads the mesher's adjacency, which
  // measure_mesh releases unless an output's boundary lists read it.
  StepLaps lap(debug::Aid::kReport, "report");  // developer aid (base/step_laps.hpp)
  std::optional<quality::ModelReadiness> ready;
  if (p.gis) ready = quality::compute_model_readiness(m, {in.hmin, p.min_depth_m, &in.input_boundary, &in.coast_figures});
  lap("model readiness");
  quality::QualityReport report = measure_mesh(m, in.f.get(), p.triangulate, rf, tri_values, p.keep_adjacency);
  lap("quality");
  report.model_ready = std::move(ready);
  add_repairs(report, in);
  if (tin) {
    report.vertical_error_max_m = tin->first;
    report.vertical_error_rms_m = tin->second;
  }
  return report;
}

}  // namespace fdr::pipeline
