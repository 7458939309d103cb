// The report's pass over the triangles (see triangle_pass.hpp).
#include "base/prefetch.hpp"
#include "quality/triangle_pass.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include "base/triangle_geometry.hpp"
#include "predicates/predicates.hpp"
#include "quality/cell_centre.hpp"

namespace fdr::quality {
namespace {

// A triangle with that corner, where the nearest-neighbour walk starts (any one gives the same
// distances: the walk is exact from each of them). Two threads may store it in either order.
template <bool kShared>
inline void keep_corner(Index& x, Index t) {
  if constexpr (kShared) std::atomic_ref<Index>(x).store(t, std::memory_order_relaxed);
  else x = t;
}

// x = min(x, v); with several threads at once an atomic minimum (a compare-exchange only when v
// is smaller: a vertex's shortest edge improves a few times among its ~6 edges). The result is
// the minimum whatever the order. NaN never lowers it, as with std::min(x, NaN).
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

}  // namespace

PassFigures::PassFigures(const QualityReport& r, std::size_t top_k)
    : angles(r.min_angle_histogram, r.max_angle_histogram), otop(top_k), stop(top_k) {
  q.min_angle_histogram = r.min_angle_histogram;
  q.max_angle_histogram = r.max_angle_histogram;
}

void PassFigures::absorb(PassFigures& o) {
  q.degenerate_triangles += o.q.degenerate_triangles;
  q.inverted_triangles += o.q.inverted_triangles;
  if (o.q.min_angle_deg) update_min(q.min_angle_deg, *o.q.min_angle_deg);
  if (o.q.max_angle_deg) update_max(q.max_angle_deg, *o.q.max_angle_deg);
  for (std::size_t i = 0; i < q.min_angle_histogram.counts.size(); ++i)
    q.min_angle_histogram.counts[i] += o.q.min_angle_histogram.counts[i];
  for (std::size_t i = 0; i < q.max_angle_histogram.counts.size(); ++i)
    q.max_angle_histogram.counts[i] += o.q.max_angle_histogram.counts[i];
  if (o.q.max_radius_edge) update_max(q.max_radius_edge, *o.q.max_radius_edge);
  interior += o.interior;
  omax = std::max(omax, o.omax);
  smax = std::max(smax, o.smax);
  otop.absorb(o.otop);
  stop.absorb(o.stop);
  not_delaunay.insert(not_delaunay.end(), o.not_delaunay.begin(), o.not_delaunay.end());
  ccw = ccw && o.ccw;
  spacing_invalid += o.spacing_invalid;
  bad += o.bad;
  if (o.max_rf) update_max(max_rf, *o.max_rf);
  if (o.el_f_max) update_max(el_f_max, *o.el_f_max);
}

void TrianglePass::el_over_f(const std::array<Index, 3>& tr, double lmax) {
  if (!in_.fv) return;
  const double l = std::max(0.0, lmax);  // el starts at 0 (a NaN length counts as 0)
  // The largest l / f(v) over the usable corners is l / (their smallest f): a correctly rounded
  // division is monotone in its divisor, so the value is the same, with one division.
  double fmin = kInf;
  for (const Index v : tr)
    if (usable_spacing(in_.fv[v])) fmin = std::min(fmin, in_.fv[v]);
  if (fmin < kInf) update_max(fig.el_f_max, l / fmin);
}

void TrianglePass::add_f(std::size_t t, double cr, double radius, Point2 center) {
  ChunkSums& cs = in_.sums[t / kSumChunk];
  cs.area.add(0.5 * cr);
  if (in_.per_triangle) in_.per_triangle->area[t] = 0.5 * cr;
  if (!in_.f) return;
  double ratio = kInf;
  if (std::isfinite(radius)) {
    const double fc = (*in_.f)(center);
    if (in_.per_triangle) in_.per_triangle->r_over_f[t] = geom::r_over_f(radius, fc);
    if (!usable_spacing(fc)) {
      ++fig.spacing_invalid;
      return;
    }
    ratio = geom::r_over_f(radius, fc);
  }
  update_max(fig.max_rf, ratio);
  cs.r_over_f.add(ratio);
  ++cs.count;
  if (ratio > in_.bound_B) ++fig.bad;
}

// In batches: the scattered loads first, then each computation in its own short loop over the
// batch, so that the divisions and square roots of different triangles overlap (the same
// operations on the same values as one triangle at a time).
template <bool kShared>
void TrianglePass::measure(std::size_t lo, std::size_t hi, bool with_f) {
  for (std::size_t b = lo; b < hi; b += kBatch) measure_batch<kShared>(b, std::min(hi, b + kBatch), with_f);
}
template void TrianglePass::measure<true>(std::size_t, std::size_t, bool);
template void TrianglePass::measure<false>(std::size_t, std::size_t, bool);

template <bool kShared>
void TrianglePass::measure_batch(std::size_t lo, std::size_t hi, bool with_f) {
  const std::size_t n = hi - lo;
  const std::size_t ne = load_batch(lo, n);
  shape_batch(n);
  triangles_batch<kShared>(lo, n, with_f);
  edges_batch(lo, ne);
}

// The corners of the batch's triangles and of their neighbours across the interior edges each
// measures; returns the number of those edges. The next batch's corners and the one after's
// neighbouring triangles are fetched now: the computations hide their latency.
std::size_t TrianglePass::load_batch(std::size_t lo, std::size_t n) {
  const auto& T = in_.m.triangles;
  const auto& V = in_.m.vertices;
  const auto& nb = in_.nb;
  std::size_t ne = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t t = lo + i;
    if (t + 2 * kBatch < T.size())
      for (int k = 0; k < 3; ++k)
        if (const Index g = nb[3 * (t + 2 * kBatch) + k]; g != kNoId) fdr::prefetch(&T[g / 3]);
    if (t + kBatch < T.size()) {
      const auto& ahead = T[t + kBatch];
      for (int k = 0; k < 3; ++k) {
        fdr::prefetch(&V[ahead[k]]);
        if (in_.fv) fdr::prefetch(&in_.fv[ahead[k]]);
        fdr::prefetch_for_write(&in_.nn2[ahead[k]]);
        if (in_.walk) fdr::prefetch_for_write(&in_.tov[ahead[k]]);
        const Index g = nb[3 * (t + kBatch) + k];
        if (g != kNoId) fdr::prefetch(&V[T[g / 3][(g % 3 + 2) % 3]]);
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
  return ne;
}

// Per triangle: orientation, edge lengths, circumcentre and radius (+inf when degenerate).
void TrianglePass::shape_batch(std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    Tri& x = tri_[i];
    x.o = predicates::orient2d(x.a, x.b, x.c);
    x.cr = geom::cross2(x.a, x.b, x.c);
    const geom::EdgeLengths2 q = geom::edge_lengths2(x.a, x.b, x.c);
    x.q[0] = q.ab;
    x.q[1] = q.bc;
    x.q[2] = q.ca;
    x.lmin = std::sqrt(q.min());
    x.lmax = std::sqrt(q.max());
    double r2 = 0;
    x.cc = geom::circumcentre(x.a, x.b, x.c, &r2);
    x.radius = x.o != 0 ? geom::circumradius(r2, x.cr) : kInf;
  }
}

// Per triangle: orientation counts, per-vertex bounds, angles, R/l, and with f the sums.
template <bool kShared>
void TrianglePass::triangles_batch(std::size_t lo, std::size_t n, bool with_f) {
  const auto& T = in_.m.triangles;
  TriangleValues* pt = in_.per_triangle;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t t = lo + i;
    const auto& tr = T[t];
    const Tri& x = tri_[i];
    if (x.o == 0) ++fig.q.degenerate_triangles;
    if (x.o < 0) ++fig.q.inverted_triangles;
    if (x.o <= 0) fig.ccw = false;
    if (with_f) el_over_f(tr, x.lmax);
    if (in_.walk)
      for (int k = 0; k < 3; ++k) keep_corner<kShared>(in_.tov[tr[k]], static_cast<Index>(t));
    for (int k = 0; k < 3; ++k) {  // an interior edge from one side (its twin w -> u has w < u)
      const Index u = tr[k], w = tr[k == 2 ? 0 : k + 1];
      if (u == w || (u > w && in_.nb[3 * t + k] != kNoId)) continue;
      lower_to<kShared>(in_.nn2[u], x.q[k]);
      lower_to<kShared>(in_.nn2[w], x.q[k]);
    }
    const double l2max = std::max({x.q[0], x.q[1], x.q[2]});
    if (fig.angles.fast(x.a, x.b, x.c, x.cr, fig.q, l2max)) {
      if (pt) pt->min_angle_deg[t] = geom::min_angle_deg(x.a, x.b, x.c, x.cr, l2max);
    } else {
      const double ang[3] = {geom::angle_deg(x.a, x.b, x.c), geom::angle_deg(x.b, x.c, x.a),
                             geom::angle_deg(x.c, x.a, x.b)};
      const double amin = std::min({ang[0], ang[1], ang[2]});
      if (pt) pt->min_angle_deg[t] = amin;
      fig.angles.add(fig.q, amin, std::max({ang[0], ang[1], ang[2]}));
    }
    update_max(fig.q.max_radius_edge, geom::radius_edge_ratio(x.radius, x.lmin));
    if (with_f) add_f(t, x.cr, x.radius, x.cc);
  }
}

// Per interior edge: the cell centres' link against the edge (orthogonality), the area ratio
// (smoothness), the local Delaunay check.
void TrianglePass::edges_batch(std::size_t lo, std::size_t ne) {
  for (std::size_t j = 0; j < ne; ++j)
    if (j == 0 || edge_[j].i != edge_[j - 1].i) {
      Tri& x = tri_[edge_[j].i];
      x.cell = cell_centre(x.a, x.b, x.c, x.cc);
    }
  double ortho[3 * kBatch], smooth[3 * kBatch];
  for (std::size_t j = 0; j < ne; ++j) {
    const Edge& e = edge_[j];
    const Tri& x = tri_[e.i];
    const double at = 0.5 * std::fabs(x.cr);
    const Point2 ccu = cell_centre(e.ga, e.gb, e.gc, geom::circumcentre(e.ga, e.gb, e.gc));
    const double au = 0.5 * std::fabs(geom::cross2(e.ga, e.gb, e.gc));
    const Point2 u = e.k == 0 ? x.a : e.k == 1 ? x.b : x.c;
    const Point2 w = e.k == 0 ? x.b : e.k == 1 ? x.c : x.a;
    const Point2 ev = w - u, l = x.cell - ccu;
    const double len = std::sqrt(norm2(ev)) * std::sqrt(norm2(l));
    const double alo = std::min(at, au), ahi = std::max(at, au);
    ortho[j] = len > 0 ? std::fabs(dot(ev, l)) / len : 0.0;
    smooth[j] = alo > 0 ? ahi / alo : kInf;
  }
  if (in_.walk)
    for (std::size_t j = 0; j < ne; ++j) {
      const Edge& e = edge_[j];
      const Tri& x = tri_[e.i];
      if (predicates::incircle(x.a, x.b, x.c, e.far) > 0)
        fig.not_delaunay.push_back(static_cast<Index>(3 * (lo + e.i) + static_cast<std::size_t>(e.k)));
    }
  fig.interior += ne;
  double omax = fig.omax, smax = fig.smax;  // in registers (the buffers' stores alias them)
  for (std::size_t j = 0; j < ne; ++j) {
    omax = std::max(omax, ortho[j]);
    smax = std::max(smax, smooth[j]);
    fig.otop.add(ortho[j]);
    fig.stop.add(smooth[j]);
  }
  fig.omax = omax;
  fig.smax = smax;
}

void TrianglePass::evaluate(std::size_t lo, std::size_t hi) {
  const auto& T = in_.m.triangles;
  const auto& V = in_.m.vertices;
  for (std::size_t t = lo; t < hi; ++t) {
    if (t + 8 < hi)
      for (const Index v : T[t + 8]) {
        fdr::prefetch(&V[v]);
        if (in_.fv) fdr::prefetch(&in_.fv[v]);
      }
    const Point2 a = V[T[t][0]], b = V[T[t][1]], c = V[T[t][2]];
    const double cr = geom::cross2(a, b, c);
    if (in_.fv) el_over_f(T[t], std::sqrt(geom::edge_lengths2(a, b, c).max()));
    if (!in_.f) {
      add_f(t, cr, kInf, {});
      continue;
    }
    double r2 = 0;
    const Point2 cc = geom::circumcentre(a, b, c, &r2);
    const double radius = cr == 0 || predicates::orient2d(a, b, c) == 0 ? kInf : geom::circumradius(r2, cr);
    add_f(t, cr, radius, cc);
  }
}

}  // namespace fdr::quality
