// Measure stage of pipeline::run: the quality report of the finished mesh (quality), or, when
// nothing reads it, only what the outputs need of it.
#pragma once
#include "api/core_stages.hpp"
#include "base/progress.hpp"
#include "mesh/mesh_view.hpp"
#include "pipeline/gis_stage.hpp"
#include "quality/report.hpp"

namespace fdr::pipeline {

// What the measure stage needs of the run's options (made by plan_run).
struct MeasureParams {
  bool gis = false;                // model readiness against the input coast
  bool tin_error = false;          // terrain runs: the TIN's vertical error against the DEM
  double min_depth_m = 1.0;        // depth clamp of the report's gravity-wave time step
  TriangulateOptions triangulate;  // bound and angle the report states
  bool keep_adjacency = false;     // an output's boundary lists read the mesh's adjacency
  bool vertex_f = false;           // an output (.node) carries f at the vertices
};

// Timings and counters of the triangulation stages, for the report.
struct TriangulateFigures {
  double cdt_s = 0;
  RefineOutcome refine;
};

// f at the vertices (when the mesh does not carry it), the quality report, model readiness
// against the input coast and the TIN error (GIS runs). `tri_values`, when not null, gets the
// per-triangle values the writers store.
quality::QualityReport measure(mesh::MeshView& m, const PreparedInput& in, const MeasureParams& p,
                               const TriangulateFigures& fig, quality::TriangleValues* tri_values, const LogFn& log);

// Instead of measure() when nothing reads the report: the counts and the run's figures only, and
// what the outputs would have read of the measurement (f at the vertices for .node files; the
// adjacency released unless an output's boundary lists read it). The files are the same.
quality::QualityReport unmeasured_report(mesh::MeshView& m, const PreparedInput& in, const MeasureParams& p,
                                         const TriangulateFigures& fig);

}  // namespace fdr::pipeline
