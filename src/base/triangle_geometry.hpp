// The geometry of one triangle, given its three corners: one definition of each quantity that
// refinement checks, smoothing, the quality report and the writers measure, so that every module
// that shows or compares one gets the same bits. Plain floating point (no exact predicate): the
// callers that take combinatorial decisions pair these with the predicates.
#pragma once
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include "base/types.hpp"

namespace fdr::geom {

inline constexpr double kDegPerRad = 180.0 / std::numbers::pi;
inline constexpr double kRadPerDeg = std::numbers::pi / 180.0;

// Twice the signed area of abc (positive when counter-clockwise).
inline double cross2(Point2 a, Point2 b, Point2 c) {
  const Point2 d = b - a, e = c - a;
  return d.x * e.y - d.y * e.x;
}

// The circumcentre of abc; *r2 (when given) its squared circumradius. A degenerate triangle
// (cross2 == 0) divides by zero: the centre and r2 are then infinite or NaN.
inline Point2 circumcentre(Point2 a, Point2 b, Point2 c, double* r2 = nullptr) {
  const double bx = b.x - a.x, by = b.y - a.y;
  const double cx = c.x - a.x, cy = c.y - a.y;
  const double b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
  const double d = 2.0 * (bx * cy - by * cx);
  const double ux = (cy * b2 - by * c2) / d;
  const double uy = (bx * c2 - cx * b2) / d;
  if (r2) *r2 = ux * ux + uy * uy;
  return {a.x + ux, a.y + uy};
}

// The circumradius from circumcentre()'s r2 and the triangle's cross2: +inf when degenerate.
inline double circumradius(double r2, double cross) {
  return cross != 0 ? std::sqrt(r2) : std::numeric_limits<double>::infinity();
}
inline double circumradius(Point2 a, Point2 b, Point2 c) {
  double r2 = 0;
  circumcentre(a, b, c, &r2);
  return circumradius(r2, cross2(a, b, c));
}

// The squared lengths of the edges ab, bc, ca.
struct EdgeLengths2 {
  double ab, bc, ca;
  double min() const { return std::min({ab, bc, ca}); }
  double max() const { return std::max({ab, bc, ca}); }
};
inline EdgeLengths2 edge_lengths2(Point2 a, Point2 b, Point2 c) { return {norm2(b - a), norm2(c - b), norm2(a - c)}; }

inline double shortest_edge(Point2 a, Point2 b, Point2 c) { return std::sqrt(edge_lengths2(a, b, c).min()); }

// R/l, l the shortest edge: +inf when l is 0 (Ruppert's radius-edge ratio; 1/sqrt(3) at best).
inline double radius_edge_ratio(double radius, double shortest) {
  return shortest > 0 ? radius / shortest : std::numeric_limits<double>::infinity();
}
inline double radius_edge_ratio(Point2 a, Point2 b, Point2 c) {
  return radius_edge_ratio(circumradius(a, b, c), shortest_edge(a, b, c));
}

// R/f(c), given f at the circumcentre (FDR's test: a triangle is bad when it exceeds B).
inline double r_over_f(double radius, double f_at_centre) { return radius / f_at_centre; }

// Mean-ratio quality 4 sqrt(3) area / (sum of squared edges): 1 for an equilateral triangle, 0 when
// degenerate, negative when clockwise.
inline double mean_ratio_quality(Point2 a, Point2 b, Point2 c) {
  constexpr double kFourSqrt3 = 6.928203230275509;
  const double area = 0.5 * cross2(a, b, c);
  const double s = norm2(b - a) + norm2(c - b) + norm2(a - c);
  return s > 0 ? kFourSqrt3 * area / s : 0.0;
}

// The angle at `apex` of the triangle (apex, p, q) in degrees, in [0, 180].
double angle_deg(Point2 apex, Point2 p, Point2 q);

// The smallest angle of abc in degrees: the smallest of angle_deg at the three corners (the one
// formula for it; NaN corners are ignored as std::min does, in corner order a, b, c).
double min_angle_deg(Point2 a, Point2 b, Point2 c);
// The same value, given cross2(a, b, c) and edge_lengths2(a, b, c).max() when the caller has them.
double min_angle_deg(Point2 a, Point2 b, Point2 c, double cross, double l2max);

// sin^2 of the smallest angle: increases with that angle (at most 60 degrees), so it compares
// smallest angles without trigonometry; 0 when degenerate.
inline double min_angle_sin2(Point2 a, Point2 b, Point2 c) {
  const double cr = cross2(a, b, c);
  const double la = norm2(c - b), lb = norm2(a - c), lc = norm2(b - a);
  double p;  // the squares of the two edges at the smallest angle (opposite the shortest)
  if (la <= lb && la <= lc) p = lb * lc;
  else if (lb <= lc) p = la * lc;
  else p = la * lb;
  return p > 0 ? cr * cr / p : 0.0;
}

}  // namespace fdr::geom
