// The top surface GeoPackage of a terrain run: io's GeoPackage writer on the 2D terrain TIN, with
// rows that name the volume's surfaces, facet markers and layers.
#include "pipeline/terrain_gpkg.hpp"
#include <nlohmann/json.hpp>
#include "base/version.hpp"
#include "io/writer.hpp"
#include "pipeline/terrain_run.hpp"

namespace fdr::pipeline {

std::vector<std::pair<std::string, std::string>> terrain_metadata(const Result3& r, const std::vector<std::string>& surfaces) {
  std::vector<std::pair<std::string, std::string>> rows;
  std::string names;
  for (const std::string& s : surfaces) names += (names.empty() ? "" : ",") + s;
  rows.emplace_back("terrain_surfaces", names);
  for (std::size_t m = 1; m < r.mesh.marker_names.size(); ++m)
    if (!r.mesh.marker_names[m].empty()) rows.emplace_back("terrain_marker_" + std::to_string(m), r.mesh.marker_names[m]);
  for (const LayerFigures& l : r.layers) rows.emplace_back("terrain_layer_" + std::to_string(l.material), l.name);
  const nlohmann::ordered_json report = nlohmann::ordered_json::parse(report_json3(r));
  if (report.contains("layers")) rows.emplace_back("terrain_layers", report["layers"].dump());
  return rows;
}

void write_top_gpkg(const std::string& path, const Result& tin_run, const Result3& r,
                    const std::vector<std::string>& surfaces, const std::string& source) {
  io::WriteOptions wo;
  wo.f = tin_run.f.get();
  wo.title = source;
  wo.repairs = tin_run.repair_rows;
  wo.metadata = {{"software", std::string("fdrmesh ") + kVersion}, {"input", source}, {"crs", tin_run.crs_name}};
  for (auto& row : terrain_metadata(r, surfaces)) wo.metadata.push_back(std::move(row));
  io::write_mesh(tin_run.mesh, path, io::Format::kGpkg, wo);
}

}  // namespace fdr::pipeline
