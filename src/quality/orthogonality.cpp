// Orthogonality (|cos| between edge and cell-centre link, D-Flow FM style) and smoothness (neighbour area ratio).
#include "quality/orthogonality.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <vector>

#include "predicates/predicates.hpp"

namespace fdr::quality {

namespace {
double nearest_rank(std::vector<double>& v, double q) {
  const std::size_t rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size())));
  const std::size_t k = rank == 0 ? 0 : std::min(rank - 1, v.size() - 1);
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
  std::vector<Point2> cc(nt);
  std::vector<double> area(nt);
  for (std::size_t t = 0; t < nt; ++t) {
    const Point2 a = m.vertices[m.triangles[t][0]], b = m.vertices[m.triangles[t][1]], c = m.vertices[m.triangles[t][2]];
    cc[t] = cell_centre(a, b, c, predicates::circumcenter(a, b, c));
    area[t] = 0.5 * std::fabs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
  }
  // Undirected edge -> first triangle seen; the second sighting makes it interior.
  std::unordered_map<std::uint64_t, std::size_t> first;
  first.reserve(3 * nt / 2 + 16);
  std::vector<double> ortho, smooth;
  ortho.reserve(3 * nt / 2);
  smooth.reserve(3 * nt / 2);
  for (std::size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      Index a = m.triangles[t][k], b = m.triangles[t][(k + 1) % 3];
      if (a > b) std::swap(a, b);
      const std::uint64_t key = static_cast<std::uint64_t>(a) << 32 ^ static_cast<std::uint64_t>(b);
      auto [it, inserted] = first.emplace(key, t);
      if (inserted) continue;
      const std::size_t u = it->second;
      const Point2 e = m.vertices[b] - m.vertices[a], l = cc[t] - cc[u];
      const double el = std::sqrt(norm2(e)) * std::sqrt(norm2(l));
      ortho.push_back(el > 0 ? std::fabs(dot(e, l)) / el : 0.0);
      const double lo = std::min(area[t], area[u]), hi = std::max(area[t], area[u]);
      smooth.push_back(lo > 0 ? hi / lo : std::numeric_limits<double>::infinity());
    }
  s.interior_edges = ortho.size();
  if (!ortho.empty()) {
    s.orthogonality_max = *std::max_element(ortho.begin(), ortho.end());
    s.smoothness_max = *std::max_element(smooth.begin(), smooth.end());
    s.orthogonality_p99 = nearest_rank(ortho, 0.99);
    s.smoothness_p99 = nearest_rank(smooth, 0.99);
  }
  return s;
}

}  // namespace fdr::quality
