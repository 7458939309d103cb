// MeshView: the plain, compact result of meshing that quality reports and writers consume.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>
#include "base/edge_kind.hpp"
#include "base/types.hpp"

namespace fdr::mesh {

using fdr::EdgeKind;  // base/edge_kind.hpp (gis and pslg use it without the mesh)
const char* edge_kind_name(EdgeKind k);

struct MeshEdge {
  Index a = 0, b = 0;   // vertex ids
  std::int32_t marker = 0;  // input segment marker (EdgeKind for GIS inputs)
  std::int32_t part = 0;    // which input chain/ring it came from (nodestring id); -1 unknown
};

// Triangles are counter-clockwise; vertex coordinates are in the frame given by `origin`:
// world = origin + vertex. All per-vertex arrays are either empty or vertices.size() long.
struct MeshView {
  Point2 origin{0, 0};
  std::vector<Point2> vertices;
  std::vector<std::array<Index, 3>> triangles;
  std::vector<MeshEdge> edges;             // every constrained edge (subsegments of the input segments)
  std::vector<std::int32_t> vertex_marker; // input point marker or segment marker, 0 for Steiner points
  std::vector<double> z;                   // optional: elevation/depth per vertex (positive up)
  std::vector<double> f;                   // optional: spacing value per vertex
  std::string crs_wkt;                     // optional: CRS of world coordinates
  // Optional adjacency: per half-edge 3t+k (from triangles[t][k] to triangles[t][(k+1)%3]) the
  // half-edge 3u+j of the neighbouring triangle u that runs the other way, or kNoId on the
  // boundary. Filled by Triangulation::to_view / take_view (the triangulation's own twins);
  // empty when unknown (e.g. a mesh read from a file). Cleared by any code that edits triangles.
  std::vector<Index> neighbours;

  std::size_t num_vertices() const { return vertices.size(); }
  std::size_t num_triangles() const { return triangles.size(); }
  Point2 world(Index v) const { return origin + vertices[v]; }
};

}  // namespace fdr::mesh
