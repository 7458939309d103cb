// 3D geometric predicates: the signs that decide every combinatorial step of the tetrahedral mesher.
// Same scheme as the 2D ones (predicates.hpp): a double-precision evaluation with a forward error
// bound, and CGAL's exact Epick predicate when the bound cannot certify the sign.
#pragma once
#include "base/point3.hpp"

namespace fdr::predicates {

// Exact fallbacks (out of line: they pull in CGAL).
int orient3d_exact(Point3 a, Point3 b, Point3 c, Point3 d);
int insphere_exact(Point3 a, Point3 b, Point3 c, Point3 d, Point3 e);

// Sign of dot(b - a, cross(c - a, d - a)): +1 when (a, b, c, d) has positive volume, -1 negative,
// 0 coplanar.
int orient3d(Point3 a, Point3 b, Point3 c, Point3 d);

// For positively oriented (a, b, c, d): +1 when e lies strictly inside their circumsphere, 0 on
// it, -1 outside (the sign flips for negatively oriented ones).
int insphere(Point3 a, Point3 b, Point3 c, Point3 d, Point3 e);

}  // namespace fdr::predicates
