// Mesh quality measurement and report writers (FDR paper: Definition 2.1, Theorems 4.3-4.5).
#include "quality/compensated_sum.hpp"
#include "quality/report.hpp"
#include "base/kd_tree.hpp"
#include <cstdio>
#include <fstream>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <ostream>
#include <string>
#include <exception>
#include <atomic>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#include <latch>
#include <memory>
#include <thread>
#include <nlohmann/json.hpp>

#include "base/error.hpp"
#include "base/memory.hpp"
#include "base/step_laps.hpp"
#include "base/parallel.hpp"
#include "predicates/predicates.hpp"
#include "quality/cell_centre.hpp"
#include "quality/mesh_adjacency.hpp"

namespace fdr::quality {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = 180.0 / kPi;
constexpr double kInf = std::numeric_limits<double>::infinity();

// Kahan-Babuska (Neumaier) compensated sum: areas of millions of triangles of very different size.

double angle_at(Point2 apex, Point2 p, Point2 q) {
  const Point2 u = p - apex, v = q - apex;
  const double cr = u.x * v.y - u.y * v.x;
  return std::atan2(std::fabs(cr), dot(u, v)) * kDeg;
}

// The smallest of angle_at(a, b, c), angle_at(b, c, a), angle_at(c, a, b), the same value, with
// atan2 only at the corners that may hold it: the smallest angle is at the largest dot product d
// (the three angles share |cross|), and a corner whose d is below the largest by more than
// 1e-7 L^2 (L^2 = l2, the largest squared edge) has an angle larger by at least ~5e-11 rad on a
// triangle that is not a sliver (|cross| >= 1e-3 L^2), far above the rounding of d, |cross| and
// atan2 (~1e-13 rad there). Slivers, degenerate and non-finite triangles: all three.
double min_angle(Point2 a, Point2 b, Point2 c, double cross, double l2) {
  const Point2 ab = b - a, bc = c - b, ca = a - c;
  const double acr = std::fabs(cross);
  if (!(acr >= 1e-3 * l2) || !(l2 < kInf))
    return std::min({angle_at(a, b, c), angle_at(b, c, a), angle_at(c, a, b)});
  const double d[3] = {-dot(ab, ca), -dot(bc, ab), -dot(ca, bc)};  // at a, b, c
  const int k = d[0] >= d[1] ? (d[0] >= d[2] ? 0 : 2) : (d[1] >= d[2] ? 1 : 2);
  auto at = [&](int i) { return i == 0 ? angle_at(a, b, c) : i == 1 ? angle_at(b, c, a) : angle_at(c, a, b); };
  const double tol = 1e-7 * l2;
  double amin = at(k);
  for (int i = 0; i < 3; ++i)
    if (i != k && !(d[k] - d[i] > tol)) amin = std::min(amin, at(i));
  return amin;
}

void update_min(std::optional<double>& m, double v) { if (!m || v < *m) m = v; }
void update_max(std::optional<double>& m, double v) { if (!m || v > *m) m = v; }

// The angle histograms and extremes without trigonometry for most triangles, with the same
// figures as atan2 (angle_at) for every triangle. The three angles of a triangle share |cross|
// (twice its area), so an angle t at a corner with dot product d satisfies cot t = d/|cross|:
// t >= phi  <=>  d <= |cross| cot(phi) (0 < phi < 180 deg). The smallest angle is at the largest d,
// the largest at the smallest. fast() decides both bins that way when every comparison is clear
// by a margin of 1e-9 L^2 (L the longest edge; rounding is ~1e-15 L^2, and atan2's ~1e-15 rad,
// far inside the margin) on triangles that are not slivers (|cross| >= 1e-3 L^2, i.e. every angle
// >= 0.057 deg), and calls atan2 only when the triangle may hold the smallest or the largest angle
// so far; otherwise (false) the caller measures the angles with atan2 as before.
class AngleBins {
 public:
  AngleBins(const Histogram& lo, const Histogram& hi) : lo_(edges<12>(lo)), hi_(edges<24>(hi)) {}
  // `l2`: the largest squared edge length, when the caller has it.
  __attribute__((always_inline)) bool fast(Point2 a, Point2 b, Point2 c, double cross, QualityReport& r,
                                           double l2 = -1) {
    const Point2 ab = b - a, bc = c - b, ca = a - c;
    if (l2 < 0) l2 = std::max({norm2(ab), norm2(bc), norm2(ca)});
    const double acr = std::fabs(cross);
    if (!(acr >= 1e-3 * l2) || !(l2 < kInf)) return false;  // slivers, degenerate, NaN, inf
    const double d0 = -dot(ab, ca), d1 = -dot(bc, ab), d2 = -dot(ca, bc);  // at a, b, c
    const double dmax = std::max({d0, d1, d2}), dmin = std::min({d0, d1, d2});
    const double tol = 1e-9 * l2;
    std::size_t bmin, bmax;
    if (!bin(lo_, dmax, acr, tol, bmin) || !bin(hi_, dmin, acr, tol, bmax)) return false;
    // Possibly a new extreme: the angles with atan2, as the slow path would.
    if (!r.min_angle_deg || !r.max_angle_deg || dmax >= acr * cot_min_ - tol || dmin <= acr * cot_max_ + tol) {
      const double ang[3] = {angle_at(a, b, c), angle_at(b, c, a), angle_at(c, a, b)};
      update(r, std::min({ang[0], ang[1], ang[2]}), std::max({ang[0], ang[1], ang[2]}));
    }
    ++r.min_angle_histogram.counts[bmin];
    ++r.max_angle_histogram.counts[bmax];
    return true;
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
    return std::cos(deg / kDeg) / std::sin(deg / kDeg);
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
  // branch on the data): a clear comparison far from the angle's bin cannot be wrong.
  template <std::size_t N>
  static bool bin(const Edges<N>& e, double d, double acr, double tol, std::size_t& out) {
    static_assert(N % 2 == 0);
    if (!e.ok) return false;
    unsigned k = 0, unclear = 0;
#if defined(__SSE2__)
    // Two edges per instruction (the same IEEE operations as the scalar loop below).
    const __m128d vd = _mm_set1_pd(d), va = _mm_set1_pd(acr), vtol = _mm_set1_pd(tol), zero = _mm_setzero_pd();
    const __m128d abs_mask = _mm_castsi128_pd(_mm_set1_epi64x(0x7fffffffffffffffLL));
    for (std::size_t i = 0; i < N; i += 2) {
      const __m128d g = _mm_sub_pd(vd, _mm_mul_pd(va, _mm_loadu_pd(&e.cot[i])));
      const unsigned below = static_cast<unsigned>(_mm_movemask_pd(_mm_cmple_pd(g, zero)));  // two bits
      k += (below & 1u) + (below >> 1);
      unclear |= static_cast<unsigned>(_mm_movemask_pd(_mm_cmpngt_pd(_mm_and_pd(g, abs_mask), vtol)));
    }
#else
    for (std::size_t i = 0; i < N; ++i) {
      const double g = d - acr * e.cot[i];
      k += g <= 0;
      unclear |= !(std::fabs(g) > tol);
    }
#endif
    out = k;
    return unclear == 0;
  }
  Edges<12> lo_;  // the report: 11 inner edges (0..60 deg by 5)
  Edges<24> hi_;  // 23 (60..180 deg by 5)
  double cot_min_ = kInf, cot_max_ = -kInf;
};

bool usable_spacing(double v) { return std::isfinite(v) && v > 0; }

}  // namespace

void Histogram::add(double v) {
  if (counts.empty()) return;
  // The floor of b without a libm call: truncation equals it for b >= 0, and below 0 (or NaN) the
  // first bin takes the value either way.
  const double b = (v - lo) / width;
  const std::size_t i = !(b >= 0) ? 0 : b >= static_cast<double>(counts.size()) ? counts.size() - 1 : static_cast<std::size_t>(b);
  ++counts[i];
}

Guarantees compute_guarantees(double alpha, double bound_B, std::optional<double> D) {
  Guarantees g;
  if (!std::isfinite(alpha) || alpha < 0) {
    g.note = "no guarantee: the Lipschitz constant alpha of f is unknown";
    return g;
  }
  if (!std::isfinite(bound_B) || bound_B <= 0) {
    g.note = "no guarantee: the bound B must be positive";
    return g;
  }
  const double ab = alpha * bound_B;
  if (ab >= 1) {
    char buf[160];
    std::snprintf(buf, sizeof buf,
                  "no guarantee: alpha*B = %.6g >= 1 (Section 4 requires B < 1/alpha)", ab);
    g.note = buf;
    return g;
  }
  const double s = 2.0 * std::sqrt(2.0) + 3.0 * ab;
  g.valid = true;
  g.beta_B = bound_B / s;
  g.beta = g.beta_B;
  // Section 4: beta = min(B/(2 sqrt(2) + 3 alpha B), D/(2 + alpha D)), D from nn_Mc >= D f. An
  // input with features finer than f (two coast vertices closer than f, a thin spit between two
  // waters) has a small D, and the bounds below are then the weaker ones the paper proves for it.
  if (D && *D >= 0 && std::isfinite(*D)) {
    g.beta_D = *D / (2.0 + alpha * *D);
    g.beta = std::min(g.beta_B, *g.beta_D);
  }
  // Theorem 4.3: R/l <= B / (2 beta (1 - alpha B)); the smallest angle theta has sin(theta) = l/(2R)
  // at the shortest edge.
  g.R_over_l_max = g.beta > 0 ? bound_B / (2.0 * g.beta * (1.0 - ab)) : std::numeric_limits<double>::infinity();
  g.min_angle_deg = g.beta > 0 ? std::asin(std::min(1.0, 0.5 / g.R_over_l_max)) * kDeg : 0.0;
  g.nn_over_f_min = 2.0 * g.beta / (1.0 + alpha * g.beta);
  g.el_over_f_max = 2.0 * bound_B / (1.0 + ab);
  g.el_over_f_max_corrected = 2.0 * bound_B / (1.0 - ab);
  if (!g.beta_D)
    g.note = "2D, beta = B/(2*sqrt(2)+3*alpha*B), assuming beta <= D/(2+alpha*D) (Section 4; D unknown)";
  else if (g.beta < g.beta_B)
    g.note = "2D, beta = D/(2+alpha*D) < B/(2*sqrt(2)+3*alpha*B): the conforming mesh has vertices nearer than f "
             "(input features finer than the spacing; D below)";
  else
    g.note = "2D, beta = B/(2*sqrt(2)+3*alpha*B) <= D/(2+alpha*D) (Section 4; D of the conforming mesh below)";
  return g;
}

std::vector<TheoremCheck> theorem_checks(const QualityReport& r) {
  std::vector<TheoremCheck> rows;
  auto add = [&](const char* key, const char* label, bool upper, double bound, std::optional<double> meas,
                 bool counts = true) {
    std::optional<bool> holds;
    if (meas) holds = upper ? *meas <= bound : *meas >= bound;  // NaN measured: false
    rows.push_back({key, label, upper, bound, meas, holds, counts});
  };
  // The refiner's invariant, the hypothesis of every theorem below (needs f).
  if (r.max_R_over_f) add("fdr_R_over_f_max", "R/f(c) max (FDR, B)", true, r.bound_B, r.max_R_over_f);
  const Guarantees& g = r.guarantees;
  if (!g.valid) return rows;
  add("theorem_4_3_R_over_l_max", "R/l max (Thm 4.3)", true, g.R_over_l_max, r.max_radius_edge);
  add("theorem_4_3_min_angle_deg", "min angle deg", false, g.min_angle_deg, r.min_angle_deg);
  add("theorem_4_4_nn_over_f_min", "nn/f min (Thm 4.4)", false, g.nn_over_f_min, r.nn_over_f_min);
  add("theorem_4_5_el_over_f_max", "el/f max (Thm 4.5)", true, g.el_over_f_max, r.el_over_f_max, false);
  add("theorem_4_5_corrected_el_over_f_max", "el/f max (4.5 fixed)", true, g.el_over_f_max_corrected, r.el_over_f_max);
  return rows;
}

bool guarantees_hold(const QualityReport& r) {
  if (!r.guarantees.valid) return false;
  for (const auto& c : theorem_checks(r))
    if (c.counts && c.holds && !*c.holds) return false;
  return true;
}

std::vector<double> nearest_neighbour_distances(const std::vector<Point2>& pts) {
  std::vector<double> nn(pts.size(), kInf);
  if (pts.size() < 2) return nn;
  const KdTree tree(pts);
  for (std::size_t k = 0; k < tree.size(); ++k) nn[tree.id_at(k)] = std::sqrt(tree.nearest_sq_at(k));
  return nn;
}

namespace {

template <class V>
void release_vector(V& v) {
  V().swap(v);
}

// At least the k largest values of a stream (as a multiset), in a buffer of fewer than 2k: a value
// below thr_ (the k-th largest at the last trim) cannot be among the k largest. NaN counts as the
// largest value (as the previous 16-bit buckets ordered it).
class TopK {
 public:
  explicit TopK(std::size_t k = 1) : k_(std::max<std::size_t>(k, 1)) {}
  void add(double x) {
    if (!(x < thr_)) {
      v_.push_back(x);
      if (v_.size() >= 2 * k_) trim();
    }
  }
  struct Less {  // a type (not a function pointer) so that sorting inlines it
    bool operator()(double a, double b) const { return a < b || (!std::isnan(a) && std::isnan(b)); }
  };
  static constexpr Less less{};
  std::vector<double>& values() { return v_; }

 private:
  void trim() {
    const auto cut = v_.begin() + static_cast<std::ptrdiff_t>(v_.size() - k_);
    std::nth_element(v_.begin(), cut, v_.end(), less);
    thr_ = *cut;
    v_.erase(v_.begin(), cut);
  }
  std::size_t k_;
  double thr_ = -kInf;
  std::vector<double> v_;
};

// The nearest-rank q-quantile of n values (rank ceil(q n)) from `top`, which holds at least the
// `keep` largest values of each part of the n (or all of a part's); nullopt when the quantile may
// lie below them (more than `keep` values from that rank up). NaN sorts last.
std::optional<double> quantile_from_top(std::vector<double>& top, std::size_t keep, std::size_t n, double q) {
  const std::size_t rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(n)));
  const std::size_t k = rank == 0 ? 0 : std::min(rank - 1, n - 1);  // 0-based
  const std::size_t from_top = n - k;                                // k is the from_top-th largest
  if (from_top > keep || from_top > top.size()) return std::nullopt;
  const auto at = top.end() - static_cast<std::ptrdiff_t>(from_top);
  std::nth_element(top.begin(), at, top.end(), TopK::less);
  return *at;
}

// A triangle with that corner, where the nearest-neighbour walk starts (any one gives the same
// distances: the walk is exact from each of them). Two threads may store it in either order.
template <bool kShared>
inline void keep_corner(Index& x, Index t) {
  if constexpr (kShared) std::atomic_ref<Index>(x).store(t, std::memory_order_relaxed);
  else x = t;
}

// x = min(x, v); with two threads at once an atomic minimum (a compare-exchange only when v is
// smaller: a vertex's shortest edge improves a few times among its ~6 edges). The result is the
// minimum whatever the order. NaN never lowers it, as with std::min(x, NaN).
template <bool kShared>
inline void lower_to(double& x, double v) {
  if constexpr (kShared) {
    std::atomic_ref<double> a(x);
    double cur = a.load(std::memory_order_relaxed);
    while (v < cur && !a.compare_exchange_weak(cur, v, std::memory_order_relaxed)) {
    }
  } else {
    x = std::min(x, v);
  }
}

// Two divisions / square roots in one instruction where SSE2 is there (the same IEEE results as
// one at a time): the report's pass is bound by them.
inline void div2(double a0, double b0, double a1, double b1, double& q0, double& q1) {
#if defined(__SSE2__)
  const __m128d q = _mm_div_pd(_mm_set_pd(a1, a0), _mm_set_pd(b1, b0));
  q0 = _mm_cvtsd_f64(q);
  q1 = _mm_cvtsd_f64(_mm_unpackhi_pd(q, q));
#else
  q0 = a0 / b0;
  q1 = a1 / b1;
#endif
}
inline void sqrt2(double a0, double a1, double& r0, double& r1) {
#if defined(__SSE2__)
  const __m128d r = _mm_sqrt_pd(_mm_set_pd(a1, a0));
  r0 = _mm_cvtsd_f64(r);
  r1 = _mm_cvtsd_f64(_mm_unpackhi_pd(r, r));
#else
  r0 = std::sqrt(a0);
  r1 = std::sqrt(a1);
#endif
}
// predicates::circumcenter, operation for operation, with its two divisions paired.
inline Point2 circumcentre(Point2 a, Point2 b, Point2 c, double* r2) {
  const double bx = b.x - a.x, by = b.y - a.y;
  const double cx = c.x - a.x, cy = c.y - a.y;
  const double b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
  const double d = 2.0 * (bx * cy - by * cx);
  double ux, uy;
  div2(cy * b2 - by * c2, d, bx * c2 - cx * b2, d, ux, uy);
  if (r2) *r2 = ux * ux + uy * uy;
  return {a.x + ux, a.y + uy};
}

// What one thread measures on its triangles (merged in a fixed order: figures do not depend on
// how the triangles were split).
struct Part {
  explicit Part(const QualityReport& r, std::size_t top_k)
      : angles(r.min_angle_histogram, r.max_angle_histogram), otop(top_k), stop(top_k) {
    q.min_angle_histogram = r.min_angle_histogram;
    q.max_angle_histogram = r.max_angle_histogram;
  }
  QualityReport q;  // degenerate, inverted, angle extremes and histograms, max R/l
  AngleBins angles;
  std::size_t interior = 0;
  double omax = -1, smax = -1;
  TopK otop, stop;
  std::vector<Index> not_delaunay;
  bool ccw = true;
};

constexpr std::size_t kSumChunk = 4096;  // triangles per chunk (sums; the threads' work units)
struct ChunkSums {
  CompensatedSum area, r_over_f;
  std::size_t count = 0;
};

// The report's single pass over the triangles and their interior edges (every metric that does
// not need f), with the adjacency `nb`; also the area and R/f(c) sums of its triangles, on the
// thread that measures them when f is thread-safe, else on the calling thread (evaluate() does
// them for the triangles measured elsewhere).
struct Pass {
  const mesh::MeshView& m;
  const std::vector<Index>& nb;
  const sizing::SizingField* f;
  double bound_B;
  TriangleValues* per_triangle;
  bool walk;  // gather what the nearest-neighbour walk needs (tri_of_vertex, local Delaunay check)
  // f at the vertices (null without f): el(p)/f(p) is the largest of lmax(T)/f(p) over the
  // triangles T at p (a division by f(p) > 0 keeps the order, also as rounded), so no el array.
  const double* fv;
  std::vector<double>& nn2;  // per vertex: shortest mesh edge, squared
  std::vector<Index>& tov;   // per vertex: a triangle with that corner (keep_corner)
  // Area and R/f(c) sums per chunk of kSumChunk triangles (each in triangle order; the chunks
  // are added in order at the end, so the sums do not depend on which thread measured what).
  ChunkSums* sums = nullptr;
  std::size_t spacing_invalid = 0, bad = 0;
  std::optional<double> max_rf;

  std::optional<double> el_f_max;  // el(p)/f(p) over this pass's triangles (with f)
  void el_over_f(const std::array<Index, 3>& tr, double lmax) {
    if (!fv) return;
    const double l = std::max(0.0, lmax);  // el starts at 0 (a NaN length counts as 0)
    // The largest l / f(v) over the usable corners is l / (their smallest f): a correctly
    // rounded division is monotone in its divisor, so the value is the same, with one division.
    double fmin = kInf;
    for (const Index v : tr)
      if (usable_spacing(fv[v])) fmin = std::min(fmin, fv[v]);
    if (fmin < kInf) update_max(el_f_max, l / fmin);
  }

  void add_f(std::size_t t, double cr, double radius, Point2 center) {
    ChunkSums& cs = sums[t / kSumChunk];
    cs.area.add(0.5 * cr);
    if (per_triangle) per_triangle->area[t] = 0.5 * cr;
    if (!f) return;
    double ratio = kInf;
    if (std::isfinite(radius)) {
      const double fc = (*f)(center);
      if (per_triangle) per_triangle->r_over_f[t] = radius / fc;
      if (!usable_spacing(fc)) {
        ++spacing_invalid;
        return;
      }
      ratio = radius / fc;
    }
    update_max(max_rf, ratio);
    cs.r_over_f.add(ratio);
    ++cs.count;
    if (ratio > bound_B) ++bad;
  }

  // Everything for the triangles [lo, hi); with_f: also the area, R/f(c) and el/f (the calling
  // thread always; the second one when f is thread-safe, else evaluate() does them). In batches: the scattered loads first, then each computation in its
  // own short loop over the batch, so that the divisions and square roots of different triangles
  // overlap (the same operations on the same values as one triangle at a time).
  template <bool kShared>
  void measure(std::size_t lo, std::size_t hi, Part& p, bool with_f) {
    for (std::size_t b = lo; b < hi; b += kBatch) measure_batch<kShared>(b, std::min(hi, b + kBatch), p, with_f);
  }

  static constexpr std::size_t kBatch = 64;
  // Per triangle of a batch.
  struct Tri {
    Point2 a, b, c;
    double cr, q[3], lmin, lmax, radius;
    Point2 cc, cell;  // circumcentre; cell centre (when the triangle measures an edge)
    int o;
  };
  // Per interior edge of a batch (measured from its half-edge u -> w with u <= w).
  struct Edge {
    std::uint32_t i;  // triangle in the batch
    int k;
    Point2 ga, gb, gc, far;
  };
  Tri tri_[kBatch];
  Edge edge_[3 * kBatch];

  template <bool kShared>
  void measure_batch(std::size_t lo, std::size_t hi, Part& p, bool with_f) {
    const auto& T = m.triangles;
    const auto& V = m.vertices;
    const std::size_t n = hi - lo;
    // 1. Loads (corners, neighbours' corners). The next batch's corners and the one after's
    // neighbouring triangles are fetched now: the computations below hide their latency.
    std::size_t ne = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t t = lo + i;
      if (t + 2 * kBatch < T.size())
        for (int k = 0; k < 3; ++k)
          if (const Index g = nb[3 * (t + 2 * kBatch) + k]; g != kNoId) __builtin_prefetch(&T[g / 3]);
      if (t + kBatch < T.size()) {
        const auto& ahead = T[t + kBatch];
        for (int k = 0; k < 3; ++k) {
          __builtin_prefetch(&V[ahead[k]]);
          if (fv) __builtin_prefetch(&fv[ahead[k]]);
          __builtin_prefetch(&nn2[ahead[k]], 1);
          if (walk) __builtin_prefetch(&tov[ahead[k]], 1);
          const Index g = nb[3 * (t + kBatch) + k];
          if (g != kNoId) __builtin_prefetch(&V[T[g / 3][(g % 3 + 2) % 3]]);
        }
      }
      const auto& tr = T[t];
      Tri& x = tri_[i];
      x.a = V[tr[0]];
      x.b = V[tr[1]];
      x.c = V[tr[2]];
      for (int k = 0; k < 3; ++k) {
        const Index u = tr[k], w = tr[k == 2 ? 0 : k + 1];
        const Index g = nb[3 * t + k];
        if (!(u <= w && g != kNoId)) continue;
        const auto& tg = T[g / 3];
        Edge& e = edge_[ne++];
        e.i = static_cast<std::uint32_t>(i);
        e.k = k;
        e.ga = V[tg[0]];
        e.gb = V[tg[1]];
        e.gc = V[tg[2]];
        const int j = (g % 3 + 2) % 3;
        e.far = j == 0 ? e.ga : j == 1 ? e.gb : e.gc;
      }
    }
    // 2. Per triangle: orientation, lengths, circumcentre.
    for (std::size_t i = 0; i < n; ++i) {
      Tri& x = tri_[i];
      x.o = predicates::orient2d(x.a, x.b, x.c);
      const Point2 d = x.b - x.a, e = x.c - x.a;
      x.cr = d.x * e.y - d.y * e.x;  // twice the signed area
      // Squared edge lengths ab, bc, ca (norm2(x - y) == norm2(y - x) exactly).
      x.q[0] = norm2(d);
      x.q[1] = norm2(x.c - x.b);
      x.q[2] = norm2(e);
      sqrt2(std::min({x.q[0], x.q[1], x.q[2]}), std::max({x.q[0], x.q[1], x.q[2]}), x.lmin, x.lmax);
      double r2 = 0;
      x.cc = circumcentre(x.a, x.b, x.c, &r2);  // a zero determinant: R infinite
      x.radius = x.o != 0 && x.cr != 0 ? std::sqrt(r2) : kInf;
    }
    // 3. Per triangle: per-vertex bounds, angles, R/l, f.
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t t = lo + i;
      const auto& tr = T[t];
      const Tri& x = tri_[i];
      if (x.o == 0) ++p.q.degenerate_triangles;
      if (x.o < 0) ++p.q.inverted_triangles;
      if (x.o <= 0) p.ccw = false;
      if (with_f) el_over_f(tr, x.lmax);
      if (walk)
        for (int k = 0; k < 3; ++k) keep_corner<kShared>(tov[tr[k]], static_cast<Index>(t));
      for (int k = 0; k < 3; ++k) {  // an interior edge from one side (its twin w -> u has w < u)
        const Index u = tr[k], w = tr[k == 2 ? 0 : k + 1];
        if (u == w || (u > w && nb[3 * t + k] != kNoId)) continue;
        lower_to<kShared>(nn2[u], x.q[k]);
        lower_to<kShared>(nn2[w], x.q[k]);
      }
      const double l2max = std::max({x.q[0], x.q[1], x.q[2]});
      if (p.angles.fast(x.a, x.b, x.c, x.cr, p.q, l2max)) {
        if (per_triangle) per_triangle->min_angle_deg[t] = min_angle(x.a, x.b, x.c, x.cr, l2max);
      } else {
        const double ang[3] = {angle_at(x.a, x.b, x.c), angle_at(x.b, x.c, x.a), angle_at(x.c, x.a, x.b)};
        const double amin = std::min({ang[0], ang[1], ang[2]});
        if (per_triangle) per_triangle->min_angle_deg[t] = amin;
        const double amax = std::max({ang[0], ang[1], ang[2]});
        p.angles.update(p.q, amin, amax);
        p.q.min_angle_histogram.add(amin);
        p.q.max_angle_histogram.add(amax);
      }
      update_max(p.q.max_radius_edge, x.lmin > 0 ? x.radius / x.lmin : kInf);
      if (with_f) add_f(t, x.cr, x.radius, x.cc);
    }
    // 4. Per interior edge: the cell centres' link against the edge, the area ratio, the local
    // Delaunay check.
    for (std::size_t j = 0; j < ne; ++j)
      if (j == 0 || edge_[j].i != edge_[j - 1].i) {
        Tri& x = tri_[edge_[j].i];
        x.cell = cell_centre(x.a, x.b, x.c, x.cc);
      }
    double ortho[3 * kBatch], smooth[3 * kBatch];
    for (std::size_t j = 0; j < ne; ++j) {
      const Edge& e = edge_[j];
      const Tri& x = tri_[e.i];
      const Point2 cct = x.cell;
      const double at = 0.5 * std::fabs(x.cr);
      const Point2 ccu = cell_centre(e.ga, e.gb, e.gc, circumcentre(e.ga, e.gb, e.gc, nullptr));
      const double au = 0.5 * std::fabs((e.gb.x - e.ga.x) * (e.gc.y - e.ga.y) - (e.gb.y - e.ga.y) * (e.gc.x - e.ga.x));
      const Point2 u = e.k == 0 ? x.a : e.k == 1 ? x.b : x.c;
      const Point2 w = e.k == 0 ? x.b : e.k == 1 ? x.c : x.a;
      const Point2 ev = w - u, l = cct - ccu;
      double le, ll;
      sqrt2(norm2(ev), norm2(l), le, ll);
      const double len = le * ll;
      const double alo = std::min(at, au), ahi = std::max(at, au);
      double o, sm;  // both divided, the unusable one discarded
      div2(std::fabs(dot(ev, l)), len, ahi, alo, o, sm);
      ortho[j] = len > 0 ? o : 0.0;
      smooth[j] = alo > 0 ? sm : kInf;
    }
    if (walk)
      for (std::size_t j = 0; j < ne; ++j) {
        const Edge& e = edge_[j];
        const Tri& x = tri_[e.i];
        if (predicates::incircle(x.a, x.b, x.c, e.far) > 0)
          p.not_delaunay.push_back(static_cast<Index>(3 * (lo + e.i) + static_cast<std::size_t>(e.k)));
      }
    p.interior += ne;
    double omax = p.omax, smax = p.smax;  // in registers (the buffers' stores alias them)
    for (std::size_t j = 0; j < ne; ++j) {
      omax = std::max(omax, ortho[j]);
      smax = std::max(smax, smooth[j]);
      p.otop.add(ortho[j]);
      p.stop.add(smooth[j]);
    }
    p.omax = omax;
    p.smax = smax;
  }

  // The area and R/f(c) of the triangles [lo, hi) measured on another thread (calling thread).
  void evaluate(std::size_t lo, std::size_t hi) {
    const auto& T = m.triangles;
    const auto& V = m.vertices;
    for (std::size_t t = lo; t < hi; ++t) {
      if (t + 8 < hi)
        for (const Index v : T[t + 8]) {
          __builtin_prefetch(&V[v]);
          if (fv) __builtin_prefetch(&fv[v]);
        }
      const Point2 a = V[T[t][0]], b = V[T[t][1]], c = V[T[t][2]];
      const Point2 d = b - a, e = c - a;
      const double cr = d.x * e.y - d.y * e.x;
      if (fv) el_over_f(T[t], std::sqrt(std::max({norm2(d), norm2(c - b), norm2(e)})));
      if (!f) {
        add_f(t, cr, kInf, {});
        continue;
      }
      double r2 = 0;
      const Point2 cc = predicates::circumcenter(a, b, c, &r2);
      const double radius = cr != 0 && predicates::orient2d(a, b, c) != 0 ? std::sqrt(r2) : kInf;
      add_f(t, cr, radius, cc);
    }
  }
};

void merge(QualityReport& r, Part& all, Part& p) {
  r.degenerate_triangles += p.q.degenerate_triangles;
  r.inverted_triangles += p.q.inverted_triangles;
  if (p.q.min_angle_deg) update_min(r.min_angle_deg, *p.q.min_angle_deg);
  if (p.q.max_angle_deg) update_max(r.max_angle_deg, *p.q.max_angle_deg);
  for (std::size_t i = 0; i < r.min_angle_histogram.counts.size(); ++i)
    r.min_angle_histogram.counts[i] += p.q.min_angle_histogram.counts[i];
  for (std::size_t i = 0; i < r.max_angle_histogram.counts.size(); ++i)
    r.max_angle_histogram.counts[i] += p.q.max_angle_histogram.counts[i];
  if (p.q.max_radius_edge) update_max(r.max_radius_edge, *p.q.max_radius_edge);
  if (&all == &p) return;
  all.interior += p.interior;
  all.omax = std::max(all.omax, p.omax);
  all.smax = std::max(all.smax, p.smax);
  all.otop.values().insert(all.otop.values().end(), p.otop.values().begin(), p.otop.values().end());
  all.stop.values().insert(all.stop.values().end(), p.stop.values().begin(), p.stop.values().end());
  all.ccw = all.ccw && p.ccw;
}

}  // namespace

QualityReport compute_quality(const mesh::MeshView& m, const sizing::SizingField* f, double bound_B,
                              double alpha, const RunInfo& run, TriangleValues* per_triangle,
                              const std::vector<double>* f_at_vertices, std::vector<double>* fill_f_at_vertices) {
  StepLaps QL(debug::Aid::kReport, "  quality");  // developer aid (base/step_laps.hpp)
  QualityReport r;
  r.vertices = m.num_vertices();
  r.triangles = m.num_triangles();
  r.bound_B = bound_B;
  // An unknown alpha (negative) falls back to the field's own Lipschitz constant, if it knows one.
  if (!(alpha >= 0) && f != nullptr && f->lipschitz() >= 0) alpha = f->lipschitz();
  r.alpha = alpha;
  r.spacing = f ? f->describe() : (!run.spacing.empty() ? run.spacing : std::string("none"));
  r.guarantees = compute_guarantees(alpha, bound_B, run.conforming_D);
  r.run = run;

  const std::size_t nv = m.num_vertices(), nt = m.num_triangles();
  for (std::size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k)
      if (m.triangles[t][k] >= nv)
        throw Error(ExitCode::kInternal, "quality: triangle " + std::to_string(t) + " references vertex " +
                                             std::to_string(m.triangles[t][k]) + " but the mesh has " +
                                             std::to_string(nv) + " vertices");
  // The mesher's adjacency, else one built from the triangles (meshes read from files).
  const bool own_nb = m.neighbours.size() != 3 * nt;
  const std::vector<Index> built = own_nb ? half_edge_neighbours(m) : std::vector<Index>{};
  const std::vector<Index>& nb = own_nb ? built : m.neighbours;
  const bool walk = !own_nb && nv >= 2;  // nearest neighbours by walking the mesher's mesh

  if (f) r.bad_triangles = 0;
  if (per_triangle) {
    assign_huge(per_triangle->area, nt, 0.0);
    assign_huge(per_triangle->min_angle_deg, nt, 0.0);
    if (f) assign_huge(per_triangle->r_over_f, nt, kInf);
    else per_triangle->r_over_f.clear();
  }
  // f at the vertices, evaluated first on this thread (when not given): el(p)/f(p) is measured
  // per triangle.
  std::vector<double> own_fv;
  std::vector<double>* fill = fill_f_at_vertices;
  if (f && !fill && !(f_at_vertices && f_at_vertices->size() == nv)) fill = &own_fv;
  const bool two = max_threads() > 1 && nt >= 16384;
  MeshWalkPrep prep;
  // The per-vertex arrays, their fresh pages faulted in on two threads when there are two (about
  // 2 500 page faults at 0.5 M vertices, 8 ms or more on one thread on this project's machine).
  auto shortest = [&] { assign_huge(prep.nn2, nv, kInf); };
  auto f_and_corners = [&] {
    if (f && fill) resize_huge(*fill, nv);
    if (walk) assign_huge(prep.tri_of_vertex, nv, kNoId);
  };
  if (two) {
    run_beside(shortest, f_and_corners);
  } else {
    f_and_corners();
    shortest();
  }
  const double* fv = f ? (fill ? fill->data() : f_at_vertices->data()) : m.f.size() == nv ? m.f.data() : nullptr;
  // Each thread has its own batch buffers.
  auto pass_mine = std::make_unique<Pass>(Pass{m, nb, f, bound_B, per_triangle, walk, fv, prep.nn2, prep.tri_of_vertex, nullptr, 0, 0, {}, {}, {}, {}});
  Pass& pass = *pass_mine;

  // The triangles in chunks: the calling thread takes them from the front (with f), a second
  // thread from the back; the calling thread then evaluates f on the back chunks (in order). Both
  // cores stay busy whatever f costs, and the figures do not depend on where the split fell.
  // Over 1 % of the interior edges (at most 3/2 per triangle but for repeated vertices; else the
  // p99s are measured again below, as a sort would).
  const std::size_t top_k = 3 * nt / 200 + 4;
  Part mine(r, top_k);
  const std::size_t nchunks = (nt + kSumChunk - 1) / kSumChunk;
  auto chunk = [&](std::size_t c) { return std::pair{c * kSumChunk, std::min(nt, (c + 1) * kSumChunk)}; };
  std::vector<ChunkSums> chunk_sums(nchunks);
  pass.sums = chunk_sums.data();
  // A thread-safe f is evaluated by the thread that measures the triangle; another one only on
  // the calling thread (evaluate(), after the second thread's chunks are measured).
  const bool f_shared = f && f->thread_safe();
  std::size_t other_invalid = 0, other_bad = 0;
  std::optional<double> other_max_rf, other_el_f;
  std::optional<Part> theirs;
  // The nearest-neighbour search over the mesher's mesh, in vertex chunks claimed by both threads.
  std::optional<MeshNearestNeighbours> search;
  std::atomic<std::size_t> next_vertices{0};
  auto search_chunks = [&] {
    constexpr std::size_t kVertices = 8192;
    for (std::size_t lo; (lo = next_vertices.fetch_add(kVertices)) < nv;) search->search(lo, std::min(nv, lo + kVertices));
  };
  auto build_search = [&](const Part* other) {
    prep.not_delaunay = mine.not_delaunay;
    if (other) prep.not_delaunay.insert(prep.not_delaunay.end(), other->not_delaunay.begin(), other->not_delaunay.end());
    prep.ccw = mine.ccw && (!other || other->ccw);
    search.emplace(m, nb, prep);
  };
  if (two) {
    theirs.emplace(r, top_k);
    // Both threads lower the shared shortest edges (lower_to: an atomic minimum). Before, the
    // second thread kept its own copy, merged at the end: 8 bytes per vertex more at the report's
    // peak (64 MB at 16 M triangles) and a pass over both.
    auto other_pass = std::make_unique<Pass>(
        Pass{m, nb, f, bound_B, per_triangle, walk, fv, prep.nn2, prep.tri_of_vertex, nullptr, 0, 0, {}, {}, {}, {}});
    other_pass->sums = chunk_sums.data();
    std::unique_ptr<std::atomic<unsigned char>[]> claimed(new std::atomic<unsigned char>[nchunks]);
    for (std::size_t c = 0; c < nchunks; ++c) claimed[c].store(0, std::memory_order_relaxed);
    // The second thread reads f at the vertices when it evaluates f itself: filled first, in two
    // halves at once (a raster spacing costs ~60 ns per evaluation: 35 ms at 0.56 M vertices on
    // one thread while the other waited).
    bool filled = false;
    if (f_shared && fill) {
      auto fill_range = [&](std::size_t lo, std::size_t hi) {
        for (std::size_t i = lo; i < hi; ++i) (*fill)[i] = (*f)(m.vertices[i]);
      };
      run_beside([&] { fill_range(nv / 2, nv); }, [&] { fill_range(0, nv / 2); });
      filled = true;
    }
    // The second thread, done with its chunks, builds the search (once the calling thread is done
    // with its chunks: every triangle measured) while the calling thread evaluates f on the second
    // thread's chunks; then both search.
    std::latch mine_done(1), search_built(1);
    std::exception_ptr error;
    std::thread other([&] {
      bool built = false;
      try {
        for (std::size_t c = nchunks; c-- > 0;) {
          if (claimed[c].exchange(1)) break;  // met the calling thread
          const auto [lo, hi] = chunk(c);
          other_pass->measure<true>(lo, hi, *theirs, f_shared);
        }
        mine_done.wait();  // every triangle measured
        if (walk) {
          build_search(&*theirs);
          search_built.count_down();
          built = true;
          if (search->usable()) search_chunks();
        }
      } catch (...) {
        error = std::current_exception();
      }
      if (walk && !built) search_built.count_down();
    });
    struct Join {
      std::thread& t;
      std::latch& done;
      bool counted = false;
      void count() {
        if (!counted) done.count_down();
        counted = true;
      }
      ~Join() {
        count();  // also when f throws: the other thread must not wait for ever
        if (t.joinable()) t.join();
      }
    } join{other, mine_done};
    if (f && fill && !filled)
      for (std::size_t i = 0; i < nv; ++i) (*fill)[i] = (*f)(m.vertices[i]);
    QL("setup+fill");
    std::size_t c = 0;
    for (; c < nchunks && !claimed[c].exchange(1); ++c) {
      const auto [lo, hi] = chunk(c);
      pass.measure<true>(lo, hi, mine, true);
    }
    join.count();
    QL("my chunks");
    if (c < nchunks && !f_shared) pass.evaluate(chunk(c).first, nt);  // the other thread's chunks
    QL("evaluate");
    if (walk) {
      search_built.wait();
      QL("wait build");
      if (search && search->usable()) search_chunks();
    }
    other.join();
    QL("search");
    if (error) std::rethrow_exception(error);
    other_invalid = other_pass->spacing_invalid;
    other_bad = other_pass->bad;
    other_max_rf = other_pass->max_rf;
    other_el_f = other_pass->el_f_max;
  } else {
    if (f && fill)
      for (std::size_t i = 0; i < nv; ++i) (*fill)[i] = (*f)(m.vertices[i]);
    pass.measure<false>(0, nt, mine, true);
    if (walk) {
      build_search(nullptr);
      if (search->usable()) search->search(0, nv);
    }
  }
  if (f && fill) f_at_vertices = fill;
  merge(r, mine, mine);
  if (theirs) merge(r, mine, *theirs);
  {
    CompensatedSum area, rf;
    std::size_t count = 0;
    for (const ChunkSums& cs : chunk_sums) {
      area.add(cs.area.sum);
      area.add(cs.area.c);
      rf.add(cs.r_over_f.sum);
      rf.add(cs.r_over_f.c);
      count += cs.count;
    }
    r.area = area.value();
    if (count > 0) r.mean_R_over_f = rf.value() / static_cast<double>(count);
    r.spacing_invalid += pass.spacing_invalid + other_invalid;
    if (f) *r.bad_triangles += pass.bad + other_bad;
    if (pass.max_rf) update_max(r.max_R_over_f, *pass.max_rf);
    if (other_max_rf) update_max(r.max_R_over_f, *other_max_rf);
  }
  release_vector(chunk_sums);
  OrthogonalityStats& s = r.orthogonality;
  s.interior_edges = mine.interior;
  if (mine.interior > 0) {
    s.orthogonality_max = mine.omax;
    s.smoothness_max = mine.smax;
    s.orthogonality_p99 = quantile_from_top(mine.otop.values(), top_k, mine.interior, 0.99);
    s.smoothness_p99 = quantile_from_top(mine.stop.values(), top_k, mine.interior, 0.99);
    if (!s.orthogonality_p99 || !s.smoothness_p99) {
      const OrthogonalityStats all = compute_orthogonality(m, nb, nullptr);
      s.orthogonality_p99 = all.orthogonality_p99;
      s.smoothness_p99 = all.smoothness_p99;
    }
  }
  release_vector(mine.otop.values());
  release_vector(mine.stop.values());

  // Vertex metrics: nn(p) is exact over all vertices (not only mesh neighbours).
  std::vector<double> nn;
  if (search && search->usable()) nn = search->take();
  search.reset();
  if (!nn.empty()) {
    for (double& d : nn) d = std::sqrt(d);
  } else {
    // A global search (k-d tree) bounded by the mesh edges: exact, only slower.
    nn = std::move(prep.nn2);
    if (nv >= 2) {
      const KdTree tree(m.vertices, max_threads());
      for (std::size_t k = 0; k < tree.size(); ++k) {
        const Index i = tree.id_at(k);
        nn[i] = std::sqrt(tree.nearest_sq_at(k, nn[i]));
      }
    }
  }
  release_vector(prep.tri_of_vertex);
  QL("merge+p99+take");
  if (nv >= 2) r.nn_min = *std::min_element(nn.begin(), nn.end());
  const bool have_vertex_f = f != nullptr || m.f.size() == nv;
  if (!have_vertex_f || nv < 2) return r;
  r.el_over_f_max = pass.el_f_max;  // el(p) is defined at corners only
  if (other_el_f) update_max(r.el_over_f_max, *other_el_f);

  // Conformity nn(p)/f(p): with f at the vertices in an array, two halves of the vertices at once (merged in order; the compensated sum runs over every vertex in order on
  // this thread). p05 from the smallest 5 % (as negated largest values): no copy of every value.
  struct VertexPart {
    std::size_t invalid = 0, nconf = 0;
    std::optional<double> nn_over_f_min, conf_min;
    Histogram hist;
    TopK low;
  };
  auto vertices = [&](std::size_t lo, std::size_t hi, VertexPart& vp, CompensatedSum* sum) {
    for (std::size_t i = lo; i < hi; ++i) {
      const double fp = fv ? fv[i] : (*f)(m.vertices[i]);
      if (!usable_spacing(fp)) { ++vp.invalid; continue; }
      const double q = nn[i] / fp;
      const double ci = std::min(q, fp / nn[i]);  // nn = 0 (duplicate point) gives 0
      ++vp.nconf;
      vp.low.add(-ci);
      update_min(vp.conf_min, ci);
      if (sum) sum->add(ci);
      vp.hist.add(ci);
      update_min(vp.nn_over_f_min, q);
    }
  };
  std::vector<VertexPart> vparts(fv && max_threads() > 1 && nv >= 16384 ? 2 : 1,
                                 VertexPart{0, 0, {}, {}, r.conformity_histogram, TopK(nv / 20 + 4)});
  CompensatedSum conf_sum;
  const std::size_t half = vparts.size() == 2 ? nv / 2 : nv;
  if (vparts.size() == 2) {
    run_beside([&] { vertices(half, nv, vparts[1], nullptr); },
               [&] {
                 vertices(0, half, vparts[0], &conf_sum);
                 for (std::size_t i = half; i < nv; ++i)  // the sum in vertex order
                   if (usable_spacing(fv[i])) conf_sum.add(std::min(nn[i] / fv[i], fv[i] / nn[i]));
               });
  } else {
    vertices(0, nv, vparts[0], &conf_sum);
  }
  std::size_t nconf = 0;
  std::optional<double> conf_min;
  TopK& low = vparts[0].low;
  for (VertexPart& vp : vparts) {
    r.spacing_invalid += vp.invalid;
    nconf += vp.nconf;
    if (vp.nn_over_f_min) update_min(r.nn_over_f_min, *vp.nn_over_f_min);
    if (vp.conf_min) update_min(conf_min, *vp.conf_min);
    for (std::size_t b = 0; b < r.conformity_histogram.counts.size(); ++b)
      r.conformity_histogram.counts[b] += vp.hist.counts[b];
    if (&vp != &vparts[0]) low.values().insert(low.values().end(), vp.low.values().begin(), vp.low.values().end());
  }
  if (nconf > 0) {
    r.conformity_mean = conf_sum.value() / static_cast<double>(nconf);
    // p05 by nearest rank: the smallest value with at least 5 % of the vertices at or below it.
    const std::size_t rank = static_cast<std::size_t>(std::ceil(0.05 * static_cast<double>(nconf)));
    const std::size_t k = rank == 0 ? 0 : rank - 1;  // the k-th smallest is the (k+1)-th largest of -ci
    std::vector<double>& v = low.values();
    if (k + 1 > v.size()) throw Error(ExitCode::kInternal, "quality: percentile buffer too small");
    const auto at = v.end() - static_cast<std::ptrdiff_t>(k + 1);
    std::nth_element(v.begin(), at, v.end(), TopK::less);
    r.conformity_p05 = -*at;
    r.conformity_min = conf_min;
  }
  QL("conformity");

  return r;
}

// ---------------------------------------------------------------- writers

namespace {

using Json = nlohmann::ordered_json;
constexpr const char* kRepairsPlaceholder = "\x01" "fdrmesh repairs" "\x01";

Json num(std::optional<double> v) {
  if (!v || !std::isfinite(*v)) return nullptr;
  return *v;
}
Json num(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }
Json count(std::optional<std::size_t> v) { return v ? Json(*v) : Json(nullptr); }

Json histogram_json(const Histogram& h) {
  Json j;
  // Integral widths (5 degrees) are written as integers: {"bin_deg": 5}.
  if (h.width == std::floor(h.width)) j["bin_deg"] = static_cast<long long>(h.width);
  else j["bin_deg"] = h.width;
  j["from_deg"] = h.lo;
  j["counts"] = h.counts;
  return j;
}

}  // namespace

void write_json(const QualityReport& r, std::ostream& out) {
  Json j;
  j["vertices"] = r.vertices;
  j["triangles"] = r.triangles;
  j["min_angle_deg"] = num(r.min_angle_deg);
  j["max_angle_deg"] = num(r.max_angle_deg);
  j["max_radius_edge"] = num(r.max_radius_edge);
  j["max_R_over_f"] = num(r.max_R_over_f);
  j["mean_R_over_f"] = num(r.mean_R_over_f);
  j["bad_triangles"] = count(r.bad_triangles);
  j["exempt_small_angle_triangles"] = r.run.exempt_small_angle_triangles;
  j["conformity"] = {{"min", num(r.conformity_min)}, {"mean", num(r.conformity_mean)},
                     {"p05", num(r.conformity_p05)}};
  j["el_over_f_max"] = num(r.el_over_f_max);
  if (r.vertical_error_max_m) {
    j["vertical_error_max_m"] = num(r.vertical_error_max_m);
    j["vertical_error_rms_m"] = num(r.vertical_error_rms_m);
  }
  j["nn_over_f_min"] = num(r.nn_over_f_min);
  j["orthogonality"] = {{"max", num(r.orthogonality.orthogonality_max)}, {"p99", num(r.orthogonality.orthogonality_p99)}};
  j["smoothness"] = {{"max", num(r.orthogonality.smoothness_max)}, {"p99", num(r.orthogonality.smoothness_p99)}};
  j["min_angle_histogram"] = histogram_json(r.min_angle_histogram);
  j["max_angle_histogram"] = histogram_json(r.max_angle_histogram);
  {
    Json h;
    h["bin"] = r.conformity_histogram.width;
    h["counts"] = r.conformity_histogram.counts;
    j["conformity_histogram"] = h;
  }
  j["timings_s"] = {{"cdt", num(r.run.cdt_s)}, {"refine", num(r.run.refine_s)},
                    {"write", num(r.run.write_s)}, {"total", num(r.run.total_s)}};
  j["peak_rss_mb"] = num(r.run.peak_rss_mb);
  j["predicate_calls"] = {{"filtered", r.run.predicate_filtered}, {"exact", r.run.predicate_exact}};
  j["steiner_points"] = {{"segment", r.run.steiner_segment}, {"interior", r.run.steiner_interior},
                         {"total", r.run.steiner_total()}};
  j["area"] = num(r.area);
  j["degenerate_triangles"] = r.degenerate_triangles;
  j["inverted_triangles"] = r.inverted_triangles;
  j["nn_min"] = num(r.nn_min);
  j["spacing_invalid_evaluations"] = r.spacing_invalid;
  j["bound_B"] = num(r.bound_B);
  j["alpha"] = r.alpha >= 0 ? num(r.alpha) : Json(nullptr);
  j["spacing"] = r.spacing;
  j["input_file"] = r.run.input_file;
  j["min_angle_option_deg"] = num(r.run.min_angle_option_deg);
  // The repairs (up to hundreds of thousands on real coasts) are streamed below instead of held as
  // one document: a placeholder marks their place.
  j["repairs"] = kRepairsPlaceholder;
  const Guarantees& g = r.guarantees;
  auto gv = [&](double v) { return g.valid ? num(v) : Json(nullptr); };
  j["guarantees"] = {{"beta", gv(g.beta)},
                     {"beta_B", gv(g.beta_B)},
                     {"beta_D", g.valid && g.beta_D ? num(*g.beta_D) : Json(nullptr)},
                     {"conforming_D", r.run.conforming_D ? num(*r.run.conforming_D) : Json(nullptr)},
                     {"conforming_D_at", r.run.conforming_D ? Json::array({num(r.run.conforming_D_at.x), num(r.run.conforming_D_at.y)})
                                                            : Json(nullptr)},
                     {"R_over_l_max", gv(g.R_over_l_max)},
                     {"min_angle_deg", gv(g.min_angle_deg)},
                     {"nn_over_f_min", gv(g.nn_over_f_min)},
                     {"el_over_f_max", gv(g.el_over_f_max)},
                     {"el_over_f_max_corrected", gv(g.el_over_f_max_corrected)},
                     {"valid", guarantees_hold(r)},  // applicable and every counted bound holds
                     {"applicable", g.valid},
                     {"note", g.note}};
  for (const auto& c : theorem_checks(r))
    j["guarantees"][c.key] = {{"relation", c.upper ? "<=" : ">="}, {"bound", num(c.bound)},
                              {"measured", num(c.measured)},
                              {"holds", c.holds ? Json(*c.holds) : Json(nullptr)},
                              {"counts_for_valid", c.counts}};
  j["measured"] = {{"R_over_l_max", num(r.max_radius_edge)},
                   {"min_angle_deg", num(r.min_angle_deg)},
                   {"nn_over_f_min", num(r.nn_over_f_min)},
                   {"el_over_f_max", num(r.el_over_f_max)}};
  if (r.model_ready) j["model_ready"] = model_ready_json(*r.model_ready);
  const std::string text = j.dump(2);
  const std::string mark = Json(kRepairsPlaceholder).dump();
  const std::size_t at = text.find(mark);
  if (at == std::string::npos) throw Error(ExitCode::kInternal, "quality: report JSON without its repairs");
  out.write(text.data(), static_cast<std::streamsize>(at));
  // Pretty printing nests: a repair object printed on its own with indent 2, its lines after
  // the first shifted by its depth (4 spaces), is the text the whole document would hold.
  if (r.repairs.empty()) {
    out << "[]";
  } else {
    out << "[\n";
    std::string obj;
    for (std::size_t i = 0; i < r.repairs.size(); ++i) {
      const auto& rp = r.repairs[i];
      obj = Json({{"kind", rp.kind}, {"x", num(rp.x)}, {"y", num(rp.y)}, {"ids", rp.ids}, {"reason", rp.reason}}).dump(2);
      out << "    ";
      std::size_t from = 0;
      for (std::size_t nl = obj.find('\n'); nl != std::string::npos; nl = obj.find('\n', from)) {
        out.write(obj.data() + from, static_cast<std::streamsize>(nl + 1 - from));
        out << "    ";
        from = nl + 1;
      }
      out.write(obj.data() + from, static_cast<std::streamsize>(obj.size() - from));
      out << (i + 1 < r.repairs.size() ? ",\n" : "\n");
    }
    out << "  ]";
  }
  out.write(text.data() + at + mark.size(), static_cast<std::streamsize>(text.size() - at - mark.size()));
  out << '\n';
}

namespace {

std::string fmt(std::optional<double> v, const char* spec = "%.6g") {
  if (!v) return "n/a";
  if (std::isinf(*v)) return *v > 0 ? "inf" : "-inf";
  if (std::isnan(*v)) return "nan";
  char buf[64];
  std::snprintf(buf, sizeof buf, spec, *v);
  return buf;
}

void line(std::ostream& out, const char* label, const std::string& value) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "  %-30s: ", label);
  out << buf << value << '\n';
}

}  // namespace

void write_text(const QualityReport& r, std::ostream& out) {
  out << "Mesh quality\n";
  if (!r.run.input_file.empty()) line(out, "input", r.run.input_file);
  line(out, "spacing f", r.spacing);
  line(out, "vertices / triangles", std::to_string(r.vertices) + " / " + std::to_string(r.triangles));
  line(out, "area", fmt(r.area, "%.10g"));
  if (r.degenerate_triangles || r.inverted_triangles) {
    line(out, "degenerate / inverted", std::to_string(r.degenerate_triangles) + " / " +
                                           std::to_string(r.inverted_triangles));
  }
  line(out, "angle min / max (deg)", fmt(r.min_angle_deg, "%.4f") + " / " + fmt(r.max_angle_deg, "%.4f"));
  line(out, "max radius-edge R/l", fmt(r.max_radius_edge, "%.4f"));
  line(out, "orthogonality max / p99", fmt(r.orthogonality.orthogonality_max, "%.3g") + " / " +
                                           fmt(r.orthogonality.orthogonality_p99, "%.3g"));
  line(out, "smoothness max / p99", fmt(r.orthogonality.smoothness_max, "%.4f") + " / " +
                                        fmt(r.orthogonality.smoothness_p99, "%.4f"));
  if (r.max_R_over_f) {
    line(out, "R/f(c) max / mean", fmt(r.max_R_over_f, "%.4f") + " / " + fmt(r.mean_R_over_f, "%.4f"));
    line(out, "bad triangles (R/f(c) > B)", std::to_string(*r.bad_triangles) + "  (B = " + fmt(r.bound_B) + ")");
  }
  if (r.conformity_min) {
    line(out, "conformity min / mean / p05", fmt(r.conformity_min, "%.4f") + " / " +
                                                 fmt(r.conformity_mean, "%.4f") + " / " +
                                                 fmt(r.conformity_p05, "%.4f"));
    line(out, "nn/f min, el/f max", fmt(r.nn_over_f_min, "%.4f") + ", " + fmt(r.el_over_f_max, "%.4f"));
    if (r.vertical_error_max_m)
      line(out, "TIN vs DEM error max / RMS (m)",
           fmt(r.vertical_error_max_m, "%.3f") + " / " + fmt(r.vertical_error_rms_m, "%.3f"));
  }
  if (r.spacing_invalid) line(out, "f <= 0 or not finite (skipped)", std::to_string(r.spacing_invalid));
  line(out, "exempt small-angle triangles", std::to_string(r.run.exempt_small_angle_triangles));
  line(out, "Steiner points seg/interior", std::to_string(r.run.steiner_segment) + " / " +
                                                 std::to_string(r.run.steiner_interior));
  line(out, "time s cdt/refine/write/total",
       fmt(r.run.cdt_s, "%.3f") + " / " + fmt(r.run.refine_s, "%.3f") + " / " + fmt(r.run.write_s, "%.3f") +
           " / " + fmt(r.run.total_s, "%.3f"));
  line(out, "peak RSS (MB)", fmt(r.run.peak_rss_mb, "%.1f"));
  line(out, "predicates filtered / exact",
       std::to_string(r.run.predicate_filtered) + " / " + std::to_string(r.run.predicate_exact));

  // Triangle-style histogram: min angles with a bar, max angles as a compact second column.
  out << "\n  Min-angle histogram" << std::string(32, ' ') << "| Max-angle histogram\n";
  std::uint64_t peak = 1;
  for (auto c : r.min_angle_histogram.counts) peak = std::max(peak, c);
  const auto& hmin = r.min_angle_histogram;
  const auto& hmax = r.max_angle_histogram;
  const std::size_t rows = std::max(hmin.counts.size(), (hmax.counts.size() + 1) / 2);
  for (std::size_t i = 0; i < rows; ++i) {
    char left[80] = "";
    if (i < hmin.counts.size()) {
      const double lo = hmin.lo + static_cast<double>(i) * hmin.width;
      const int bar = static_cast<int>(std::lround(24.0 * static_cast<double>(hmin.counts[i]) /
                                                   static_cast<double>(peak)));
      std::snprintf(left, sizeof left, "  %3.0f - %3.0f deg: %10llu %-24s", lo, lo + hmin.width,
                    static_cast<unsigned long long>(hmin.counts[i]), std::string(bar, '#').c_str());
    }
    out << left;
    // Two max-angle bins per row keep the table as tall as the min-angle one.
    for (std::size_t k = 2 * i; k < 2 * i + 2 && k < hmax.counts.size(); ++k) {
      const double lo = hmax.lo + static_cast<double>(k) * hmax.width;
      char right[64];
      std::snprintf(right, sizeof right, " | %3.0f-%3.0f: %9llu", lo, lo + hmax.width,
                    static_cast<unsigned long long>(hmax.counts[k]));
      out << right;
    }
    out << '\n';
  }

  if (r.model_ready) write_model_ready_text(*r.model_ready, out);

  const Guarantees& g = r.guarantees;
  out << "\n  Theory vs measured (alpha = " << (r.alpha >= 0 ? fmt(r.alpha) : std::string("unknown"))
      << ", B = " << fmt(r.bound_B) << ")\n";
  if (!g.valid) out << "    " << g.note << '\n';
  else out << "    beta = " << fmt(g.beta, "%.6f") << "; " << g.note << '\n';
  if (g.valid && r.run.conforming_D) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "    D = min nn/f of the conforming mesh = %.4g at (%.1f, %.1f); beta_B = %.6f, beta_D = %.6f\n",
                  *r.run.conforming_D, r.run.conforming_D_at.x, r.run.conforming_D_at.y, g.beta_B, g.beta_D.value_or(0));
    out << buf;
  }
  const auto checks = theorem_checks(r);
  if (!checks.empty()) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "    %-22s %-4s %12s %12s  %s\n", "quantity", "", "theory", "measured", "holds");
    out << buf;
    for (const auto& c : checks) {
      const char* ok = !c.holds ? "n/a" : *c.holds ? "yes" : (c.counts ? "NO" : "no (printed bound)");
      std::snprintf(buf, sizeof buf, "    %-22s %-4s %12s %12s  %s\n", c.label, c.upper ? "<=" : ">=",
                    fmt(c.bound, "%.4f").c_str(), fmt(c.measured, "%.4f").c_str(), ok);
      out << buf;
    }
    if (g.valid) out << "    all bounds hold: " << (guarantees_hold(r) ? "yes" : "NO") << '\n';
  }
}

void write_json_file(const QualityReport& r, const std::string& path) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    if (!out) throw Error(ExitCode::kOutputError, path + ": cannot write");
    write_json(r, out);
    out.flush();
    if (!out) {
      out.close();
      std::remove(tmp.c_str());
      throw Error(ExitCode::kOutputError, path + ": write failed");
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw Error(ExitCode::kOutputError, path + ": cannot rename the temporary file");
  }
}

}  // namespace fdr::quality
