// Orthogonality (|cos| between edge and cell-centre link, D-Flow FM style) and smoothness (neighbour area ratio).
#include "base/prefetch.hpp"
#include "quality/orthogonality.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "base/parallel.hpp"
#include "base/triangle_geometry.hpp"
#include "predicates/predicates.hpp"
#include "quality/cell_centre.hpp"
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
}  // namespace

OrthogonalityStats compute_orthogonality(const mesh::MeshView& m, unsigned threads) {
  const std::size_t nt = m.triangles.size();
  for (const auto& tr : m.triangles)
    for (Index v : tr)
      if (v >= m.vertices.size()) return {};  // invalid mesh: compute_quality reports it
  if (m.neighbours.size() == 3 * nt) return compute_orthogonality(m, m.neighbours, nullptr, threads);
  return compute_orthogonality(m, half_edge_neighbours(m), nullptr, threads);
}

OrthogonalityStats compute_orthogonality(const mesh::MeshView& m, const std::vector<Index>& nb, MeshWalkPrep* prep,
                                         unsigned threads) {
  OrthogonalityStats s;
  const std::size_t nt = m.triangles.size(), nv = m.vertices.size();
  if (prep) {
    prep->nn2.assign(nv, std::numeric_limits<double>::infinity());
    prep->tri_of_vertex.assign(nv, kNoId);
    prep->not_delaunay.clear();
    prep->ccw = true;
  }
  auto centre_area = [&](std::size_t t, Point2& cc, double& area) {
    const Point2 a = m.vertices[m.triangles[t][0]], b = m.vertices[m.triangles[t][1]], c = m.vertices[m.triangles[t][2]];
    cc = cell_centre(a, b, c, geom::circumcentre(a, b, c));
    area = 0.5 * std::fabs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
  };
  auto is_edge = [&](std::size_t t, int k) {
    return m.triangles[t][k] <= m.triangles[t][(k + 1) % 3] && nb[3 * t + k] != kNoId;
  };
  // Each interior edge once, from its half-edge a -> b with a <= b, in triangle order; the edges
  // of the triangles [lo, hi) are numbered from 0. want(j) says whether edge j is measured, then
  // visit(j, |cos|, area ratio). With `prep` (one thread only), also what the nearest-neighbour
  // search needs, gathered while the same triangles are in cache.
  auto for_each_edge = [&](std::size_t lo, std::size_t hi, auto&& want, auto&& visit, MeshWalkPrep* pr, bool prefetch) {
    std::size_t j = 0;
    for (std::size_t t = lo; t < hi; ++t) {
      // The neighbours are scattered in memory: fetch their triangles 16 ahead and the corners 8
      // ahead (by then their triangles are in cache), so the loads below wait less.
      if (prefetch && t + 16 < hi)
        for (int k = 0; k < 3; ++k)
          if (nb[3 * (t + 16) + k] != kNoId) fdr::prefetch(&m.triangles[nb[3 * (t + 16) + k] / 3]);
      if (prefetch && t + 8 < hi) {
        const auto& ahead = m.triangles[t + 8];
        for (int k = 0; k < 3; ++k) {
          fdr::prefetch(&m.vertices[ahead[k]]);
          if (pr) fdr::prefetch_for_write(&pr->nn2[ahead[k]]);
          const Index g = nb[3 * (t + 8) + k];
          if (g != kNoId) fdr::prefetch(&m.vertices[m.triangles[g / 3][(g % 3 + 2) % 3]]);
        }
      }
      const auto& tr = m.triangles[t];
      Point2 cct{};
      double at = -1;
      if (pr) {
        const Point2 a = m.vertices[tr[0]], b = m.vertices[tr[1]], c = m.vertices[tr[2]];
        if (predicates::orient2d(a, b, c) <= 0) pr->ccw = false;
        for (int k = 0; k < 3; ++k) {
          const Index u = tr[k], w = tr[k == 2 ? 0 : k + 1];
          pr->tri_of_vertex[u] = static_cast<Index>(t);
          if (u == w) continue;
          const double d = norm2(m.vertices[w] - m.vertices[u]);
          pr->nn2[u] = std::min(pr->nn2[u], d);
          pr->nn2[w] = std::min(pr->nn2[w], d);
        }
      }
      for (int k = 0; k < 3; ++k) {
        if (!is_edge(t, k)) continue;
        if (!want(j)) { ++j; continue; }
        const Index a = tr[k], b = tr[(k + 1) % 3];
        const Index g = nb[3 * t + k];
        if (at < 0) centre_area(t, cct, at);
        Point2 ccu;
        double au;
        centre_area(g / 3, ccu, au);
        if (pr && predicates::incircle(m.vertices[tr[0]], m.vertices[tr[1]], m.vertices[tr[2]],
                                       m.vertices[m.triangles[g / 3][(g % 3 + 2) % 3]]) > 0)
          pr->not_delaunay.push_back(static_cast<Index>(3 * t + k));
        const Point2 e = m.vertices[b] - m.vertices[a], l = cct - ccu;
        const double el = std::sqrt(norm2(e)) * std::sqrt(norm2(l));
        const double alo = std::min(at, au), ahi = std::max(at, au);
        visit(j++, el > 0 ? std::fabs(dot(e, l)) / el : 0.0,
              alo > 0 ? ahi / alo : std::numeric_limits<double>::infinity());
      }
    }
  };
  // p99 without keeping the values: pass 1 keeps each value's top 16 bits (sign, exponent and 4
  // mantissa bits order non-negative doubles like the values) and counts them; the rank falls in
  // one such bucket, and pass 2 measures again only the edges in it (the same value as a sort).
  struct Part {
    std::size_t lo = 0, hi = 0;
    std::vector<std::uint16_t> ortho_key, smooth_key;
    std::vector<std::uint32_t> ortho_count, smooth_count;
    double omax = -1, smax = -1;
  };
  auto pass1 = [&](Part& part, MeshWalkPrep* pr) {
    part.ortho_count.assign(1 << 16, 0);
    part.smooth_count.assign(1 << 16, 0);
    part.ortho_key.reserve(3 * (part.hi - part.lo) / 2 + 1);
    part.smooth_key.reserve(3 * (part.hi - part.lo) / 2 + 1);
    for_each_edge(part.lo, part.hi, [](std::size_t) { return true; }, [&](std::size_t, double o, double sm) {
      const std::uint16_t ko = top_bits(o), ks = top_bits(sm);
      part.ortho_key.push_back(ko);
      part.smooth_key.push_back(ks);
      ++part.ortho_count[ko];
      ++part.smooth_count[ks];
      part.omax = std::max(part.omax, o);
      part.smax = std::max(part.smax, sm);
    }, pr, true);
  };
  // Two fixed halves of the triangles when threads > 1 and no `prep` (same figures either way).
  std::vector<Part> parts(threads > 1 && !prep && nt >= 8192 ? 2 : 1);
  for (std::size_t i = 0; i < parts.size(); ++i) {
    parts[i].lo = nt * i / parts.size();
    parts[i].hi = nt * (i + 1) / parts.size();
  }
  if (parts.size() == 2) {
    run_beside([&] { pass1(parts[1], nullptr); }, [&] { pass1(parts[0], nullptr); });
  } else {
    pass1(parts[0], prep);
  }
  Part& all = parts[0];
  for (std::size_t i = 1; i < parts.size(); ++i) {
    for (std::size_t b = 0; b < all.ortho_count.size(); ++b) {
      all.ortho_count[b] += parts[i].ortho_count[b];
      all.smooth_count[b] += parts[i].smooth_count[b];
    }
    all.omax = std::max(all.omax, parts[i].omax);
    all.smax = std::max(all.smax, parts[i].smax);
  }
  std::size_t n = 0;
  for (const Part& part : parts) n += part.ortho_key.size();
  s.interior_edges = n;
  if (n == 0) return s;
  s.orthogonality_max = all.omax;
  s.smoothness_max = all.smax;
  const Rank ro = rank_bucket(all.ortho_count, n, 0.99), rs = rank_bucket(all.smooth_count, n, 0.99);
  std::vector<double> in_o, in_s;
  for (const Part& part : parts)
    for_each_edge(part.lo, part.hi,
                  [&](std::size_t j) { return part.ortho_key[j] == ro.bucket || part.smooth_key[j] == rs.bucket; },
                  [&](std::size_t j, double o, double sm) {
                    if (part.ortho_key[j] == ro.bucket) in_o.push_back(o);
                    if (part.smooth_key[j] == rs.bucket) in_s.push_back(sm);
                  },
                  nullptr, false);
  s.orthogonality_p99 = kth(in_o, ro.within);
  s.smoothness_p99 = kth(in_s, rs.within);
  return s;
}

}  // namespace fdr::quality
