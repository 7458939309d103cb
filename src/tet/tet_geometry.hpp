// Measurements of one tetrahedron in double precision: constructions for refinement and quality
// reports, never a combinatorial decision (those go through predicates/predicates3d.hpp).
#pragma once
#include "base/point3.hpp"

namespace fdr::tet {

struct Sphere {
  Point3 centre;
  double radius = 0;
};

// The sphere through a, b, c, d (non-coplanar). Computed relative to a, which keeps the
// rounding error proportional to the tetrahedron's size rather than to its distance from the
// origin; a tetrahedron too flat for that has its centre constructed exactly and rounded.
Sphere circumsphere(Point3 a, Point3 b, Point3 c, Point3 d);

// Length of the shortest of the six edges.
double shortest_edge(Point3 a, Point3 b, Point3 c, Point3 d);

// Circumradius over shortest edge (sqrt(6)/4 for the regular tetrahedron, the least possible).
double radius_edge_ratio(Point3 a, Point3 b, Point3 c, Point3 d);

}  // namespace fdr::tet
