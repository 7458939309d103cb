// 3D geometric predicates: the signs that decide every combinatorial step of the tetrahedral mesher.
// Same scheme as the 2D ones (predicates.hpp): a double-precision evaluation with a forward error
// bound (Shewchuk 1997, stage A), and CGAL's exact Epick predicate when the bound cannot certify
// the sign. Each call counts as filtered or exact in the same per-thread counters as the 2D ones.
// Like the 2D bounds, these assume that no intermediate product underflows; an overflow or a NaN
// makes the comparisons fail and so goes to the exact fallback.
#pragma once
#include <cmath>
#include "base/point3.hpp"
#include "predicates/predicates.hpp"

namespace fdr::predicates {

// Exact fallbacks (out of line: they pull in CGAL).
int orient3d_exact(Point3 a, Point3 b, Point3 c, Point3 d);
int insphere_exact(Point3 a, Point3 b, Point3 c, Point3 d, Point3 e);

// Encroachment in 3D refinement, exact (CGAL's filtered exact kernel; few calls, so no own filter).
// +1 when p lies strictly inside the sphere with diameter ab (the sign of -(a - p).(b - p)), 0 on
// it, -1 outside; a != b.
int diametral_side(Point3 a, Point3 b, Point3 p);
// +1 when p lies strictly inside the equatorial sphere of triangle abc (the smallest sphere through
// a, b, c: its centre lies in their plane), 0 on it, -1 outside; a, b, c not collinear. A sphere
// through a, b, c and a fourth point is not this one, so insphere cannot decide it.
int equatorial_side(Point3 a, Point3 b, Point3 c, Point3 p);

// The centre of the sphere through a, b, c, d (not coplanar), constructed exactly and rounded to
// the nearest doubles (CGAL's exact kernel): for tetrahedra too flat for a double formula, whose
// rounding error in the triple product can be as large as the product itself.
Point3 circumcentre_exact(Point3 a, Point3 b, Point3 c, Point3 d);
// The centre of the circle through a, b, c (in their plane), constructed exactly and rounded to
// the nearest doubles, for triangles too close to collinear for the double formula; a, b, c not
// collinear (collinear3d says so exactly).
Point3 triangle_circumcentre_exact(Point3 a, Point3 b, Point3 c);
// True when a, b, c lie on one line (or two of them coincide), decided exactly.
bool collinear3d(Point3 a, Point3 b, Point3 c);

namespace detail {
inline constexpr double kO3dBound = (7.0 + 56.0 * kEps) * kEps;
inline constexpr double kIspBound = (16.0 + 224.0 * kEps) * kEps;
}  // namespace detail

// Sign of dot(b - a, cross(c - a, d - a)): +1 when (a, b, c, d) has positive volume, -1 negative,
// 0 coplanar.
inline int orient3d(Point3 a, Point3 b, Point3 c, Point3 d) {
  // The determinant of the rows b - a, c - a, d - a, expanded along the z column: each term is a
  // difference times a 2x2 minor of differences, the form the stage-A bound is proved for.
  const double bx = b.x - a.x, by = b.y - a.y, bz = b.z - a.z;
  const double cx = c.x - a.x, cy = c.y - a.y, cz = c.z - a.z;
  const double dx = d.x - a.x, dy = d.y - a.y, dz = d.z - a.z;
  const double cxdy = cx * dy, dxcy = dx * cy;
  const double dxby = dx * by, bxdy = bx * dy;
  const double bxcy = bx * cy, cxby = cx * by;
  const double det = bz * (cxdy - dxcy) + cz * (dxby - bxdy) + dz * (bxcy - cxby);
  const double perm = (std::fabs(cxdy) + std::fabs(dxcy)) * std::fabs(bz) +
                      (std::fabs(dxby) + std::fabs(bxdy)) * std::fabs(cz) +
                      (std::fabs(bxcy) + std::fabs(cxby)) * std::fabs(dz);
  const double bound = detail::kO3dBound * perm;
  if (det > bound) { ++counters().filtered; return 1; }
  if (-det > bound) { ++counters().filtered; return -1; }
  ++counters().exact;
  return orient3d_exact(a, b, c, d);
}

// For positively oriented (a, b, c, d): +1 when e lies strictly inside their circumsphere, 0 on
// it, -1 outside (the sign flips for negatively oriented ones).
inline int insphere(Point3 a, Point3 b, Point3 c, Point3 d, Point3 e) {
  // The lifted 4x4 determinant with e moved to the origin, expanded by the lifts; its sign is the
  // opposite of the orientation convention above, hence the negation at the end.
  const double aex = a.x - e.x, aey = a.y - e.y, aez = a.z - e.z;
  const double bex = b.x - e.x, bey = b.y - e.y, bez = b.z - e.z;
  const double cex = c.x - e.x, cey = c.y - e.y, cez = c.z - e.z;
  const double dex = d.x - e.x, dey = d.y - e.y, dez = d.z - e.z;
  const double aexbey = aex * bey, bexaey = bex * aey;
  const double bexcey = bex * cey, cexbey = cex * bey;
  const double cexdey = cex * dey, dexcey = dex * cey;
  const double dexaey = dex * aey, aexdey = aex * dey;
  const double aexcey = aex * cey, cexaey = cex * aey;
  const double bexdey = bex * dey, dexbey = dex * bey;
  const double ab = aexbey - bexaey, bc = bexcey - cexbey, cd = cexdey - dexcey;
  const double da = dexaey - aexdey, ac = aexcey - cexaey, bd = bexdey - dexbey;
  const double abc = aez * bc - bez * ac + cez * ab;
  const double bcd = bez * cd - cez * bd + dez * bc;
  const double cda = cez * da + dez * ac + aez * cd;
  const double dab = dez * ab + aez * bd + bez * da;
  const double alift = aex * aex + aey * aey + aez * aez;
  const double blift = bex * bex + bey * bey + bez * bez;
  const double clift = cex * cex + cey * cey + cez * cez;
  const double dlift = dex * dex + dey * dey + dez * dez;
  const double det = (dlift * abc - clift * dab) + (blift * cda - alift * bcd);
  const double aez_ = std::fabs(aez), bez_ = std::fabs(bez), cez_ = std::fabs(cez), dez_ = std::fabs(dez);
  const double p_ab = std::fabs(aexbey) + std::fabs(bexaey), p_bc = std::fabs(bexcey) + std::fabs(cexbey);
  const double p_cd = std::fabs(cexdey) + std::fabs(dexcey), p_da = std::fabs(dexaey) + std::fabs(aexdey);
  const double p_ac = std::fabs(aexcey) + std::fabs(cexaey), p_bd = std::fabs(bexdey) + std::fabs(dexbey);
  const double perm = (p_cd * bez_ + p_bd * cez_ + p_bc * dez_) * alift +
                      (p_da * cez_ + p_ac * dez_ + p_cd * aez_) * blift +
                      (p_ab * dez_ + p_bd * aez_ + p_da * bez_) * clift +
                      (p_bc * aez_ + p_ac * bez_ + p_ab * cez_) * dlift;
  const double bound = detail::kIspBound * perm;
  if (det > bound) { ++counters().filtered; return -1; }
  if (-det > bound) { ++counters().filtered; return 1; }
  ++counters().exact;
  return insphere_exact(a, b, c, d, e);
}

}  // namespace fdr::predicates
