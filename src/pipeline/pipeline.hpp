// pipeline::run: the only place that knows the order of the stages (read, clean, size, CDT,
// refine, report, write).
#pragma once
#include <string>
#include <vector>
#include "base/progress.hpp"
#include "io/writer.hpp"
#include "mesh/mesh_view.hpp"
#include "pipeline/options.hpp"
#include "pipeline/stage_time.hpp"
#include "quality/report.hpp"

namespace fdr::pipeline {

struct Result {
  mesh::MeshView mesh;
  quality::QualityReport report;
  std::vector<std::string> written;   // output paths
  std::string crs_name;               // working CRS ("" for .poly input)
  std::size_t repairs = 0;
  std::vector<StageTime> stages;      // wall time and peak memory per stage, in order
  std::vector<io::RepairRow> repair_rows;  // the repairs themselves (world coordinates)
  sizing::SizingPtr f;                // the spacing in the mesh's local frame
  double alpha = -1;                  // Lipschitz constant of f the guarantees were computed for
  double min_angle_deg = 0;           // the angle bound used (--min-angle, or its automatic value)
};

// Runs one meshing job. Throws fdr::Error (exit codes in base/error.hpp) on failure; outputs are
// written to temporary files and renamed, so a failed run leaves no partial output.
Result run(const Options& options, const ProgressFn& progress, const LogFn& log);

// True if `path` is read as a Triangle .poly/.node file (by extension).
bool is_poly_input(const std::string& path);

}  // namespace fdr::pipeline
