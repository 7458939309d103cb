// A global mesh measured on the sphere: great-circle edge lengths, spherical areas, R/f with R the
// circumradius on the sphere, the gravity-wave time step and whether the mesh closes on the sphere.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>
#include "base/types.hpp"
#include "gis/global_spacing.hpp"

namespace fdr::gis {

struct SphereMeshInput {
  const std::vector<Point2>* vertices = nullptr;                   // stereographic world coordinates
  const std::vector<std::array<Index, 3>>* triangles = nullptr;    // counter-clockwise in the plane
  // Constrained edges (vertex pairs) that are coast: land or island boundary segments.
  const std::vector<std::pair<Index, Index>>* coast_edges = nullptr;
  const std::vector<double>* z = nullptr;                          // elevation per vertex (optional)
  const SphereStereo* proj = nullptr;
  const LonLatGrid* f_ground = nullptr;                            // spacing in ground metres (optional)
  double bound = 1;                                                // B
  double hmin = 0;                                                 // metres (0: unknown)
  double min_depth_m = 1;                                          // depth clamp for the time step
};

struct SphereMeasure {
  std::size_t triangles = 0, edges = 0;
  double shortest_edge_m = 0, longest_edge_m = 0, mean_edge_m = 0;
  std::size_t edges_below_tenth_hmin = 0;
  double area_m2 = 0;                    // sum of the spherical triangles' areas
  std::size_t negative_triangles = 0;    // clockwise on the sphere (none in a valid mesh)
  double max_r_over_f = 0;               // spherical circumradius / f_ground(circumcentre)
  LonLat max_r_over_f_at{};
  std::size_t r_over_f_above_bound = 0;
  double min_angle_deg = 180;            // of the chord triangles
  std::size_t below_30_deg = 0;
  double mean_quality = 0;               // 4 sqrt(3) area / sum of squared edges, chord triangles
  double dt_s = 0;                       // min over triangles of shortest altitude / sqrt(g depth)
  LonLat dt_at{};
  std::size_t boundary_edges = 0;        // edges of one triangle
  std::size_t boundary_edges_not_coast = 0;  // of those, not a coast edge: a hole in the sphere mesh
  std::size_t edges_over_two = 0;        // edges of more than two triangles
  bool closed() const { return boundary_edges_not_coast == 0 && edges_over_two == 0; }
};

SphereMeasure measure_on_sphere(const SphereMeshInput& in);

// The figures as (name, value) rows for the report ("sphere_..." names).
std::vector<std::pair<std::string, double>> sphere_figures(const SphereMeasure& s);

}  // namespace fdr::gis
