// Frontal point placement (Rebay's frontal Delaunay refinement): where a bad triangle that borders
// an accepted triangle or a boundary segment (its front edge) is split, so that the triangle made
// on the front edge is close to equilateral at the target size.
#pragma once
#include "base/types.hpp"

namespace fdr::refine {

struct FrontalPoint {
  Point2 x;       // the point to insert
  Point2 centre;  // circumcentre of the triangle (p, q, x) (where its size is judged)
  bool clamped = false;  // moved back towards the front edge to stay inside the bad triangle's circumcircle
};

// The point on the perpendicular bisector of the front edge p-q, on its left (the bad triangle's
// side: (p, q, apex) counterclockwise), at which the triangle (p, q, x) has circumradius rho (at
// least half the edge: then it is a right triangle). Clamped so that it lies inside the bad
// triangle's circumcircle (centre cc, radius r) and never beyond cc along the bisector: a point
// inside that circle removes the bad triangle, and one beyond cc would be farther from the front
// than the circumcentre rule goes. The caller confirms the circle test with exact predicates.
FrontalPoint frontal_point(Point2 p, Point2 q, Point2 cc, double r, double rho);

}  // namespace fdr::refine
