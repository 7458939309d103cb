// The terrain-volume run of `fdrmesh mesh DOMAIN --dem ...` (GIS side): the 2D terrain TIN of the
// domain, the surfaces sampled on it, the terrain PLC, its depth-graded spacing, the tetrahedral
// mesh, the report with each layer's volume, the outputs in world coordinates.
#pragma once
#include <optional>
#include <string>
#include "base/progress.hpp"
#include "pipeline/options.hpp"
#include "pipeline/run3d.hpp"

namespace fdr::pipeline {

// Runs one terrain job (check_terrain_options first). Throws fdr::Error; all outputs or none.
Result3 run_terrain(const Options& opt, const ProgressFn& progress, const LogFn& log);

// The 3D report as JSON text (quality::write_json3), with `layers` when the run made any: what
// --report writes for a terrain run.
std::string report_json3(const Result3& r);

// The --base value as an elevation in metres when it is a number (a raster path otherwise).
std::optional<double> base_elevation(const std::string& base);

}  // namespace fdr::pipeline
