// Model readiness of a final mesh: what a coastal modeler checks before running it —
// shortest edge against hmin, skinny triangles, mean element quality, coast deviation both ways
// between the input boundary and the mesh boundary, connected pieces, the gravity-wave (CFL)
// time step, and the features the GIS stage removed.
#pragma once
#include <cstddef>
#include <iosfwd>
#include <optional>
#include <string>
#include <utility>
#include <vector>
#include <nlohmann/json_fwd.hpp>
#include "base/types.hpp"
#include "mesh/mesh_view.hpp"

namespace fdr::quality {

// What the report knows beyond the mesh. Everything is optional: without an input boundary the
// coast deviation is not measured, without hmin the ratios to hmin are not given.
struct ModelReadyInputs {
  double hmin = 0;         // metres (0: unknown)
  double min_depth_m = 1;  // depth clamp for the time step (--min-depth)
  // Input domain boundary segments (before any change), in the mesh's local frame: the boundary
  // of the domain the mesher meshes, adjacent or overlapping input polygons united.
  const std::vector<std::pair<Point2, Point2>>* input_boundary = nullptr;
  // GIS-stage figures (name, value): input_pieces, water_removed_m2, islands_removed, ...;
  // input_polygons and input_polygons_united say how the input boundary was united.
  const std::vector<std::pair<std::string, double>>* coast_figures = nullptr;
};

// Distance of one boundary to the other, sampled at every vertex and every hmin/2 along edges.
struct CoastDeviation {
  double max_m = 0;
  double p99_m = 0;        // nearest rank over the samples
  std::size_t samples = 0;
  Point2 max_at{};         // world coordinates of the sample with the largest distance
};

// Smallest gravity-wave time step over the triangles: h / sqrt(g * depth), h = the triangle's
// shortest altitude (2 * area / longest edge), depth = max(-(mean z of its corners), min_depth).
struct TimeStep {
  double dt_s = 0;
  double h_m = 0;
  double depth_m = 0;
  Point2 at{};             // world coordinates of the triangle's centroid
  std::size_t triangle = 0;
};

struct ModelReadiness {
  std::optional<double> hmin_m;
  double min_depth_m = 1;

  // Edges (every distinct triangle edge once).
  std::size_t edges = 0;
  std::optional<double> shortest_edge_m;
  Point2 shortest_edge_at{};  // world coordinates of its midpoint
  std::size_t edges_below_half_hmin = 0, edges_below_tenth_hmin = 0;  // counted only with hmin

  // Triangles.
  std::size_t triangles = 0;
  std::size_t triangles_below_20_deg = 0, triangles_below_30_deg = 0;  // by minimum angle
  std::optional<double> mean_quality;  // mean of 4*sqrt(3)*area / sum(edge^2), 1 = equilateral
  std::optional<double> min_quality;

  // Connected pieces (triangles joined through shared edges) and the input's (GIS stage).
  std::size_t mesh_pieces = 0;
  std::optional<double> input_pieces;

  // Coast deviation (only with an input boundary).
  std::optional<CoastDeviation> input_to_mesh, mesh_to_input;
  std::size_t mesh_boundary_edges = 0;  // triangle edges used by one triangle

  // Time step (only when the mesh has z and some vertex below sea level: an explicit ocean
  // model's limit, meaningless on a land-only mesh whose every depth would be the clamp).
  std::optional<TimeStep> time_step;
  bool land_only = false;  // z given, no vertex below sea level (z < 0)

  // Areas: the mesh's, the input's (GIS stage) and the relative change in percent.
  double mesh_area_m2 = 0;
  std::optional<double> input_area_m2;

  // Every GIS-stage figure as given (features closed/removed, resampling counts, ...).
  std::vector<std::pair<std::string, double>> coast_figures;

  std::optional<double> figure(const std::string& name) const;  // one of coast_figures
  std::optional<double> shortest_edge_over_hmin() const;
  std::optional<double> pct_edges_below_half_hmin() const;
  std::optional<double> pct_edges_below_tenth_hmin() const;
  double pct_triangles_below_20() const;
  double pct_triangles_below_30() const;
  std::optional<double> area_change_pct() const;
  bool time_step_depth_clamped() const;  // the limiting triangle's depth is the --min-depth clamp
};

// Measures `m` (local frame, triangles counter-clockwise; z positive up when present). Linear in
// the mesh size; the coast deviation uses a uniform grid over the boundary segments. With the
// mesher's adjacency (m.neighbours filled: call it before the report releases it) one pass over
// the triangles on up to two threads (FDR_THREADS); else compute_model_readiness_plain. The
// figures are the same bit for bit either way and for every FDR_THREADS.
ModelReadiness compute_model_readiness(const mesh::MeshView& m, const ModelReadyInputs& in);
// Without the adjacency (meshes read from files): the half-edges grouped by their smaller vertex.
ModelReadiness compute_model_readiness_plain(const mesh::MeshView& m, const ModelReadyInputs& in);

// Distance from each point to the nearest of `segments` (+inf when there is none); exposed for
// tests.
std::vector<double> distances_to_segments(const std::vector<Point2>& points,
                                          const std::vector<std::pair<Point2, Point2>>& segments);

// Report pieces: the JSON object written under "model_ready" and the text block.
nlohmann::ordered_json model_ready_json(const ModelReadiness& r);
void write_model_ready_text(const ModelReadiness& r, std::ostream& out);

}  // namespace fdr::quality
