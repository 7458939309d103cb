// Fan insertions of the smoothing: a free vertex added where a fixed vertex's fan (its triangles,
// counter-clockwise round it) holds a triangle too few for its angle. Why: once the moves have
// converged, most of the quality left next to a coast is in such fans (the angle over the number
// of triangles far from 60 degrees), and moving a free vertex rarely adds an edge to the fan;
// a new vertex on the bisector of its widest angle does. The vertex goes in by Bowyer-Watson
// (the mesh stays constrained Delaunay) and only if, decided before anything changes, the new
// triangles' summed quality deficit (1 - q) is below the old ones', each keeps R/f(c) <= B, its
// min angle (not below the old cavity's or the --min-angle target), no subsegment is encroached
// and no new edge, nor the distance to a constrained edge of the cavity, is under f/2.
#pragma once
#include <cstddef>
#include "mesh/triangulation.hpp"
#include "sizing/sizing_field.hpp"

namespace fdr::refine {

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
};
Fan fan_of(const mesh::Triangulation& tri, Index y);

// One serial pass over the fixed (input and segment) vertices in index order; returns the
// number of vertices added.
std::size_t insert_fan_vertices(mesh::Triangulation& tri, const sizing::SizingField& f, const FanOptions& o);

}  // namespace fdr::refine
