// The report's angle histograms and extremes with atan2 for few triangles, the same figures as
// geom::angle_deg at every corner of every triangle.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include "base/triangle_geometry.hpp"
#include "quality/extremes.hpp"
#include "quality/report.hpp"

namespace fdr::quality {

// The three angles of a triangle share |cross| (twice its area), so an angle t at a corner with
// dot product d satisfies cot t = d/|cross|: t >= phi  <=>  d <= |cross| cot(phi) (0 < phi < 180
// deg). The smallest angle is at the largest d, the largest at the smallest. fast() decides both
// bins that way when every comparison is clear by a margin of 1e-9 L^2 (L the longest edge;
// rounding is ~1e-15 L^2, and atan2's ~1e-15 rad, far inside the margin) on triangles that are not
// slivers (|cross| >= 1e-3 L^2, i.e. every angle >= 0.057 deg), and calls atan2 only when the
// triangle may hold the smallest or the largest angle so far; otherwise (false) the caller
// measures the angles with atan2 and calls add().
class AngleBins {
 public:
  AngleBins(const Histogram& lo, const Histogram& hi) : lo_(edges<12>(lo)), hi_(edges<24>(hi)) {}
  // `l2`: the largest squared edge length.
  __attribute__((always_inline)) bool fast(Point2 a, Point2 b, Point2 c, double cross, QualityReport& r, double l2) {
    const Point2 ab = b - a, bc = c - b, ca = a - c;
    const double acr = std::fabs(cross);
    if (!(acr >= 1e-3 * l2) || !(l2 < kInf)) return false;  // slivers, degenerate, NaN, inf
    const double d0 = -dot(ab, ca), d1 = -dot(bc, ab), d2 = -dot(ca, bc);  // at a, b, c
    const double dmax = std::max({d0, d1, d2}), dmin = std::min({d0, d1, d2});
    const double tol = 1e-9 * l2;
    std::size_t bmin, bmax;
    if (!bin(lo_, dmax, acr, tol, bmin) || !bin(hi_, dmin, acr, tol, bmax)) return false;
    // Possibly a new extreme: the angles with atan2, as the slow path would.
    if (!r.min_angle_deg || !r.max_angle_deg || dmax >= acr * cot_min_ - tol || dmin <= acr * cot_max_ + tol) {
      const double ang[3] = {geom::angle_deg(a, b, c), geom::angle_deg(b, c, a), geom::angle_deg(c, a, b)};
      update(r, std::min({ang[0], ang[1], ang[2]}), std::max({ang[0], ang[1], ang[2]}));
    }
    ++r.min_angle_histogram.counts[bmin];
    ++r.max_angle_histogram.counts[bmax];
    return true;
  }
  // A triangle's smallest and largest angle measured with atan2 (the slow path).
  void add(QualityReport& r, double amin, double amax) {
    update(r, amin, amax);
    r.min_angle_histogram.add(amin);
    r.max_angle_histogram.add(amax);
  }
  void update(QualityReport& r, double amin, double amax) {
    if (!r.min_angle_deg || amin < *r.min_angle_deg) {
      r.min_angle_deg = amin;
      cot_min_ = cot_deg(amin);
    }
    if (!r.max_angle_deg || amax > *r.max_angle_deg) {
      r.max_angle_deg = amax;
      cot_max_ = cot_deg(amax);
    }
  }

 private:
  // cot of the inner bin edges lo + k*width, k = 1..n-1, then -inf (never counted, always clear)
  // up to a fixed size, so that bin() compares them all without a branch.
  template <std::size_t N>
  struct Edges {
    std::array<double, N> cot;
    std::size_t n = 0;  // inner edges
    bool ok = false;    // edges strictly inside (0, 180) deg, and at most N of them
  };
  static double cot_deg(double deg) {
    if (!(deg > 0)) return kInf;
    if (!(deg < 180)) return -kInf;
    return std::cos(deg / geom::kDegPerRad) / std::sin(deg / geom::kDegPerRad);
  }
  template <std::size_t N>
  static Edges<N> edges(const Histogram& h) {
    Edges<N> e;
    e.cot.fill(-kInf);
    e.n = h.counts.size() >= 1 ? h.counts.size() - 1 : 0;
    e.ok = h.counts.size() >= 1 && e.n <= N && h.width > 0;
    for (std::size_t k = 1; e.ok && k < h.counts.size(); ++k) {
      const double phi = h.lo + static_cast<double>(k) * h.width;
      if (!(phi > 1 && phi < 179)) e.ok = false;
      e.cot[k - 1] = cot_deg(phi);
    }
    return e;
  }
  // The bin of the angle with dot product d: the number of inner edges phi_k <= t (the first and
  // last bins take the values outside, as Histogram::add). False when a comparison is unclear.
  // d - acr cot(phi_k) increases with k; <= 0 means t >= phi_k. Every edge is compared (no
  // branch on the data): a clear comparison far from the angle's bin cannot be wrong. The counts
  // are doubles (exact for these small numbers) so that the compiler compares two edges per
  // instruction.
  template <std::size_t N>
  static bool bin(const Edges<N>& e, double d, double acr, double tol, std::size_t& out) {
    if (!e.ok) return false;
    double k = 0, unclear = 0;
    for (std::size_t i = 0; i < N; ++i) {
      const double g = d - acr * e.cot[i];
      k += g <= 0 ? 1.0 : 0.0;
      unclear += std::fabs(g) > tol ? 0.0 : 1.0;  // NaN: unclear
    }
    out = static_cast<std::size_t>(k);
    return unclear == 0;
  }
  Edges<12> lo_;  // the report: 11 inner edges (0..60 deg by 5)
  Edges<24> hi_;  // 23 (60..180 deg by 5)
  double cot_min_ = kInf, cot_max_ = -kInf;
};

}  // namespace fdr::quality
