// Model readiness of a final mesh: edges against hmin, skinny triangles, mean quality,
// coast deviation both ways, connected pieces, gravity-wave time step, removed features.
// Measurements only (double precision); no combinatorial decision is taken here.
#include "base/prefetch.hpp"
#include "quality/compensated_sum.hpp"
#include "quality/text_format.hpp"
#include "quality/model_ready.hpp"

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <numeric>
#include <ostream>
#include <string>
#include <nlohmann/json.hpp>

#include "base/error.hpp"
#include "base/parallel.hpp"
#include "base/triangle_geometry.hpp"
#include "base/step_laps.hpp"

namespace fdr::quality {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kGravity = 9.81;                   // m/s^2
const double kCos20 = std::cos(20.0 * std::numbers::pi / 180.0);
const double kCos30 = std::cos(30.0 * std::numbers::pi / 180.0);
constexpr std::size_t kMaxSamples = 4'000'000;      // cap on coast-deviation samples per direction

// Twice the signed area of triangle p[0] p[1] p[2], and its mean-ratio quality (unsigned): one
// definition for every path (the sums must agree bit for bit).
inline double cross2(const Point2 (&p)[3]) { return geom::cross2(p[0], p[1], p[2]); }
inline double quality_of(const Point2 (&p)[3]) { return std::fabs(geom::mean_ratio_quality(p[0], p[1], p[2])); }

// Uniform grid over segments for nearest-segment distance queries. Each segment is cut into
// pieces no longer than a cell and registered in the (at most 2x2) cells of each piece's box, so
// that every cell lists every segment passing through it. A query searches square rings of cells
// around the query's cell and stops once the next ring cannot hold anything nearer.
class SegmentGrid {
 public:
  explicit SegmentGrid(const std::vector<std::pair<Point2, Point2>>& segs) : segs_(segs) {
    if (segs.empty()) return;
    Box2 box;
    double total = 0;
    for (const auto& [a, b] : segs) {
      box.add(a);
      box.add(b);
      total += dist(a, b);
    }
    lo_ = box.lo;
    const double n = static_cast<double>(segs.size());
    const double w = box.width(), h = box.height();
    // Cells about as long as the segments, at most about 16 per segment (a coast fills few of
    // the cells of its box; the queries lie near it and mostly end in their own cell).
    cell_ = std::max(total / n, std::sqrt(w * h / (16.0 * n)));
    if (!(cell_ > 0) || !std::isfinite(cell_)) cell_ = std::max({w, h, 1.0});
    for (int guard = 0; guard < 200; ++guard) {
      nx_ = static_cast<std::size_t>(w / cell_) + 1;
      ny_ = static_cast<std::size_t>(h / cell_) + 1;
      if (static_cast<double>(nx_) * static_cast<double>(ny_) <= 16.0 * n + 16.0) break;
      cell_ *= 1.5;
    }
    start_.assign(nx_ * ny_ + 1, 0);
    std::vector<std::uint32_t> last(nx_ * ny_, std::numeric_limits<std::uint32_t>::max());
    // Two passes over the same enumeration: count per cell, then fill (CSR).
    auto each = [&](auto&& visit) {
      std::fill(last.begin(), last.end(), std::numeric_limits<std::uint32_t>::max());
      for (std::size_t s = 0; s < segs.size(); ++s) {
        const Point2 a = segs[s].first, b = segs[s].second;
        const double len = dist(a, b);
        const std::size_t k = std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(len / cell_)));
        for (std::size_t i = 0; i < k; ++i) {
          const Point2 p = a + (static_cast<double>(i) / static_cast<double>(k)) * (b - a);
          const Point2 q = i + 1 == k ? b : a + (static_cast<double>(i + 1) / static_cast<double>(k)) * (b - a);
          const std::size_t i0 = ix(std::min(p.x, q.x)), i1 = ix(std::max(p.x, q.x));
          const std::size_t j0 = iy(std::min(p.y, q.y)), j1 = iy(std::max(p.y, q.y));
          for (std::size_t j = j0; j <= j1; ++j)
            for (std::size_t ii = i0; ii <= i1; ++ii) {
              const std::size_t c = j * nx_ + ii;
              if (last[c] == s) continue;
              last[c] = static_cast<std::uint32_t>(s);
              visit(c, static_cast<std::uint32_t>(s));
            }
        }
      }
    };
    each([&](std::size_t c, std::uint32_t) { ++start_[c + 1]; });
    for (std::size_t c = 0; c < nx_ * ny_; ++c) start_[c + 1] += start_[c];
    items_.resize(start_.back());
    std::vector<std::size_t> cursor(start_.begin(), start_.end() - 1);
    each([&](std::size_t c, std::uint32_t s) { items_[cursor[c]++] = s; });
  }

  // Distance from q to the nearest segment (+inf without segments).
  double nearest(Point2 q) const {
    if (segs_.empty()) return kInf;
    const std::size_t ci = ix(q.x), cj = iy(q.y);
    double best2 = kInf;
    const std::size_t rmax = std::max(nx_, ny_);
    for (std::size_t r = 0; r <= rmax; ++r) {
      // Cells of Chebyshev ring r around (ci, cj), clipped to the grid.
      const long long i_lo = static_cast<long long>(ci) - static_cast<long long>(r);
      const long long i_hi = static_cast<long long>(ci) + static_cast<long long>(r);
      const long long j_lo = static_cast<long long>(cj) - static_cast<long long>(r);
      const long long j_hi = static_cast<long long>(cj) + static_cast<long long>(r);
      for (long long j = std::max(0LL, j_lo); j <= std::min<long long>(j_hi, static_cast<long long>(ny_) - 1); ++j) {
        const bool edge_row = j == j_lo || j == j_hi;
        for (long long i = std::max(0LL, i_lo); i <= std::min<long long>(i_hi, static_cast<long long>(nx_) - 1);) {
          scan(static_cast<std::size_t>(j) * nx_ + static_cast<std::size_t>(i), q, best2);
          // Inside the ring only its left and right columns belong to it.
          if (edge_row || i == i_hi) ++i;
          else i = i_hi;
        }
      }
      // The cells not scanned yet lie beyond the sides of the square of rings 0..r that have
      // cells beyond them, at least that far from q (q inside the square, or outside the grid on
      // a side without cells beyond). Rounding: ~1e-16 of the coordinates, far inside the slack.
      double reach = kInf;
      const double sx0 = lo_.x + static_cast<double>(i_lo) * cell_, sx1 = lo_.x + static_cast<double>(i_hi + 1) * cell_;
      const double sy0 = lo_.y + static_cast<double>(j_lo) * cell_, sy1 = lo_.y + static_cast<double>(j_hi + 1) * cell_;
      if (i_lo > 0) reach = std::min(reach, q.x - sx0);
      if (i_hi + 1 < static_cast<long long>(nx_)) reach = std::min(reach, sx1 - q.x);
      if (j_lo > 0) reach = std::min(reach, q.y - sy0);
      if (j_hi + 1 < static_cast<long long>(ny_)) reach = std::min(reach, sy1 - q.y);
      if (reach == kInf) break;  // every cell scanned
      reach -= 1e-9 * (std::fabs(q.x) + std::fabs(q.y) + cell_);
      if (reach > 0 && best2 <= reach * reach) break;
    }
    return std::sqrt(best2);
  }

 private:
  std::size_t ix(double x) const { return clampi((x - lo_.x) / cell_, nx_); }
  std::size_t iy(double y) const { return clampi((y - lo_.y) / cell_, ny_); }
  static std::size_t clampi(double v, std::size_t n) {
    if (!(v > 0)) return 0;
    if (v >= static_cast<double>(n - 1)) return n - 1;
    return static_cast<std::size_t>(v);
  }
  void scan(std::size_t c, Point2 q, double& best2) const {
    for (std::size_t k = start_[c]; k < start_[c + 1]; ++k) {
      const auto& [a, b] = segs_[items_[k]];
      const Point2 d = b - a;
      const double l2 = norm2(d);
      const double t = l2 > 0 ? std::clamp(dot(q - a, d) / l2, 0.0, 1.0) : 0.0;
      best2 = std::min(best2, norm2(q - (a + t * d)));
    }
  }

  const std::vector<std::pair<Point2, Point2>>& segs_;
  Point2 lo_{};
  double cell_ = 1;
  std::size_t nx_ = 1, ny_ = 1;
  std::vector<std::size_t> start_;
  std::vector<std::uint32_t> items_;
};

// Every segment's start and points every `step` along it (closed rings: the end is the next
// segment's start). `step` is raised when the samples would exceed kMaxSamples.
std::vector<Point2> sample_segments(const std::vector<std::pair<Point2, Point2>>& segs, double step) {
  double total = 0;
  for (const auto& [a, b] : segs) total += dist(a, b);
  if (step > 0 && total / step > static_cast<double>(kMaxSamples)) step = total / static_cast<double>(kMaxSamples);
  std::vector<Point2> out;
  out.reserve(segs.size() + (step > 0 ? static_cast<std::size_t>(total / step) : 0));
  for (const auto& [a, b] : segs) {
    out.push_back(a);
    if (!(step > 0)) continue;
    const double len = dist(a, b);
    const std::size_t k = static_cast<std::size_t>(std::ceil(len / step));
    for (std::size_t i = 1; i < k; ++i) out.push_back(a + (static_cast<double>(i) / static_cast<double>(k)) * (b - a));
  }
  return out;
}

// `threads` > 1: the samples in two halves at once (the same distances; the first largest wins).
CoastDeviation deviation(const std::vector<Point2>& samples, const SegmentGrid& grid, Point2 origin,
                         unsigned threads = 1) {
  CoastDeviation d;
  d.samples = samples.size();
  if (samples.empty()) return d;
  std::vector<double> dd(samples.size());
  auto part = [&](std::size_t lo, std::size_t hi) {
    std::size_t arg = lo;
    for (std::size_t i = lo; i < hi; ++i) {
      dd[i] = grid.nearest(samples[i]);
      if (dd[i] > dd[arg]) arg = i;
    }
    return arg;
  };
  std::size_t arg = 0;
  if (threads > 1 && samples.size() >= 8192) {
    const std::size_t half = samples.size() / 2;
    std::size_t arg2 = half;
    run_beside([&] { arg2 = part(half, samples.size()); }, [&] { arg = part(0, half); });
    if (dd[arg2] > dd[arg]) arg = arg2;
  } else {
    arg = part(0, samples.size());
  }
  d.max_m = dd[arg];
  d.max_at = origin + samples[arg];
  // p99 by nearest rank: the smallest value with at least 99 % of the samples at or below it.
  const std::size_t rank = static_cast<std::size_t>(std::ceil(0.99 * static_cast<double>(dd.size())));
  const std::size_t k = rank == 0 ? 0 : rank - 1;
  std::nth_element(dd.begin(), dd.begin() + static_cast<std::ptrdiff_t>(k), dd.end());
  d.p99_m = dd[k];
  return d;
}

struct UnionFind {
  std::vector<Index> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), Index{0}); }
  Index find(Index x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(Index a, Index b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

// Coast deviation, both directions, sampled at every vertex and every hmin/2 (`boundary`: the
// mesh boundary edges ordered by their (smaller, larger) vertex ids, from the smaller).
void coast_deviation(ModelReadiness& r, const std::vector<std::pair<Point2, Point2>>& boundary,
                     const ModelReadyInputs& in, double hmin, Point2 origin) {
  if (!in.input_boundary || in.input_boundary->empty() || boundary.empty()) return;
  const unsigned threads = max_threads();
  const double step = hmin > 0 ? 0.5 * hmin : 0.0;
  const SegmentGrid mesh_grid(boundary);
  r.input_to_mesh = deviation(sample_segments(*in.input_boundary, step), mesh_grid, origin, threads);
  const SegmentGrid input_grid(*in.input_boundary);
  r.mesh_to_input = deviation(sample_segments(boundary, step), input_grid, origin, threads);
}

}  // namespace

std::vector<double> distances_to_segments(const std::vector<Point2>& points,
                                          const std::vector<std::pair<Point2, Point2>>& segments) {
  const SegmentGrid grid(segments);
  std::vector<double> out(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) out[i] = grid.nearest(points[i]);
  return out;
}

// The figures both paths start from: hmin, minimum depth and the coast figures of the run.
static ModelReadiness readiness_from_inputs(const ModelReadyInputs& in) {
  ModelReadiness r;
  const double hmin = in.hmin > 0 && std::isfinite(in.hmin) ? in.hmin : 0.0;
  if (hmin > 0) r.hmin_m = hmin;
  r.min_depth_m = in.min_depth_m;
  if (in.coast_figures) r.coast_figures = *in.coast_figures;
  r.input_pieces = r.figure("input_pieces");
  r.input_area_m2 = r.figure("input_area_m2");
  return r;
}

// A mesh with z but no vertex below sea level is land only: no water, so no gravity-wave time
// step (every depth would be the --min-depth clamp, and the figure would look like a real limit).
static void drop_land_time_step(ModelReadiness& r, const mesh::MeshView& m) {
  if (m.z.empty() || m.z.size() != m.num_vertices()) return;
  for (const double z : m.z)
    if (z < 0) return;
  r.land_only = true;
  r.time_step.reset();
}

ModelReadiness compute_model_readiness_plain(const mesh::MeshView& m, const ModelReadyInputs& in) {
  ModelReadiness r = readiness_from_inputs(in);
  const double hmin = r.hmin_m.value_or(0.0);

  const std::size_t nv = m.num_vertices(), nt = m.num_triangles();
  r.triangles = nt;
  for (std::size_t t = 0; t < nt; ++t)
    for (Index v : m.triangles[t])
      if (v >= nv)
        throw Error(ExitCode::kInternal, "model readiness: triangle " + std::to_string(t) + " references vertex " +
                                             std::to_string(v) + " of " + std::to_string(nv));

  // Half-edges grouped by their smaller endpoint (CSR), each group sorted by the other endpoint:
  // the triangles sharing an edge are then adjacent entries (one pass of scattered writes, then
  // sequential work; much faster than searching vertex stars on a mesh in refinement order).
  struct HalfEdge {
    Index other, t;
    bool operator<(const HalfEdge& h) const { return other != h.other ? other < h.other : t < h.t; }
  };
  std::vector<Index> start(nv + 1, 0);
  for (const auto& tri : m.triangles)
    for (int k = 0; k < 3; ++k) ++start[std::min(tri[k], tri[(k + 1) % 3]) + 1];
  for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  std::vector<HalfEdge> he(3 * nt);
  {
    std::vector<Index> cursor(start.begin(), start.end() - 1);
    for (std::size_t t = 0; t < nt; ++t) {
      const auto& tri = m.triangles[t];
      for (int k = 0; k < 3; ++k) {
        const Index a = tri[k], b = tri[(k + 1) % 3];
        he[cursor[std::min(a, b)]++] = {std::max(a, b), static_cast<Index>(t)};
      }
    }
  }

  UnionFind pieces(nt);
  std::vector<std::pair<Point2, Point2>> boundary;  // mesh boundary edges, local frame
  double shortest = kInf;
  const double half = 0.5 * hmin, tenth = 0.1 * hmin;
  for (std::size_t v = 0; v < nv; ++v) {
    const auto first = he.begin() + start[v], last = he.begin() + start[v + 1];
    std::sort(first, last);
    for (auto g = first; g != last;) {
      auto e = g + 1;
      while (e != last && e->other == g->other) pieces.unite(g->t, (e++)->t);
      const Point2 a = m.vertices[v], b = m.vertices[g->other];
      if (e - g == 1) boundary.push_back({a, b});  // used by one triangle
      const double len = dist(a, b);
      ++r.edges;
      if (len < shortest) {
        shortest = len;
        r.shortest_edge_at = m.origin + 0.5 * (a + b);
      }
      if (hmin > 0) {
        if (len < half) ++r.edges_below_half_hmin;
        if (len < tenth) ++r.edges_below_tenth_hmin;
      }
      g = e;
    }
  }

  const bool have_z = !m.z.empty() && m.z.size() == nv;
  const double min_depth = in.min_depth_m > 0 ? in.min_depth_m : 0.0;
  CompensatedSum area, qsum;
  for (std::size_t t = 0; t < nt; ++t) {
    const auto& tri = m.triangles[t];
    const Point2 p[3] = {m.vertices[tri[0]], m.vertices[tri[1]], m.vertices[tri[2]]};
    // len[k]: edge k from corner k to corner k+1
    const double len[3] = {dist(p[0], p[1]), dist(p[1], p[2]), dist(p[2], p[0])};
    const double cr = cross2(p);
    area.add(0.5 * cr);
    const double q = quality_of(p);
    qsum.add(q);
    if (!r.min_quality || q < *r.min_quality) r.min_quality = q;
    // The smallest angle is at the corner opposite the shortest edge; it is acute, so comparing
    // its cosine decides "< 20 deg" without trigonometry.
    const int ks = len[0] <= len[1] ? (len[0] <= len[2] ? 0 : 2) : (len[1] <= len[2] ? 1 : 2);
    const int apex = (ks + 2) % 3;
    const double lu = len[(ks + 1) % 3], lv = len[(ks + 2) % 3];  // the two edges at the apex
    const double c = lu > 0 && lv > 0 ? dot(p[(apex + 1) % 3] - p[apex], p[(apex + 2) % 3] - p[apex]) / (lu * lv) : 1.0;
    if (c > kCos20) ++r.triangles_below_20_deg;
    if (c > kCos30) ++r.triangles_below_30_deg;
    if (have_z) {
      const double lmax = std::max({len[0], len[1], len[2]});
      const double h = lmax > 0 ? std::fabs(cr) / lmax : 0.0;  // shortest altitude = 2 * area / longest edge
      const double depth = std::max(-(m.z[tri[0]] + m.z[tri[1]] + m.z[tri[2]]) / 3.0, min_depth);
      if (depth > 0 && std::isfinite(depth)) {
        const double dt = h / std::sqrt(kGravity * depth);
        if (!r.time_step || dt < r.time_step->dt_s)
          r.time_step = TimeStep{dt, h, depth, m.origin + (1.0 / 3.0) * (p[0] + p[1] + p[2]), t};
      }
    }
  }
  if (std::isfinite(shortest)) r.shortest_edge_m = shortest;
  if (nt > 0) r.mean_quality = qsum.value() / static_cast<double>(nt);
  r.mesh_area_m2 = area.value();
  for (std::size_t t = 0; t < nt; ++t)
    if (pieces.find(static_cast<Index>(t)) == t) ++r.mesh_pieces;
  r.mesh_boundary_edges = boundary.size();
  drop_land_time_step(r, m);

  coast_deviation(r, boundary, in, hmin, m.origin);
  return r;
}

namespace {

using Key = std::pair<Index, Index>;  // an edge: (smaller id, larger id)

// The figures of a contiguous range of triangles (compute_model_readiness).
struct RangeFigures {
  std::size_t edges = 0, below_half = 0, below_tenth = 0, below20 = 0, below30 = 0;
  double shortest = kInf;
  Key shortest_key{kNoId, kNoId};  // the first in the plain path's order among equal lengths
  std::optional<double> min_q;
  std::optional<TimeStep> step;
  std::vector<Key> boundary;  // the boundary edges
};

// Measures ranges of triangles with the mesher's adjacency; an edge is counted once, from its
// boundary half-edge or from its interior half-edge u -> w with u < w.
class ReadinessPass {
 public:
  ReadinessPass(const mesh::MeshView& m, const ModelReadyInputs& in, double hmin)
      : m_(m), have_z_(!m.z.empty() && m.z.size() == m.num_vertices()),
        min_depth_(in.min_depth_m > 0 ? in.min_depth_m : 0.0), hmin_(hmin) {}

  // The triangles [lo, hi) in order; `sums` (when given) adds their areas and qualities in order.
  void measure(std::size_t lo, std::size_t hi, RangeFigures& p, CompensatedSum* area, CompensatedSum* qsum) const;
  // Only the area and quality sums of [lo, hi), in order: the values measure() adds.
  void sums(std::size_t lo, std::size_t hi, CompensatedSum& area, CompensatedSum& qsum) const;

 private:
  // A triangle's time step h / sqrt(g depth), h its shortest altitude, when it may be below `best`.
  void time_step(std::size_t t, const Point2 (&pt)[3], double cr, double lmax, RangeFigures& p, double& best) const;

  const mesh::MeshView& m_;
  bool have_z_;
  double min_depth_, hmin_;
};

void ReadinessPass::measure(std::size_t lo, std::size_t hi, RangeFigures& p, CompensatedSum* area,
                            CompensatedSum* qsum) const {
  const auto& T = m_.triangles;
  const auto& V = m_.vertices;
  const auto& nb = m_.neighbours;
  const double half = 0.5 * hmin_, tenth = 0.1 * hmin_;
  // The accumulators in locals (the per-triangle stores below could alias them), written back.
  std::size_t edges = 0, below_half = 0, below_tenth = 0, below20 = 0, below30 = 0;
  double shortest = p.shortest, min_q = p.min_q.value_or(kInf), best_dt = p.step ? p.step->dt_s : kInf;
  Key shortest_key = p.shortest_key;
  for (std::size_t t = lo; t < hi; ++t) {
    if (t + 16 < hi)  // the corners a few triangles ahead (scattered loads)
      for (const Index v : T[t + 16]) {
        fdr::prefetch(&V[v]);
        if (have_z_) fdr::prefetch(&m_.z[v]);
      }
    const auto& tri = T[t];
    const Point2 pt[3] = {V[tri[0]], V[tri[1]], V[tri[2]]};
    const double len[3] = {dist(pt[0], pt[1]), dist(pt[1], pt[2]), dist(pt[2], pt[0])};
    for (int k = 0; k < 3; ++k) {
      const Index u = tri[k], w = tri[k == 2 ? 0 : k + 1];
      const bool boundary = nb[3 * t + k] == kNoId;
      if (!boundary && !(u < w)) continue;
      const Key key{std::min(u, w), std::max(u, w)};
      if (boundary) p.boundary.push_back(key);
      ++edges;
      // dist() is symmetric bit for bit: len[k] is the plain path's dist(smaller, larger).
      if (len[k] < shortest || (len[k] == shortest && key < shortest_key)) {
        shortest = len[k];
        shortest_key = key;
      }
      below_half += len[k] < half;
      below_tenth += len[k] < tenth;
    }
    const double cr = cross2(pt);
    const double qt = quality_of(pt);
    if (area) {
      area->add(0.5 * cr);
      qsum->add(qt);
    }
    if (qt < min_q) min_q = qt;  // qt is finite (the mesher's coordinates)
    const int ks = len[0] <= len[1] ? (len[0] <= len[2] ? 0 : 2) : (len[1] <= len[2] ? 1 : 2);
    const int apex = (ks + 2) % 3;
    const double lu = len[(ks + 1) % 3], lv = len[(ks + 2) % 3];
    if (lu > 0 && lv > 0) {
      // c = d / (lu lv) > cos 30 (and so > cos 20) is impossible when d is clearly below
      // cos 30 * lu lv (the division's rounding is ~1e-16 of c): no division then.
      const double d = dot(pt[(apex + 1) % 3] - pt[apex], pt[(apex + 2) % 3] - pt[apex]), l = lu * lv;
      if (!(d < kCos30 * l * (1 - 1e-12))) {
        const double c = d / l;
        below20 += c > kCos20;
        below30 += c > kCos30;
      }
    } else {  // c = 1
      below20 += 1.0 > kCos20;
      below30 += 1.0 > kCos30;
    }
    if (have_z_) time_step(t, pt, cr, std::max({len[0], len[1], len[2]}), p, best_dt);
  }
  p.edges += edges;
  if (hmin_ > 0) {
    p.below_half += below_half;
    p.below_tenth += below_tenth;
  }
  p.below20 += below20;
  p.below30 += below30;
  p.shortest = shortest;
  p.shortest_key = shortest_key;
  if (min_q < kInf) p.min_q = min_q;
}

void ReadinessPass::time_step(std::size_t t, const Point2 (&pt)[3], double cr, double lmax, RangeFigures& p,
                              double& best) const {
  const auto& tri = m_.triangles[t];
  const double h = lmax > 0 ? std::fabs(cr) / lmax : 0.0;  // shortest altitude = 2 * area / longest edge
  const double depth = std::max(-(m_.z[tri[0]] + m_.z[tri[1]] + m_.z[tri[2]]) / 3.0, min_depth_);
  // dt = h / sqrt(g depth) >= best is certain when h^2 >= best^2 g depth by a margin far above
  // the rounding of either side: no square root or division then.
  if (!(depth > 0 && std::isfinite(depth)) || h * h > best * best * (kGravity * depth) * (1 + 1e-9)) return;
  const double dt = h / std::sqrt(kGravity * depth);
  if (!p.step || dt < p.step->dt_s) {
    p.step = TimeStep{dt, h, depth, m_.origin + (1.0 / 3.0) * (pt[0] + pt[1] + pt[2]), t};
    best = dt;
  }
}

void ReadinessPass::sums(std::size_t lo, std::size_t hi, CompensatedSum& area, CompensatedSum& qsum) const {
  const auto& T = m_.triangles;
  const auto& V = m_.vertices;
  for (std::size_t t = lo; t < hi; ++t) {
    if (t + 16 < hi)
      for (const Index v : T[t + 16]) fdr::prefetch(&V[v]);
    const auto& tri = T[t];
    const Point2 pt[3] = {V[tri[0]], V[tri[1]], V[tri[2]]};
    area.add(0.5 * cross2(pt));
    qsum.add(quality_of(pt));
  }
}

// The connected pieces: a flood fill over the triangles through the adjacency (one visit each).
std::size_t count_pieces(const std::vector<Index>& nb, std::size_t nt) {
  std::vector<std::uint8_t> seen(nt, 0);
  std::vector<Index> stack;
  std::size_t n = 0;
  for (std::size_t s0 = 0; s0 < nt; ++s0) {
    if (seen[s0]) continue;
    ++n;
    seen[s0] = 1;
    stack.push_back(static_cast<Index>(s0));
    while (!stack.empty()) {
      const Index t = stack.back();
      stack.pop_back();
      for (int k = 0; k < 3; ++k) {
        const Index g = nb[3 * static_cast<std::size_t>(t) + k];
        if (g != kNoId && !seen[g / 3]) {
          seen[g / 3] = 1;
          stack.push_back(g / 3);
        }
      }
    }
  }
  return n;
}

// The figures of the front range [0, split) and the back range [split, nt) into r (ties go to the
// front, first in triangle order); returns the mesh boundary in the plain path's order.
std::vector<std::pair<Point2, Point2>> merge_ranges(ModelReadiness& r, RangeFigures& front, const RangeFigures& back,
                                                     const mesh::MeshView& m) {
  const auto& V = m.vertices;
  r.edges = front.edges + back.edges;
  r.edges_below_half_hmin = front.below_half + back.below_half;
  r.edges_below_tenth_hmin = front.below_tenth + back.below_tenth;
  r.triangles_below_20_deg = front.below20 + back.below20;
  r.triangles_below_30_deg = front.below30 + back.below30;
  const RangeFigures& se =
      back.shortest < front.shortest || (back.shortest == front.shortest && back.shortest_key < front.shortest_key)
          ? back : front;
  if (std::isfinite(se.shortest)) {
    r.shortest_edge_m = se.shortest;
    r.shortest_edge_at = m.origin + 0.5 * (V[se.shortest_key.first] + V[se.shortest_key.second]);
  }
  r.min_quality = front.min_q;
  if (back.min_q && (!r.min_quality || *back.min_q < *r.min_quality)) r.min_quality = back.min_q;
  r.time_step = front.step;
  if (back.step && (!r.time_step || back.step->dt_s < r.time_step->dt_s)) r.time_step = back.step;
  // The boundary in the plain path's order: by (smaller id, larger id), from the smaller.
  std::vector<Key>& keys = front.boundary;
  keys.insert(keys.end(), back.boundary.begin(), back.boundary.end());
  std::sort(keys.begin(), keys.end());
  std::vector<std::pair<Point2, Point2>> boundary(keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) boundary[i] = {V[keys[i].first], V[keys[i].second]};
  return boundary;
}

}  // namespace

// With the mesher's adjacency (m.neighbours): every figure of compute_model_readiness_plain, the
// same values bit for bit, without grouping and sorting the half-edges; the pieces join
// triangles through m.neighbours. With two threads the triangles are cut in a front and a back
// half: the second thread counts the pieces and measures the back half while the calling thread
// measures the front half and then adds the back half's area and quality in order (the
// compensated sums depend on the order).
ModelReadiness compute_model_readiness(const mesh::MeshView& m, const ModelReadyInputs& in) {
  const std::size_t nv = m.num_vertices(), nt = m.num_triangles();
  if (m.neighbours.size() != 3 * nt || nt == 0) return compute_model_readiness_plain(m, in);
  for (std::size_t t = 0; t < nt; ++t)
    for (Index v : m.triangles[t])
      if (v >= nv) return compute_model_readiness_plain(m, in);  // which throws the error
  ModelReadiness r = readiness_from_inputs(in);
  StepLaps L(debug::Aid::kReport, "  model readiness");  // developer aid (base/step_laps.hpp)
  const double hmin = r.hmin_m.value_or(0.0);
  r.triangles = nt;
  const ReadinessPass pass(m, in, hmin);
  CompensatedSum area, qsum;
  RangeFigures front, back;
  std::size_t pieces = 0;
  constexpr std::size_t kMinHalf = 3 * 8192;  // a second thread costs more than it saves below
  if (max_threads() > 1 && nt > kMinHalf) {
    const std::size_t split = nt / 2;
    run_beside(
        [&] {
          pieces = count_pieces(m.neighbours, nt);
          pass.measure(split, nt, back, nullptr, nullptr);
        },
        [&] {
          pass.measure(0, split, front, &area, &qsum);
          pass.sums(split, nt, area, qsum);
        });
  } else {
    pass.measure(0, nt, front, &area, &qsum);
    pieces = count_pieces(m.neighbours, nt);
  }
  L("measure");
  const std::vector<std::pair<Point2, Point2>> boundary = merge_ranges(r, front, back, m);
  r.mean_quality = qsum.value() / static_cast<double>(nt);
  r.mesh_area_m2 = area.value();
  r.mesh_pieces = pieces;
  r.mesh_boundary_edges = boundary.size();
  drop_land_time_step(r, m);
  L("boundary");
  coast_deviation(r, boundary, in, hmin, m.origin);
  L("deviation");
  return r;
}

std::optional<double> ModelReadiness::figure(const std::string& name) const {
  for (const auto& [k, v] : coast_figures)
    if (k == name) return v;
  return std::nullopt;
}
std::optional<double> ModelReadiness::shortest_edge_over_hmin() const {
  if (!shortest_edge_m || !hmin_m) return std::nullopt;
  return *shortest_edge_m / *hmin_m;
}
static std::optional<double> pct(std::size_t k, std::size_t n) {
  if (n == 0) return std::nullopt;
  return 100.0 * static_cast<double>(k) / static_cast<double>(n);
}
std::optional<double> ModelReadiness::pct_edges_below_half_hmin() const {
  return hmin_m ? pct(edges_below_half_hmin, edges) : std::nullopt;
}
std::optional<double> ModelReadiness::pct_edges_below_tenth_hmin() const {
  return hmin_m ? pct(edges_below_tenth_hmin, edges) : std::nullopt;
}
double ModelReadiness::pct_triangles_below_20() const { return pct(triangles_below_20_deg, triangles).value_or(0); }
double ModelReadiness::pct_triangles_below_30() const { return pct(triangles_below_30_deg, triangles).value_or(0); }
bool ModelReadiness::time_step_depth_clamped() const { return time_step && time_step->depth_m <= min_depth_m; }
std::optional<double> ModelReadiness::area_change_pct() const {
  if (!input_area_m2 || !(*input_area_m2 > 0)) return std::nullopt;
  return 100.0 * (mesh_area_m2 - *input_area_m2) / *input_area_m2;
}

// ---------------------------------------------------------------- writers

namespace {
using Json = nlohmann::ordered_json;
Json num(std::optional<double> v) {
  if (!v || !std::isfinite(*v)) return nullptr;
  return *v;
}
// Counts among the GIS figures are doubles; integral values are written as JSON integers.
Json figure_json(std::optional<double> v) {
  if (v && std::isfinite(*v) && *v == std::floor(*v) && std::fabs(*v) < 9e15) return static_cast<long long>(*v);
  return num(v);
}
Json xy(Point2 p) { return Json::array({p.x, p.y}); }
std::optional<double> over(std::optional<double> v, std::optional<double> h) {
  if (!v || !h || !(*h > 0)) return std::nullopt;
  return *v / *h;
}
constexpr const char* kLandOnly = "no vertex below sea level (land-only mesh): no gravity-wave time step";
// What the input->mesh deviation measures against, in words.
std::string boundary_label(const ModelReadiness& r) {
  const auto n = r.figure("input_polygons"), u = r.figure("input_polygons_united");
  if (n && u && *u < *n)
    return "boundary of the united input domain (" + fmt(n, "%.0f") + " polygons united into " + fmt(u, "%.0f") + ")";
  return "boundary of the input domain";
}
Json deviation_json(const std::optional<CoastDeviation>& d, std::optional<double> hmin) {
  if (!d) return nullptr;
  return {{"max_m", num(d->max_m)},
          {"p99_m", num(d->p99_m)},
          {"max_over_hmin", num(over(d->max_m, hmin))},
          {"p99_over_hmin", num(over(d->p99_m, hmin))},
          {"max_at", xy(d->max_at)},
          {"samples", d->samples}};
}
}  // namespace

nlohmann::ordered_json model_ready_json(const ModelReadiness& r) {
  Json j;
  j["hmin_m"] = num(r.hmin_m);
  j["edges"] = r.edges;
  j["shortest_edge_m"] = num(r.shortest_edge_m);
  j["shortest_edge_over_hmin"] = num(r.shortest_edge_over_hmin());
  j["shortest_edge_at"] = r.shortest_edge_m ? xy(r.shortest_edge_at) : Json(nullptr);
  j["edges_below_half_hmin_pct"] = num(r.pct_edges_below_half_hmin());
  j["edges_below_tenth_hmin_pct"] = num(r.pct_edges_below_tenth_hmin());
  j["edges_below_half_hmin"] = r.hmin_m ? Json(r.edges_below_half_hmin) : Json(nullptr);
  j["edges_below_tenth_hmin"] = r.hmin_m ? Json(r.edges_below_tenth_hmin) : Json(nullptr);
  j["triangles_below_20_deg_pct"] = r.pct_triangles_below_20();
  j["triangles_below_30_deg_pct"] = r.pct_triangles_below_30();
  j["triangles_below_20_deg"] = r.triangles_below_20_deg;
  j["triangles_below_30_deg"] = r.triangles_below_30_deg;
  j["mean_quality"] = num(r.mean_quality);
  j["min_quality"] = num(r.min_quality);
  j["pieces"] = {{"mesh", r.mesh_pieces}, {"input", figure_json(r.input_pieces)}};
  j["coast_deviation"] = {{"input_to_mesh", deviation_json(r.input_to_mesh, r.hmin_m)},
                          {"mesh_to_input", deviation_json(r.mesh_to_input, r.hmin_m)},
                          {"mesh_boundary_edges", r.mesh_boundary_edges},
                          {"measured_against", r.input_to_mesh ? Json(boundary_label(r)) : Json(nullptr)}};
  if (r.time_step) {
    j["time_step"] = {{"dt_s", num(r.time_step->dt_s)},
                      {"at", xy(r.time_step->at)},
                      {"h_m", num(r.time_step->h_m)},
                      {"depth_m", num(r.time_step->depth_m)},
                      {"h", "shortest altitude"},
                      {"min_depth_m", num(r.min_depth_m)},
                      {"depth_clamped", r.time_step_depth_clamped()}};
  } else {
    j["time_step"] = nullptr;
  }
  if (r.land_only) j["time_step_omitted"] = kLandOnly;
  j["area"] = {{"mesh_m2", num(r.mesh_area_m2)}, {"input_m2", num(r.input_area_m2)},
               {"change_pct", num(r.area_change_pct())}};
  j["features_removed"] = {{"water_closed", figure_json(r.figure("narrow_water_closed"))},
                           {"water_closed_m2", num(r.figure("water_removed_m2"))},
                           {"islands", figure_json(r.figure("islands_removed"))},
                           {"islands_m2", num(r.figure("islands_removed_m2"))}};
  Json figs = Json::object();
  for (const auto& [k, v] : r.coast_figures) figs[k] = figure_json(v);
  j["coast_figures"] = figs;
  return j;
}

void write_model_ready_text(const ModelReadiness& r, std::ostream& out) {
  out << "\n  Model readiness" << (r.hmin_m ? " (hmin = " + fmt(r.hmin_m, "%.6g") + " m)" : std::string()) << '\n';
  std::string se = fmt(r.shortest_edge_m, "%.4g") + " m";
  if (auto q = r.shortest_edge_over_hmin()) se += " = " + fmt(q, "%.3g") + " hmin";
  line(out, "shortest edge", se);
  if (r.hmin_m)
    line(out, "edges < hmin/2, < hmin/10", fmt(r.pct_edges_below_half_hmin(), "%.3f") + " %, " +
                                               fmt(r.pct_edges_below_tenth_hmin(), "%.3f") + " %");
  line(out, "triangles < 20 deg, < 30 deg",
       fmt(r.pct_triangles_below_20(), "%.3f") + " %, " + fmt(r.pct_triangles_below_30(), "%.3f") + " %");
  line(out, "mean quality (1 = equilateral)", fmt(r.mean_quality, "%.4f"));
  line(out, "pieces mesh / input",
       std::to_string(r.mesh_pieces) + " / " + (r.input_pieces ? fmt(r.input_pieces, "%.0f") : std::string("n/a")));
  auto dev = [&](const char* label, const std::optional<CoastDeviation>& d) {
    if (!d) return;
    std::string s = fmt(d->max_m, "%.4g") + " / " + fmt(d->p99_m, "%.4g") + " m";
    if (r.hmin_m)
      s += " = " + fmt(over(d->max_m, r.hmin_m), "%.3g") + " / " + fmt(over(d->p99_m, r.hmin_m), "%.3g") + " hmin";
    line(out, label, s);
  };
  if (r.input_to_mesh) line(out, "coast measured against", boundary_label(r));
  dev("coast in->mesh max / p99", r.input_to_mesh);
  dev("coast mesh->in max / p99", r.mesh_to_input);
  if (r.time_step) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "%.4g s at (%.1f, %.1f): h %.4g m, depth %.4g m%s", r.time_step->dt_s,
                  r.time_step->at.x, r.time_step->at.y, r.time_step->h_m, r.time_step->depth_m,
                  r.time_step_depth_clamped() ? " (the --min-depth clamp)" : "");
    line(out, "time step h/sqrt(g depth)", buf);
  } else if (r.land_only) {
    line(out, "time step h/sqrt(g depth)", "n/a: no vertex below sea level (land-only mesh)");
  }
  if (auto a = r.area_change_pct()) line(out, "area change vs input", fmt(a, "%+.4f") + " %");
  auto removed = [&](const char* label, const char* count, const char* area) {
    if (auto n = r.figure(count))
      line(out, label, fmt(n, "%.0f") + " (" + fmt(r.figure(area).value_or(0) / 1e6, "%.4g") + " km^2)");
  };
  // The generalisation treats the domain as water; on a land-only mesh its figures are about the
  // domain's own narrow parts and holes.
  const bool land = r.land_only;
  removed(land ? "narrow domain parts closed" : "narrow water closed", "narrow_water_closed", "water_removed_m2");
  removed(land ? "holes removed" : "islands removed", "islands_removed", "islands_removed_m2");
  removed(land ? "narrow domain parts widened" : "narrow water widened", "water_widened", "water_widened_m2");
  if (auto a = r.figure("thin_land_removed_m2"))
    line(out, land ? "thin gaps filled, tips kept" : "thin land removed, tips kept",
         fmt(*a / 1e6, "%.4g") + " km^2, " + fmt(r.figure("tips_kept").value_or(0), "%.0f"));
}

}  // namespace fdr::quality
