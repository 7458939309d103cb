// Frontal point placement: Rebay's point on the Voronoi edge between an accepted triangle and the
// bad one (the bisector of their common edge), with the circumradius the front asks for.
#include "refine/frontal.hpp"
#include <algorithm>
#include <cmath>

namespace fdr::refine {

FrontalPoint frontal_point(Point2 p, Point2 q, Point2 cc, double r, double rho) {
  const Point2 m = 0.5 * (p + q);
  const Point2 e = q - p;
  const double len = std::sqrt(norm2(e));
  const double h = 0.5 * len;
  const Point2 n{-e.y / len, e.x / len};  // unit normal into the bad triangle (left of p->q)
  // The circle through p and q with radius rh has its far point at distance rh + sqrt(rh^2 - h^2)
  // from the edge's midpoint along n: the apex of the triangle (p, q, x) of circumradius rh.
  const double rh = std::max(rho, h);
  const double want = rh + std::sqrt(std::max(0.0, rh * rh - h * h));
  const double qc = dot(cc - m, n);  // the bad triangle's circumcentre along the bisector
  // Inside the bad circumcircle along the bisector means (qc - r, qc + r), and qc - r < 0 < d
  // (m is inside: it is the midpoint of a chord). Past the circumcentre is not needed: there the
  // circumcentre itself is the better point; with qc <= 0 (the front edge is the bad triangle's
  // longest, obtuse opposite) halfway to the circle.
  const double limit = qc > 0 ? qc : 0.5 * (qc + r);
  FrontalPoint out;
  double d = want;
  if (d > limit) {
    d = limit;
    out.clamped = true;
  }
  out.x = m + d * n;
  const double rx = d > 0 ? (h * h + d * d) / (2 * d) : h;  // circumradius of (p, q, x)
  out.centre = m + (d - rx) * n;
  return out;
}

}  // namespace fdr::refine
