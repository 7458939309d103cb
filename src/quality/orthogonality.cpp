// Orthogonality (|cos| between edge and cell-centre link, D-Flow FM style) and smoothness (neighbour area ratio).
#include "quality/orthogonality.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "predicates/predicates.hpp"
#include "quality/mesh_adjacency.hpp"

namespace fdr::quality {

namespace {
// Top 16 bits of a non-negative double (sign, exponent, 4 mantissa bits): monotone in the value.
std::uint16_t top_bits(double v) {
  std::uint64_t u;
  std::memcpy(&u, &v, sizeof u);
  return static_cast<std::uint16_t>(u >> 48);
}
// The nearest-rank q-quantile of n values lies in `bucket`, as the `within`-th smallest there.
struct Rank {
  std::uint16_t bucket = 0;
  std::size_t within = 0;
};
Rank rank_bucket(const std::vector<std::uint32_t>& count, std::size_t n, double q) {
  const std::size_t rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(n)));
  const std::size_t k = rank == 0 ? 0 : std::min(rank - 1, n - 1);  // 0-based
  std::size_t below = 0;
  for (std::size_t b = 0; b < count.size(); ++b) {
    if (below + count[b] > k) return {static_cast<std::uint16_t>(b), k - below};
    below += count[b];
  }
  return {};
}
double kth(std::vector<double>& v, std::size_t k) {
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}
// The circumcentre c of triangle abc (counter-clockwise), or the nearest point of the triangle's
// boundary when c lies outside (a measurement: plain doubles, no exact predicate needed).
Point2 cell_centre(Point2 a, Point2 b, Point2 c, Point2 cc) {
  auto side = [](Point2 p, Point2 q, Point2 r) { return (q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x); };
  if (side(a, b, cc) >= 0 && side(b, c, cc) >= 0 && side(c, a, cc) >= 0) return cc;
  auto nearest = [](Point2 p, Point2 u, Point2 v) {
    const Point2 d = v - u;
    const double l2 = norm2(d);
    const double t = l2 > 0 ? std::clamp(dot(p - u, d) / l2, 0.0, 1.0) : 0.0;
    return u + t * d;
  };
  Point2 best = nearest(cc, a, b);
  for (const Point2 q : {nearest(cc, b, c), nearest(cc, c, a)})
    if (norm2(q - cc) < norm2(best - cc)) best = q;
  return best;
}

}  // namespace

OrthogonalityStats compute_orthogonality(const mesh::MeshView& m) {
  OrthogonalityStats s;
  const std::size_t nt = m.triangles.size();
  for (const auto& tr : m.triangles)
    for (Index v : tr)
      if (v >= m.vertices.size()) return s;  // invalid mesh: compute_quality reports it
  std::vector<Index> built;
  if (m.neighbours.size() != 3 * nt) built = half_edge_neighbours(m);
  const std::vector<Index>& nb = built.empty() ? m.neighbours : built;
  auto centre_area = [&](std::size_t t, Point2& cc, double& area) {
    const Point2 a = m.vertices[m.triangles[t][0]], b = m.vertices[m.triangles[t][1]], c = m.vertices[m.triangles[t][2]];
    cc = cell_centre(a, b, c, predicates::circumcenter(a, b, c));
    area = 0.5 * std::fabs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
  };
  // Each interior edge once, from its half-edge a -> b with a <= b, in triangle order. Its two
  // values, |cos| and the area ratio; `visit(j, ortho, smooth)` gets the edge's running number j.
  auto for_each_edge = [&](auto&& visit) {
    std::size_t j = 0;
    for (std::size_t t = 0; t < nt; ++t) {
      Point2 cct{};
      double at = -1;
      for (int k = 0; k < 3; ++k) {
        const Index a = m.triangles[t][k], b = m.triangles[t][(k + 1) % 3];
        const Index g = nb[3 * t + k];
        if (a > b || g == kNoId) continue;
        if (at < 0) centre_area(t, cct, at);
        Point2 ccu;
        double au;
        centre_area(g / 3, ccu, au);
        const Point2 e = m.vertices[b] - m.vertices[a], l = cct - ccu;
        const double el = std::sqrt(norm2(e)) * std::sqrt(norm2(l));
        const double lo = std::min(at, au), hi = std::max(at, au);
        visit(j++, el > 0 ? std::fabs(dot(e, l)) / el : 0.0, lo > 0 ? hi / lo : std::numeric_limits<double>::infinity());
      }
    }
  };
  // p99 without keeping the values: pass 1 keeps each value's top 16 bits (sign, exponent and 4
  // mantissa bits order non-negative doubles like the values) and counts them; the rank falls in
  // one such bucket, and pass 2 recomputes only the edges in it (the same value as a sort).
  std::vector<std::uint16_t> ortho_key, smooth_key;
  ortho_key.reserve(3 * nt / 2 + 1);
  smooth_key.reserve(3 * nt / 2 + 1);
  std::vector<std::uint32_t> ortho_count(1 << 16, 0), smooth_count(1 << 16, 0);
  double omax = -1, smax = -1;
  for_each_edge([&](std::size_t, double o, double sm) {
    const std::uint16_t ko = top_bits(o), ks = top_bits(sm);
    ortho_key.push_back(ko);
    smooth_key.push_back(ks);
    ++ortho_count[ko];
    ++smooth_count[ks];
    omax = std::max(omax, o);
    smax = std::max(smax, sm);
  });
  s.interior_edges = ortho_key.size();
  if (s.interior_edges == 0) return s;
  s.orthogonality_max = omax;
  s.smoothness_max = smax;
  const Rank ro = rank_bucket(ortho_count, s.interior_edges, 0.99), rs = rank_bucket(smooth_count, s.interior_edges, 0.99);
  std::vector<double> in_o, in_s;
  for_each_edge([&](std::size_t j, double o, double sm) {
    if (ortho_key[j] == ro.bucket) in_o.push_back(o);
    if (smooth_key[j] == rs.bucket) in_s.push_back(sm);
  });
  s.orthogonality_p99 = kth(in_o, ro.within);
  s.smoothness_p99 = kth(in_s, rs.within);
  return s;
}

}  // namespace fdr::quality
