// Coast deviation on the sphere (global_coast.hpp).
#include "gis/global_coast.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace fdr::gis {
namespace {

constexpr std::uint32_t kLeafArcs = 8;
constexpr double kMaxSamples = 4e6;

double angle(Point3 u, Point3 v) { return std::atan2(std::sqrt(norm2(cross(u, v))), dot(u, v)); }

// Euclidean distance from p to the box (0 inside).
double box_distance(Point3 p, const Box3& b) {
  const double dx = std::max({b.lo.x - p.x, 0.0, p.x - b.hi.x});
  const double dy = std::max({b.lo.y - p.y, 0.0, p.y - b.hi.y});
  const double dz = std::max({b.lo.z - p.z, 0.0, p.z - b.hi.z});
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

double axis(Point3 p, int k) { return k == 0 ? p.x : k == 1 ? p.y : p.z; }

Point3 normalized(Point3 p) { return (1.0 / std::sqrt(norm2(p))) * p; }

}  // namespace

double arc_distance(Point3 p, Point3 a, Point3 b) {
  const Point3 n = cross(a, b);
  const double nn = norm2(n);
  const double ends = std::min(angle(p, a), angle(p, b));
  if (!(nn > 1e-30)) return ends;
  // p's foot on the arc's great circle lies on the arc when a turns to it, and it to b, as a to b.
  if (dot(cross(a, p), n) >= 0 && dot(cross(p, b), n) >= 0) {
    const double s = std::abs(dot(p, n)) / std::sqrt(nn);  // sine of the angle to the great circle
    return std::atan2(s, std::sqrt(std::max(0.0, norm2(p) - s * s)));
  }
  return ends;
}

ArcIndex::ArcIndex(const std::vector<SphereArc>& arcs) : arcs_(arcs) {
  if (arcs.empty()) return;
  boxes_.resize(arcs.size());
  order_.resize(arcs.size());
  for (std::size_t i = 0; i < arcs.size(); ++i) {
    // The minor arc lies within its chord's box grown by its sagitta 1 - cos(theta / 2).
    const double c = dist(arcs[i].a, arcs[i].b);
    const double sag = 1.0 - std::sqrt(std::max(0.0, 1.0 - 0.25 * c * c)) + 1e-12;
    Box3 b;
    b.add(arcs[i].a);
    b.add(arcs[i].b);
    b.lo = b.lo - Point3{sag, sag, sag};
    b.hi = b.hi + Point3{sag, sag, sag};
    boxes_[i] = b;
    order_[i] = static_cast<std::uint32_t>(i);
  }
  nodes_.reserve(arcs.size() / 2 + 2);
  build(0, static_cast<std::uint32_t>(arcs.size()));
}

std::uint32_t ArcIndex::build(std::uint32_t lo, std::uint32_t hi) {
  const auto id = static_cast<std::uint32_t>(nodes_.size());
  nodes_.emplace_back();
  Box3 box;
  for (std::uint32_t i = lo; i < hi; ++i) box.add(boxes_[order_[i]].lo), box.add(boxes_[order_[i]].hi);
  nodes_[id].box = box;
  if (hi - lo <= kLeafArcs) {
    nodes_[id].first = lo;
    nodes_[id].count = hi - lo;
    return id;
  }
  // Split at the median box centre along the box's longest side.
  const Point3 ext = box.hi - box.lo;
  const int k = ext.x >= ext.y && ext.x >= ext.z ? 0 : ext.y >= ext.z ? 1 : 2;
  const std::uint32_t mid = lo + (hi - lo) / 2;
  std::nth_element(order_.begin() + lo, order_.begin() + mid, order_.begin() + hi, [&](std::uint32_t u, std::uint32_t v) {
    return axis(boxes_[u].center(), k) < axis(boxes_[v].center(), k);
  });
  const std::uint32_t left = build(lo, mid);
  const std::uint32_t right = build(mid, hi);
  nodes_[id].left = left;  // by index: nodes_ may have moved while the children were built
  nodes_[id].right = right;
  return id;
}

double ArcIndex::nearest(Point3 p) const {
  double best = std::numeric_limits<double>::infinity();
  if (nodes_.empty()) return best;
  std::vector<std::pair<double, std::uint32_t>> stack{{box_distance(p, nodes_[0].box), 0}};
  auto chord = [](double ang) { return ang >= std::numbers::pi ? 2.0 : 2.0 * std::sin(0.5 * ang); };
  while (!stack.empty()) {
    const auto [d, id] = stack.back();
    stack.pop_back();
    if (d >= chord(best)) continue;
    const Node& nd = nodes_[id];
    if (nd.count > 0) {
      for (std::uint32_t i = nd.first; i < nd.first + nd.count; ++i) {
        const SphereArc& s = arcs_[order_[i]];
        best = std::min(best, arc_distance(p, s.a, s.b));
      }
      continue;
    }
    const std::uint32_t l = nd.left, r = nd.right;
    const double dl = box_distance(p, nodes_[l].box), dr = box_distance(p, nodes_[r].box);
    // The nearer child is searched first: pushed last.
    if (dl <= dr) {
      stack.push_back({dr, r});
      stack.push_back({dl, l});
    } else {
      stack.push_back({dl, l});
      stack.push_back({dr, r});
    }
  }
  return best;
}

std::vector<Point3> sample_arcs(const std::vector<SphereArc>& arcs, double step_rad) {
  std::vector<Point3> out;
  for (const SphereArc& s : arcs) {
    out.push_back(s.a);
    if (!(step_rad > 0)) continue;
    const double th = angle(s.a, s.b);
    const auto k = static_cast<std::size_t>(std::ceil(th / step_rad));
    if (k < 2 || !(th > 0)) continue;
    // Points at equal angles along the arc (spherical linear interpolation).
    const double st = std::sin(th);
    for (std::size_t i = 1; i < k; ++i) {
      const double t = static_cast<double>(i) / static_cast<double>(k);
      out.push_back(normalized((std::sin((1 - t) * th) / st) * s.a + (std::sin(t * th) / st) * s.b));
    }
  }
  return out;
}

namespace {

SphereDeviation deviation_to(const std::vector<SphereArc>& from, const ArcIndex& index, double step_m, double r) {
  SphereDeviation d;
  if (from.empty()) return d;
  double total = 0;
  for (const SphereArc& s : from) total += angle(s.a, s.b);
  double step = step_m > 0 ? step_m / r : 0.0;
  if (step > 0 && total / step > kMaxSamples) step = total / kMaxSamples;
  const std::vector<Point3> samples = sample_arcs(from, step);
  std::vector<double> dd(samples.size());
  std::size_t arg = 0;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    dd[i] = index.nearest(samples[i]) * r;
    if (dd[i] > dd[arg]) arg = i;
  }
  d.samples = samples.size();
  d.max_m = dd[arg];
  d.max_at = to_lonlat(samples[arg]);
  // p99 by nearest rank: the smallest value with at least 99 % of the samples at or below it.
  const auto rank = static_cast<std::size_t>(std::ceil(0.99 * static_cast<double>(dd.size())));
  const std::size_t k = rank == 0 ? 0 : rank - 1;
  std::nth_element(dd.begin(), dd.begin() + static_cast<std::ptrdiff_t>(k), dd.end());
  d.p99_m = dd[k];
  return d;
}

}  // namespace

SphereDeviation sphere_deviation(const std::vector<SphereArc>& from, const std::vector<SphereArc>& to, double step_m,
                                 double r) {
  if (from.empty() || to.empty()) return {};
  const ArcIndex index(to);
  return deviation_to(from, index, step_m, r);
}

SphereDeviation sphere_deviation_kept(const std::vector<SphereArc>& from, const std::vector<SphereArc>& to,
                                      double step_m, double keep_m, std::size_t* lost_rings, double r) {
  if (lost_rings) *lost_rings = 0;
  if (from.empty() || to.empty()) return {};
  const ArcIndex index(to);
  std::vector<SphereArc> kept;
  kept.reserve(from.size());
  for (std::size_t first = 0; first < from.size();) {
    std::size_t end = first;  // the ring: arcs first .. end, the last one back at its start
    while (end + 1 < from.size() && !(from[end].b == from[first].a)) ++end;
    bool near = false;
    for (std::size_t i = first; i <= end && !near; ++i) near = index.nearest(from[i].a) * r <= keep_m;
    if (near) kept.insert(kept.end(), from.begin() + static_cast<std::ptrdiff_t>(first),
                          from.begin() + static_cast<std::ptrdiff_t>(end) + 1);
    else if (lost_rings) ++*lost_rings;
    first = end + 1;
  }
  return deviation_to(kept, index, step_m, r);
}

}  // namespace fdr::gis
