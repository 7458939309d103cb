// Closed polygonal surfaces (.off, .stl, .ply) as a plc::Plc: each face a facet of one polygon.
#pragma once
#include <cstdint>
#include <string>
#include <vector>
#include "base/point3.hpp"
#include "base/types.hpp"
#include "plc/plc.hpp"

namespace fdr::tetio {

// A surface as a file lists it: points (possibly repeated, as in STL) and faces of >= 3 corners.
struct Surface {
  std::vector<Point3> points;
  std::vector<std::vector<VertexId>> faces;
  std::vector<std::int32_t> face_marker;  // empty or one per face
};

// Ids that merge exactly equal points (+0 and -0 equal): remap[i] is the id of point i among the
// distinct points, numbered in order of first appearance; `distinct` gets those points.
std::vector<VertexId> merge_equal_points(const std::vector<Point3>& points, std::vector<Point3>& distinct);

// The PLC of a closed surface: equal points merged, one facet per face. A face that repeats a
// corner after merging, or an edge used by an odd number of faces (an open surface), is
// Error(kInvalidGeometry) naming the face (numbered from 0 in file order) and the coordinates.
plc::Plc surface_to_plc(Surface s, const std::string& path);

plc::Plc read_off(const std::string& path);
plc::Plc read_stl(const std::string& path);  // ASCII or binary (told apart by the file size)
plc::Plc read_ply(const std::string& path);  // ASCII, binary little or big endian

}  // namespace fdr::tetio
