// The plan of one pipeline::run: what the run will do, decided from the options alone, and the
// parameters of each stage. Every usage error (exit 2) is raised here, before any file is read.
#pragma once
#include <string>
#include "api/core_stages.hpp"
#include "pipeline/measure.hpp"
#include "pipeline/options.hpp"
#include "pipeline/write.hpp"

namespace fdr::pipeline {

struct Plan {
  bool gis = false;                // OGR/GDAL inputs (else .poly/.node)
  std::string source;              // input named in messages, titles and metadata
  TriangulateOptions triangulate;  // bound, automatic min angle and smoothing, cap, check
  bool measure_report = true;      // something reads the quality report (else unmeasured_report)
  bool triangle_values = false;    // the report measures the per-triangle values an output stores
  MeasureParams measure;
  WriteParams write;
};
Plan plan_run(const Options& opt);

// Error(kUsage) when a layer option (--open-boundary-layer, --breaklines-layer, --points-layer)
// is given without its input. plan_run checks it; the GIS read does too, for callers that start
// there.
void check_layer_options(const Options& opt);

// The CRS the outputs are written in: --output-crs, else EPSG:4326 for --global runs (lon/lat on
// the mesh's sphere), else "" (the working CRS).
std::string output_crs_of(const Options& opt);

// Whether anything reads the quality report: always, unless Options::report_only_if_read, and then
// when it is printed (not quiet), written (--report) or stored by an output (GPKG, VTU, UGRID,
// D-Flow FM net file).
bool report_is_read(const Options& opt, const std::vector<io::Format>& formats);

}  // namespace fdr::pipeline
