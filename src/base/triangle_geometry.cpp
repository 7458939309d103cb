// The angles of a triangle (see triangle_geometry.hpp).
#include "base/triangle_geometry.hpp"

namespace fdr::geom {

double angle_deg(Point2 apex, Point2 p, Point2 q) {
  const Point2 u = p - apex, v = q - apex;
  const double cr = u.x * v.y - u.y * v.x;
  return std::atan2(std::fabs(cr), dot(u, v)) * kDegPerRad;
}

double min_angle_deg(Point2 a, Point2 b, Point2 c) {
  return min_angle_deg(a, b, c, cross2(a, b, c), edge_lengths2(a, b, c).max());
}

// atan2 only at the corners that may hold the smallest angle, with the value of all three: the
// three angles share |cross|, so the smallest is at the largest dot product d, and a corner whose
// d is below the largest by more than 1e-7 L^2 (L^2 = l2max) has an angle larger by at least
// ~5e-11 rad on a triangle that is not a sliver (|cross| >= 1e-3 L^2), far above the rounding of
// d, |cross| and atan2 (~1e-13 rad there). Slivers, degenerate and non-finite triangles: all three.
double min_angle_deg(Point2 a, Point2 b, Point2 c, double cross, double l2max) {
  const double acr = std::fabs(cross);
  if (!(acr >= 1e-3 * l2max) || !(l2max < std::numeric_limits<double>::infinity()))
    return std::min({angle_deg(a, b, c), angle_deg(b, c, a), angle_deg(c, a, b)});
  const Point2 ab = b - a, bc = c - b, ca = a - c;
  const double d[3] = {-dot(ab, ca), -dot(bc, ab), -dot(ca, bc)};  // at a, b, c
  const int k = d[0] >= d[1] ? (d[0] >= d[2] ? 0 : 2) : (d[1] >= d[2] ? 1 : 2);
  auto at = [&](int i) { return i == 0 ? angle_deg(a, b, c) : i == 1 ? angle_deg(b, c, a) : angle_deg(c, a, b); };
  const double tol = 1e-7 * l2max;
  double amin = at(k);
  for (int i = 0; i < 3; ++i)
    if (i != k && !(d[k] - d[i] > tol)) amin = std::min(amin, at(i));
  return amin;
}

}  // namespace fdr::geom
