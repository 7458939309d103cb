// A tetrahedral mesh as the 3D mesher returns it and the 3D writers take it.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>
#include "base/point3.hpp"
#include "base/types.hpp"

namespace fdr::tet {

// Tetrahedra are stored with positive volume: dot(b - a, cross(c - a, d - a)) > 0 (VTK's and
// Gmsh's and TetGen's order).
struct TetMesh {
  std::vector<Point3> points;
  std::vector<std::array<VertexId, 4>> tets;
  std::vector<std::int32_t> tet_material;          // one per tetrahedron (region attribute; 0 none)
  std::vector<std::array<VertexId, 3>> faces;      // subfacets: the mesh faces that tile input facets
  std::vector<std::int32_t> face_marker;           // one per face: its facet's boundary marker
  std::vector<std::array<VertexId, 2>> edges;      // subsegments: mesh edges that tile input segments
  std::vector<std::int32_t> edge_marker;           // one per edge
  // Named per-tetrahedron values the writers carry along (e.g. "r_over_f", "radius_edge",
  // "min_dihedral_deg"), each with one value per tetrahedron.
  std::vector<std::pair<std::string, std::vector<double>>> cell_fields;
  std::vector<std::string> marker_names;           // optional: name of face/edge marker m at m
  std::vector<std::string> material_names;         // optional: name of material m at m
};

}  // namespace fdr::tet
