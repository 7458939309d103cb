// Planar straight-line graph: the input of the triangulator (Triangle .poly semantics).
#pragma once
#include <cstdint>
#include <string>
#include <vector>
#include "base/types.hpp"

namespace fdr::pslg {

// Segment marker of an interior constraint (same value as mesh::EdgeKind::kBreakline); every
// other marker is a domain boundary, whose copies cancel by parity in clean().
inline constexpr std::int32_t kBreaklineMarker = 4;

struct Segment {
  Index a = 0, b = 0;         // indices into Pslg::points
  std::int32_t marker = 0;    // boundary marker (mesh::EdgeKind for GIS inputs)
  std::int32_t part = -1;     // id of the chain/ring it came from (for nodestrings), -1 unknown
  bool is_boundary() const { return marker != kBreaklineMarker; }
};

// A regional attribute / area constraint seed (Triangle .poly "regions" section).
struct Region {
  Point2 seed;
  double attribute = 0;
  double max_area = -1;  // negative: none
};

struct Pslg {
  Point2 origin{0, 0};                 // world = origin + local point
  std::vector<Point2> points;          // local coordinates
  std::vector<std::int32_t> point_markers;  // empty or points.size()
  std::vector<Segment> segments;
  std::vector<Point2> holes;           // hole seeds (local coordinates)
  std::vector<Region> regions;

  Box2 bbox() const {
    Box2 b;
    for (const auto& p : points) b.add(p);
    return b;
  }
};

}  // namespace fdr::pslg
