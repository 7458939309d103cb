// The cell centre of a triangle as D-Flow FM places it (see orthogonality.hpp): shared by the
// orthogonality measure and the report's single pass.
#pragma once
#include <algorithm>
#include "base/types.hpp"

namespace fdr::quality {

// The circumcentre cc of triangle abc (counter-clockwise), or the nearest point of the triangle's
// boundary when cc lies outside (a measurement: plain doubles, no exact predicate needed).
Point2 cell_centre_outside(Point2 a, Point2 b, Point2 c, Point2 cc);

__attribute__((always_inline)) inline Point2 cell_centre(Point2 a, Point2 b, Point2 c, Point2 cc) {
  auto side = [](Point2 p, Point2 q, Point2 r) { return (q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x); };
  if (side(a, b, cc) >= 0 && side(b, c, cc) >= 0 && side(c, a, cc) >= 0) return cc;
  return cell_centre_outside(a, b, c, cc);
}

// The nearest point of the triangle's boundary to cc.
inline Point2 cell_centre_outside(Point2 a, Point2 b, Point2 c, Point2 cc) {
  auto nearest = [](Point2 p, Point2 u, Point2 v) {
    const Point2 d = v - u;
    const double l2 = norm2(d);
    const double t = l2 > 0 ? std::clamp(dot(p - u, d) / l2, 0.0, 1.0) : 0.0;
    return u + t * d;
  };
  Point2 best = nearest(cc, a, b);
  for (const Point2 q : {nearest(cc, b, c), nearest(cc, c, a)})
    if (norm2(q - cc) < norm2(best - cc)) best = q;
  return best;
}

}  // namespace fdr::quality
