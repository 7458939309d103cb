#include "tet/tet_geometry.hpp"
#include <algorithm>
#include <cmath>

namespace fdr::tet {

Sphere circumsphere(Point3 a, Point3 b, Point3 c, Point3 d) {
  // The centre's offset from a solves 2 (x - a) . (q - a) = |q - a|^2 for q = b, c, d; by
  // Cramer's rule it is the lifts times the cross products of the other two edges, over twice
  // the triple product.
  const Point3 ba = b - a, ca = c - a, da = d - a;
  const Point3 cxd = cross(ca, da), dxb = cross(da, ba), bxc = cross(ba, ca);
  const double den = 2 * dot(ba, cxd);
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
