#include "tet/tet_geometry.hpp"
#include <algorithm>
#include <cmath>
#include <limits>
#include "predicates/predicates3d.hpp"

namespace fdr::tet {

Sphere circumsphere(Point3 a, Point3 b, Point3 c, Point3 d) {
  // The centre's offset from a solves 2 (x - a) . (q - a) = |q - a|^2 for q = b, c, d; by
  // Cramer's rule it is the lifts times the cross products of the other two edges, over twice
  // the triple product.
  const Point3 ba = b - a, ca = c - a, da = d - a;
  const Point3 cxd = cross(ca, da), dxb = cross(da, ba), bxc = cross(ba, ca);
  const double den = 2 * dot(ba, cxd);
  // The triple product's rounding error is a few units in the last place of the sum of its
  // terms' magnitudes; a tetrahedron whose triple product is within a million times that has a
  // double centre that may be anywhere (even outside its own sphere), so it is constructed exactly.
  constexpr double kFlat = 1e6 * 8 * std::numeric_limits<double>::epsilon();
  const double magnitude = std::fabs(ba.x) * (std::fabs(ca.y * da.z) + std::fabs(ca.z * da.y)) +
                           std::fabs(ba.y) * (std::fabs(ca.z * da.x) + std::fabs(ca.x * da.z)) +
                           std::fabs(ba.z) * (std::fabs(ca.x * da.y) + std::fabs(ca.y * da.x));
  if (!(std::fabs(den) > 2 * kFlat * magnitude) && magnitude > 0 && predicates::orient3d(a, b, c, d) != 0) {
    const Point3 o = predicates::circumcentre_exact(a, b, c, d);
    return {o, dist(o, a)};
  }
  const Point3 off = (1 / den) * (norm2(ba) * cxd + norm2(ca) * dxb + norm2(da) * bxc);
  return {a + off, std::sqrt(norm2(off))};
}

double shortest_edge(Point3 a, Point3 b, Point3 c, Point3 d) {
  const double m = std::min({norm2(a - b), norm2(a - c), norm2(a - d), norm2(b - c), norm2(b - d), norm2(c - d)});
  return std::sqrt(m);
}

double radius_edge_ratio(Point3 a, Point3 b, Point3 c, Point3 d) {
  return circumsphere(a, b, c, d).radius / shortest_edge(a, b, c, d);
}

}  // namespace fdr::tet
