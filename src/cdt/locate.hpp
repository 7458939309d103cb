// Point location in a Triangulation: visibility walk and straight-line walk.
#pragma once
#include "mesh/triangulation.hpp"

namespace fdr::cdt {

enum class LocateKind {
  kInTriangle,  // he = 3t of the containing triangle (strictly inside)
  kOnEdge,      // he = a half-edge whose relative interior contains p
  kOnVertex,    // he = a half-edge leaving the vertex equal to p
  kBlocked,     // straight walk stopped at a constrained or boundary half-edge `he` (seen from inside)
};

struct Location {
  LocateKind kind = LocateKind::kInTriangle;
  HalfEdge he = kNoId;
};

// Visibility walk from triangle `start` (ignores constraints; needs a closed mesh, i.e. before
// holes are removed). Deterministic: the edge order comes from a fixed-seed generator.
// `steps` (optional) gets the number of triangles stepped through added.
Location locate_visibility(const mesh::Triangulation& tri, TriangleId start, Point2 p, std::size_t* steps = nullptr);

// Walk along the line from a point inside `start` (its centroid) towards p; stops at the first
// constrained or boundary edge that separates p from `start` (kind kBlocked). `max_steps`
// bounds the walk (returns kBlocked with he = kNoId when exceeded).
Location locate_straight(const mesh::Triangulation& tri, TriangleId start, Point2 p,
                         std::size_t max_steps = 1u << 26);

}  // namespace fdr::cdt
