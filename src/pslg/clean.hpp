// PSLG cleaning for messy GIS input: snap, remove degenerate pieces, split crossings,
// drop tiny islands, simplify; every change recorded as a Repair.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>
#include "pslg/pslg.hpp"

namespace fdr::pslg {

struct Repair {
  std::string kind;          // e.g. "snap", "zero_length", "backtrack", "crossing_split",
                             // "duplicate_segment", "tiny_island", "sliver", "simplify"
  Point2 where;              // local coordinates of the change
  double size = 0;           // a length or area that quantifies it (metres / m^2)
  std::string reason;        // one human sentence
  std::int32_t part = -1;    // Segment::part (input ring/line id) it concerns, -1 if unknown
  // Ids concerned, in the order named by `reason`: vertex ids (snap: the dropped vertex and the
  // one kept) and/or Segment::part values of the segments involved (the .poly path sets part to
  // the input segment index, see resolve.hpp).
  std::vector<std::int64_t> ids{};
};

struct CleanOptions {
  double snap_distance = 0;       // vertices closer than this are merged (0: exact duplicates only)
  // Closed rings (chains of boundary segments) with area < min_island_area_factor * f(c)^2
  // are removed (c: ring centroid); 0 keeps all.
  double min_island_area_factor = 0;
  // Boundary vertices closer than simplify_factor * f to their neighbours are removed where the
  // boundary moves by less than simplify_tolerance (metres); 0 disables.
  double simplify_factor = 0;
  double simplify_tolerance = 0;
  std::function<double(Point2)> spacing;  // f in the local frame; required when a factor > 0
  std::size_t max_iterations = 64;        // cap on crossing-split rounds (error if exceeded)
  // true (GIS): coincident boundary segments cancel in pairs (the domain is defined by crossing
  // parity). false (Triangle .poly semantics): every copy of a segment merges into the first.
  bool boundary_parity = true;
  // > 0: a vertex within this distance of a segment's interior splits it there (the segment is
  // routed through the vertex: snap rounding's hot-pixel rule), so that no feature far below
  // floating-point resolution is left for the triangulator (reported as "snap_to_segment").
  double segment_snap = 0;
};

// Returns a PSLG with no duplicate points, no zero-length or duplicate segments and no two
// segments crossing or overlapping except at shared endpoints. Boundary segments (marker !=
// mesh::EdgeKind::kBreakline) that coincide an even number of times cancel (they bound the
// domain by parity); breaklines are merged. Appends every change to `repairs`.
Pslg clean(const Pslg& in, const CleanOptions& options, std::vector<Repair>* repairs);

// Sorted (vertex, segment) pairs where the vertex lies off the segment's line but within `tol`
// of its open interior and farther than `tol` from its endpoints (`present` masks vertices).
std::vector<std::pair<Index, Index>> vertices_near_segments(const std::vector<Point2>& points,
                                                            const std::vector<Segment>& segments,
                                                            const std::vector<char>* present, double tol);

}  // namespace fdr::pslg
