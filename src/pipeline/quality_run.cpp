// `fdrmesh quality`: reads a mesh (2DM, fort.14, msh, node/ele, fdrmesh GPKG), evaluates f and
// measures the same report as `fdrmesh mesh --report`.
#include "pipeline/quality_run.hpp"
#include "api/core_stages.hpp"
#include "base/error.hpp"
#include "pipeline/gis_backend.hpp"
#include "quality/rss.hpp"
#include "sizing/field_checks.hpp"
#include "sizing/fields.hpp"
#include "sizing/grid_field.hpp"
#include "sizing/make_spacing.hpp"

namespace fdr::pipeline {

quality::QualityReport run_quality(const QualityOptions& a, std::ostream* text) {
  mesh::MeshView m = gis_backend().read_mesh(a.mesh);  // GIS side (GPKG, UGRID readers)
  if (!a.spacing.empty() && !a.raster.empty())
    throw Error(ExitCode::kUsage, "give either --spacing or --raster, not both");
  sizing::SizingPtr f;
  if (!a.spacing.empty()) {
    f = fdr::spacing_in_frame(a.spacing, m.origin);  // as the .poly path of `mesh`
  } else if (!a.raster.empty()) {
    sizing::Grid g = gis_backend().read_raster_native(a.raster, m.origin);
    f = std::make_shared<sizing::GridField>(std::move(g), "size raster " + a.raster);
  }
  double alpha = -1;
  if (f) {
    Box2 b;
    for (const auto& p : m.vertices) b.add(p);
    alpha = fdr::lipschitz_of(*f, b);
  }
  quality::RunInfo ri;
  ri.input_file = a.mesh;
  ri.spacing = f ? f->describe() : "none";
  quality::QualityReport r = quality::compute_quality(m, f.get(), a.bound, alpha, ri);
  r.model_ready = quality::compute_model_readiness(m, {});  // mesh-only: no hmin, no input coast
  r.run.peak_rss_mb = quality::peak_rss_mb_value();
  if (text) quality::write_text(r, *text);
  if (!a.report_json.empty()) quality::write_json_file(r, a.report_json);
  return r;
}

}  // namespace fdr::pipeline
