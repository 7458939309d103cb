// A piecewise linear complex in 3D: the input of the tetrahedral mesher (vertices, planar facets
// with holes, free segments, volume holes and regions), as TetGen's .poly/.smesh describe it.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>
#include "base/point3.hpp"
#include "base/types.hpp"

namespace fdr::plc {

// A planar facet. Each polygon is a closed chain of vertex ids (a 2-vertex polygon is a segment
// lying in the facet, a 1-vertex polygon an isolated vertex in it), as in TetGen's facets; holes
// are points in the facet's plane whose enclosing polygon's inside is not part of the facet.
struct Facet {
  std::vector<std::vector<VertexId>> polygons;
  std::vector<Point3> holes;
  std::int32_t marker = 0;  // boundary marker: the physical group of its faces in the outputs
};

// A region: the connected volume containing `point` gets material `attribute`; a positive
// `max_volume` caps its tetrahedra's volume (TetGen's regional volume constraint).
struct Region {
  Point3 point;
  double attribute = 0;
  double max_volume = -1;
};

struct Plc {
  std::vector<Point3> points;
  std::vector<std::int32_t> point_markers;         // empty or one per point
  std::vector<Facet> facets;
  std::vector<std::array<VertexId, 2>> segments;   // free segments (e.g. wells) in the volume
  std::vector<Point3> holes;                       // volume holes: the region holding one is not meshed
  std::vector<Region> regions;
  std::vector<std::string> marker_names;           // optional: name of boundary marker m at m (outputs' physical groups)
  std::vector<std::string> material_names;         // optional: name of material m at m
  std::string source;                              // file name for messages
};

}  // namespace fdr::plc
