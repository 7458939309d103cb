// The GIS stage of the pipeline: OGR/GDAL inputs -> PSLG in a projected local frame + spacing f.
#pragma once
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>
#include "base/progress.hpp"
#include "io/writer.hpp"
#include "mesh/mesh_view.hpp"
#include "pipeline/options.hpp"
#include "pipeline/stage_time.hpp"
#include "pslg/pslg.hpp"
#include "sizing/sizing_field.hpp"

namespace fdr::pipeline {

struct PreparedInput {
  pslg::Pslg pslg;                        // local frame (pslg.origin = world offset)
  sizing::SizingPtr f;                    // spacing in the local frame (grid units, corrected for scale)
  std::string crs_name;                   // printed and stored
  std::vector<io::RepairRow> repairs;     // world coordinates
  std::vector<std::pair<std::string, std::string>> metadata;  // extra provenance
  // Called on the final mesh (local frame): sets z (depth/elevation) and crs_wkt.
  std::function<void(mesh::MeshView&)> attach;
  // --output-crs: reprojects a copy of the mesh for writing (same topology); empty if not asked.
  std::function<void(mesh::MeshView&)> to_output_crs;
  // Extra outputs written after the mesh (e.g. --write-spacing GeoTIFF).
  std::vector<std::function<void()>> extra_outputs;
  // Terrain runs: (max, RMS) vertical error of the TIN against the DEM, filled by attach().
  std::shared_ptr<std::optional<std::pair<double, double>>> tin_error =
      std::make_shared<std::optional<std::pair<double, double>>>();
  std::vector<StageTime> stages;          // read, sizing, limit, repair (times of this stage's parts)
  // Model-readiness inputs for the report (GIS runs).
  double hmin = 0;                        // metres
  std::vector<std::pair<Point2, Point2>> input_boundary;  // input domain rings, local frame
  std::vector<std::pair<std::string, double>> coast_figures;  // filter/resample counts for the report
};

// Reads OGR/GDAL inputs named in `opt` (any non-.poly input). Throws fdr::Error.
PreparedInput prepare_gis_input(const Options& opt, const ProgressFn& progress, const LogFn& log);

}  // namespace fdr::pipeline
