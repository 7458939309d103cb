// Geometric predicates: the only place in fdrmesh where a sign is decided.
//
// Each predicate first evaluates in double precision with a forward error
// bound (Shewchuk, "Adaptive Precision Floating-Point Arithmetic and Fast
// Robust Geometric Predicates", 1997, stage A bounds); when the bound cannot
// certify the sign, it falls back to CGAL's Epick kernel predicate, which is
// exact. Results are therefore exact for all finite double inputs.
#pragma once
#include <cmath>
#include <cstdint>
#include "base/types.hpp"

namespace fdr::predicates {

// How many decisions were certified by the double filter and how many needed
// the exact fallback. Per thread; reset with reset_counters().
struct Counters {
  std::uint64_t filtered = 0;
  std::uint64_t exact = 0;
};
inline thread_local Counters tls_counters;
inline Counters& counters() { return tls_counters; }
inline void reset_counters() { tls_counters = Counters{}; }

// Exact fallbacks (out of line: they pull in CGAL).
int orient2d_exact(Point2 a, Point2 b, Point2 c);
int incircle_exact(Point2 a, Point2 b, Point2 c, Point2 d);
int diametral_exact(Point2 a, Point2 b, Point2 p);

// Intersection of the lines ab and cd computed exactly (rationals), each coordinate rounded to
// the nearest double. Returns false when the lines are parallel (or a degenerate segment).
// A construction, not a predicate: used where constraints are split at their crossings.
bool line_intersection_rounded(Point2 a, Point2 b, Point2 c, Point2 d, Point2* out);

namespace detail {
inline constexpr double kEps = 1.1102230246251565e-16;  // 2^-53
inline constexpr double kCcwBound = (3.0 + 16.0 * kEps) * kEps;
inline constexpr double kIccBound = (10.0 + 96.0 * kEps) * kEps;
inline constexpr double kDotBound = 8.0 * kEps;
}  // namespace detail

// Sign of the signed area of (a,b,c): +1 counter-clockwise, -1 clockwise, 0 collinear.
inline int orient2d(Point2 a, Point2 b, Point2 c) {
  const double l = (a.x - c.x) * (b.y - c.y);
  const double r = (a.y - c.y) * (b.x - c.x);
  const double det = l - r;
  const double bound = detail::kCcwBound * (std::fabs(l) + std::fabs(r));
  if (det > bound) { ++counters().filtered; return 1; }
  if (-det > bound) { ++counters().filtered; return -1; }
  // Opposite signs (or a zero) with equal magnitude bounds still need care: fall back.
  ++counters().exact;
  return orient2d_exact(a, b, c);
}

// +1 if d lies strictly inside the circle through a,b,c (given CCW), -1 outside, 0 on it.
// For clockwise (a,b,c) the sign is reversed, as usual.
inline int incircle(Point2 a, Point2 b, Point2 c, Point2 d) {
  const double adx = a.x - d.x, ady = a.y - d.y;
  const double bdx = b.x - d.x, bdy = b.y - d.y;
  const double cdx = c.x - d.x, cdy = c.y - d.y;
  const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
  const double alift = adx * adx + ady * ady;
  const double cdxady = cdx * ady, adxcdy = adx * cdy;
  const double blift = bdx * bdx + bdy * bdy;
  const double adxbdy = adx * bdy, bdxady = bdx * ady;
  const double clift = cdx * cdx + cdy * cdy;
  const double det = alift * (bdxcdy - cdxbdy) + blift * (cdxady - adxcdy) + clift * (adxbdy - bdxady);
  const double perm = (std::fabs(bdxcdy) + std::fabs(cdxbdy)) * alift +
                      (std::fabs(cdxady) + std::fabs(adxcdy)) * blift +
                      (std::fabs(adxbdy) + std::fabs(bdxady)) * clift;
  const double bound = detail::kIccBound * perm;
  if (det > bound) { ++counters().filtered; return 1; }
  if (-det > bound) { ++counters().filtered; return -1; }
  ++counters().exact;
  return incircle_exact(a, b, c, d);
}

// +1 if p lies strictly inside the diametral circle of segment ab (angle apb obtuse),
// 0 if on the circle, -1 outside. Sign of -(a-p).(b-p).
inline int diametral(Point2 a, Point2 b, Point2 p) {
  const double x = (a.x - p.x) * (b.x - p.x);
  const double y = (a.y - p.y) * (b.y - p.y);
  const double d = x + y;
  const double bound = detail::kDotBound * (std::fabs(x) + std::fabs(y));
  if (d > bound) { ++counters().filtered; return -1; }
  if (-d > bound) { ++counters().filtered; return 1; }
  ++counters().exact;
  return diametral_exact(a, b, p);
}

// True if p encroaches segment ab: p lies strictly inside its diametral circle.
inline bool encroaches(Point2 a, Point2 b, Point2 p) { return diametral(a, b, p) > 0; }

}  // namespace fdr::predicates
