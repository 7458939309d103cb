// The stages of pipeline::run that belong to no single module: the run's plan (options checked
// before any I/O), the measure stage (quality) and the write stage (io). The others are module
// functions: read (gis: prepare_gis_input / pslg: prepare_poly_input), spacing
// (sizing::spacing_from_rules), CDT + refinement + smoothing (fdr::build_cdt, fdr::refine_stage,
// shared with the core API), depths (gis: sample_depths).
#pragma once
#include <array>
#include <chrono>
#include <string>
#include <vector>
#include "api/stages.hpp"
#include "base/progress.hpp"
#include "io/writer.hpp"
#include "pipeline/gis_stage.hpp"
#include "pipeline/options.hpp"
#include "pipeline/pipeline.hpp"
#include "quality/report.hpp"

namespace fdr::pipeline {

// What a run will do, decided from the options alone. Every usage error (exit 2) is raised here,
// before any file is read.
struct Plan {
  bool gis = false;                       // OGR/GDAL inputs (else .poly/.node)
  std::string source;                     // input named in messages, titles and metadata
  TriangulateOptions triangulate;         // bound, automatic min angle and smoothing, cap, check
  std::vector<io::Format> formats;        // one per Options::outputs
  std::array<int, 3> telemac_codes{5, 4, 4};
};
Plan plan_run(const Options& opt);

// Timings and counters of the triangulation stages, for the report.
struct TriangulateFigures {
  double cdt_s = 0;
  RefineOutcome refine;
};

// Measure stage: f at the vertices (when the mesh does not carry it), the quality report, model
// readiness against the input coast and the TIN error (GIS runs). `tri_values`, when not null,
// gets the per-triangle values the writers store.
quality::QualityReport measure(mesh::MeshView& m, const PreparedInput& in, const Options& opt, const Plan& plan,
                               const TriangulateFigures& fig, quality::TriangleValues* tri_values, const LogFn& log);

// Whether anything reads the quality report: always, unless Options::report_only_if_read, and then
// when it is printed (not quiet), written (--report) or stored by an output (GPKG, VTU, UGRID,
// D-Flow FM net file).
bool report_is_read(const Options& opt, const Plan& plan);

// Instead of measure() when nothing reads the report: the counts and the run's figures only, and
// what the outputs would have read of the measurement (f at the vertices for .node files; the
// adjacency released unless an output's boundary lists read it). The files are the same.
quality::QualityReport unmeasured_report(mesh::MeshView& m, const PreparedInput& in, const Options& opt,
                                         const Plan& plan, const TriangulateFigures& fig);

// Write stage: every output of the run (meshes, --write-spacing GeoTIFF, JSON report), all or
// nothing (files already written are removed when a later one fails). Sets the report's write
// and total times; returns the paths written.
std::vector<std::string> write_outputs(Result& result, const PreparedInput& in, const Options& opt, const Plan& plan,
                                       const quality::TriangleValues* tri_values,
                                       std::chrono::steady_clock::time_point t_start, const ProgressFn& progress);

// True if one of the formats stores per-triangle R/f(c), angle and area (GPKG, VTU, UGRID).
bool stores_triangle_values(const std::vector<io::Format>& formats);

}  // namespace fdr::pipeline
