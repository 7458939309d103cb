// Write stage of pipeline::run: every output of the run (meshes, spacing GeoTIFF, JSON report),
// all or nothing.
#pragma once
#include <array>
#include <chrono>
#include <string>
#include <vector>
#include "base/progress.hpp"
#include "io/writer.hpp"
#include "mesh/mesh_view.hpp"
#include "pipeline/gis_stage.hpp"
#include "quality/report.hpp"

namespace fdr::pipeline {

// What the write stage needs of the run's options (made by plan_run).
struct WriteParams {
  bool gis = false;
  std::vector<std::string> outputs;       // mesh files
  std::vector<io::Format> formats;        // one per output
  std::string output_crs;                 // GIS runs: the meshes reprojected to this CRS
  std::string write_spacing;              // GIS runs: the final spacing as GeoTIFF
  std::string report_json;                // the quality report as JSON
  std::string source;                     // the input, for titles and metadata
  std::string command_line;               // for the metadata
  double bound = 1.0;
  double min_angle_deg = 0;               // the angle bound used
  bool slf_double = false;
  std::array<int, 3> telemac_codes{5, 4, 4};
  io::PostgisOptions postgis;             // -o PG:...: table prefix, schema, --overwrite
};

// The finished run that the write stage writes.
struct WriteInput {
  const mesh::MeshView& mesh;
  quality::QualityReport& report;                  // its write and total times are set here
  const PreparedInput& in;
  double alpha = -1;                               // Lipschitz constant of f, for the metadata
  const quality::TriangleValues* triangle_values;  // the report's per-triangle values, or null
};

// The files written, in order (meshes, then the JSON report).
struct WrittenOutputs {
  std::vector<std::string> paths;
};

// Writes every output; a failure or a cancellation removes the files written before. Sets the
// report's write and total times (from `t_start`) and reports "done" to `progress`.
WrittenOutputs write_outputs(const WriteInput& w, const WriteParams& p, std::chrono::steady_clock::time_point t_start,
                             const ProgressFn& progress);

// True if one of the formats stores per-triangle R/f(c), angle and area (GPKG, VTU, UGRID).
bool stores_triangle_values(const std::vector<io::Format>& formats);

// True if one of the formats is written on the sphere for a --global run (VTU, msh: Earth-centred
// x, y, z).
bool writes_on_sphere(const std::vector<io::Format>& formats);

// True if one of the formats stores the run's metadata, the JSON report among it (GPKG, UGRID,
// D-Flow FM net file).
bool stores_metadata(const std::vector<io::Format>& formats);

}  // namespace fdr::pipeline
