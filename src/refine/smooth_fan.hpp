// Fan insertions of the smoothing: a free vertex added on the bisector of a fixed vertex's widest
// angle in its fan (its triangles, counter-clockwise round it) when that angle is wider than
// kFanWideDeg. Why: once the moves have converged, most of the quality left next to a coast is in
// fans whose angle over the number of triangles is far from 60 degrees, and moving a free vertex
// rarely adds an edge to the fan; a new vertex in its widest angle does. The vertex goes in by
// Bowyer-Watson (the mesh stays constrained Delaunay) and only if, decided before anything
// changes, the new triangles' summed quality deficit (1 - q) is below the old ones' (so the mean
// quality rises although the count grows), each keeps R/f(c) <= B, its min angle (not below the
// old cavity's or the --min-angle target), no subsegment is encroached and no new edge, nor the
// distance to a constrained edge of the cavity, is under f/2.
#pragma once
#include <cstddef>
#include "mesh/triangulation.hpp"
#include "sizing/sizing_field.hpp"

namespace fdr::refine {

// A fan angle wider than this is tried (75: a triangle there is wider than the 60 of an
// equilateral one by a quarter; narrower ones rarely pass the deficit test).
inline constexpr double kFanWideDeg = 75.0;

struct FanOptions {
  double bound = 1.0;          // B
  double min_angle_deg = 0.0;  // the --min-angle target
};

// The number of triangles round fixed vertex y and their angles' sum in degrees (0, 0 when y has
// no triangle or touches a super vertex).
struct Fan {
  int triangles = 0;
  double angle_deg = 0;
  HalfEdge widest = kNoId;  // the half-edge leaving y of its widest triangle
  double widest_deg = 0;    // and its angle at y
};
Fan fan_of(const mesh::Triangulation& tri, Index y);

// One serial pass over the fixed (input and segment) vertices in index order, each tried once, at
// the mean of its widest angle's two spokes along the bisector, else at 0.8 or 1.2 of it; returns
// the number of vertices added.
std::size_t insert_fan_vertices(mesh::Triangulation& tri, const sizing::SizingField& f, const FanOptions& o);

}  // namespace fdr::refine
