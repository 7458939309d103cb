// Orthogonality (|cos| between edge and cell-centre link, D-Flow FM style) and smoothness (neighbour area ratio).
#include "quality/orthogonality.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
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
  for (const auto& tr : m.triangles)
    for (Index v : tr)
      if (v >= m.vertices.size()) return s;  // invalid mesh: compute_quality reports it
  for (std::size_t t = 0; t < nt; ++t) {
    const Point2 a = m.vertices[m.triangles[t][0]], b = m.vertices[m.triangles[t][1]], c = m.vertices[m.triangles[t][2]];
    cc[t] = cell_centre(a, b, c, predicates::circumcenter(a, b, c));
    area[t] = 0.5 * std::fabs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
  }
  // Half-edges grouped by tail vertex, each stored with its head and triangle and sorted by head
  // (compressed rows): the twin of a -> b is a binary search among the half-edges leaving b; no
  // hashing, and no lookups back into the triangles while sorting and searching.
  const std::size_t nv = m.vertices.size();
  auto tail = [&](std::size_t h) { return m.triangles[h / 3][h % 3]; };
  auto head = [&](std::size_t h) { return m.triangles[h / 3][(h % 3 + 1) % 3]; };
  struct Out {
    Index head;
    TriangleId t;
  };
  std::vector<std::size_t> start(nv + 1, 0);
  std::vector<Out> out(3 * nt);
  for (std::size_t h = 0; h < 3 * nt; ++h) ++start[tail(h) + 1];
  for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  {
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::size_t t = 0; t < nt; ++t)
      for (int k = 0; k < 3; ++k)
        out[fill[m.triangles[t][k]]++] = {m.triangles[t][(k + 1) % 3], static_cast<TriangleId>(t)};
  }
  auto before = [](const Out& x, const Out& y) { return x.head < y.head || (x.head == y.head && x.t < y.t); };
  for (std::size_t v = 0; v < nv; ++v) {
    Out* b = out.data() + start[v];
    Out* e = out.data() + start[v + 1];
    for (Out* i = b + 1; i < e; ++i)  // insertion sort: a vertex has a handful of half-edges
      for (Out* j = i; j > b && before(*j, *(j - 1)); --j) std::swap(*j, *(j - 1));
  }
  std::vector<double> ortho, smooth;
  ortho.reserve(3 * nt / 2);
  smooth.reserve(3 * nt / 2);
  for (std::size_t h = 0; h < 3 * nt; ++h) {
    const Index a = tail(h), b = head(h);
    if (a > b) continue;  // each interior edge once, from its lower-numbered end
    const Out* b0 = out.data() + start[b];
    const Out* b1 = out.data() + start[b + 1];
    const Out* it = std::lower_bound(b0, b1, a, [](const Out& x, Index key) { return x.head < key; });
    if (it == b1 || it->head != a) continue;  // boundary edge
    const std::size_t t = h / 3, u = it->t;
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
