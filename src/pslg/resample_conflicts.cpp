// Resampling's exact conflict checks: pieces that cross or touch other segments, sweep over
// other vertices, or make a sharp wedge inside the domain (see resample.hpp).
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <vector>
#include "predicates/predicates.hpp"
#include "pslg/resampler.hpp"
#include "pslg/segment_grid.hpp"

namespace fdr::pslg::resampling {

bool Resampler::find_conflicts(const Pslg& out, std::vector<std::size_t>* bad) {
  std::vector<char> mark(flat_.size(), 0);
  auto restore = [&](std::size_t q) {
    if (q != kNoPiece && !mark[q]) {
      mark[q] = 1;
      bad->push_back(q);
    }
  };
  const Contacts ct = find_contacts(out.points, out.segments, nullptr);
  for (const auto& [s, t] : ct.segment_pairs) {
    restore(seg_piece_[s]);
    restore(seg_piece_[t]);
  }
  for (const auto& [v, s] : ct.vertex_on_segment) {
    restore(pt_piece_[v]);
    restore(seg_piece_[s]);
  }
  if (!bad->empty()) return true;
  // Angles: resampling may not create a wedge between two segments at a vertex that is much
  // sharper than any the input had there (a rounded inlet end simplified into a spike, two
  // chains leaving a junction almost together): refinement would need tiny elements in it.
  {
    const std::size_t n = out.points.size();
    std::vector<std::uint32_t> deg(n + 1, 0);
    for (const auto& sg : out.segments) { ++deg[sg.a + 1]; ++deg[sg.b + 1]; }
    for (std::size_t v = 0; v < n; ++v) deg[v + 1] += deg[v];
    std::vector<std::size_t> inc(deg[n]);
    std::vector<std::uint32_t> fill(deg.begin(), deg.end() - 1);
    for (std::size_t k = 0; k < out.segments.size(); ++k) {
      inc[fill[out.segments[k].a]++] = k;
      inc[fill[out.segments[k].b]++] = k;
    }
    std::vector<std::pair<double, std::size_t>> dirs;
    for (std::size_t v = 0; v < n; ++v) {
      if (deg[v + 1] - deg[v] < 2) continue;
      dirs.clear();
      for (std::uint32_t k = deg[v]; k < deg[v + 1]; ++k) {
        const auto& sg = out.segments[inc[k]];
        const Point2 o = out.points[v], q = out.points[sg.a == v ? sg.b : sg.a];
        dirs.push_back({std::atan2(q.y - o.y, q.x - o.x), inc[k]});
      }
      std::sort(dirs.begin(), dirs.end());
      for (std::size_t i = 0; i < dirs.size(); ++i) {
        const auto& [d1, s1] = dirs[i];
        const auto& [d2, s2] = dirs[(i + 1) % dirs.size()];
        double wedge = d2 - d1;
        if (wedge <= 0) wedge += 2 * std::numbers::pi;
        if (wedge >= kSharp) continue;
        const std::size_t q1 = seg_piece_[s1], q2 = seg_piece_[s2];
        if (q1 == kNoPiece && q2 == kNoPiece) continue;
        // A wedge outside the domain (the tip of a needle of land) needs no small elements:
        // the water around it spans the rest of the turn.
        if (o_.domain_by_parity && !wedge_is_inside(out, static_cast<Index>(v), s1, s2)) continue;
        const double ref = std::min(q1 == kNoPiece ? std::numbers::pi : piece_min_angle(q1), q2 == kNoPiece ? std::numbers::pi : piece_min_angle(q2));
        if (wedge < 0.7 * ref) {
          restore(q1);
          restore(q2);
        }
      }
    }
    if (!bad->empty()) return true;
  }
  // Swept regions: no other vertex may lie between a new chain piece and its input polyline.
  if (out.points.empty()) return false;
  Box2 box = out.bbox();
  double mean = 0;
  for (const auto& s : out.segments) mean += dist(out.points[s.a], out.points[s.b]);
  mean = out.segments.empty() ? 1 : mean / static_cast<double>(out.segments.size());
  for (const auto& p : in_.points) box.add(p);
  SegmentGrid grid(box, out.points.size(), std::max(mean, 1e-300));
  for (Index v = 0; v < out.points.size(); ++v) grid.add_point(v, out.points[v]);
  std::vector<Index> near;
  std::vector<Point2> poly;
  std::size_t q = 0;
  for (std::size_t c = 0; c < chains_.size(); ++c)
    for (const Piece& p : chain_pieces_[c]) {
      const std::size_t qi = q++;
      if (p.restored || !p.changed()) continue;
      poly.clear();
      for (std::size_t k = p.k0; k <= p.k1; ++k) poly.push_back(P(p.chain, k));
      for (std::size_t i = p.inner.size(); i-- > 0;) poly.push_back(p.inner[i]);
      Box2 pb;
      for (const auto& x : poly) pb.add(x);
      grid.points_near(pb, &near);
      const Point2 e0 = P(p.chain, p.k0), e1 = P(p.chain, p.k1);
      for (Index v : near) {
        if (pt_piece_[v] == qi) continue;
        const Point2 x = out.points[v];
        if (x == e0 || x == e1) continue;
        if (inside_or_on(x, poly)) {
          restore(qi);
          break;
        }
      }
    }
  return !bad->empty();
}

bool Resampler::wedge_is_inside(const Pslg& out, Index v, std::size_t s1, std::size_t s2) {
  for (std::size_t s : {s1, s2}) {
    const auto& sg = out.segments[s];
    if (!sg.is_boundary()) continue;
    const bool forward = sg.a == v;  // the ray from v runs along the chain
    const bool left = chain_left_inside(seg_chain_[s]);
    return s == s1 ? (left == forward) : (left != forward);
  }
  return true;
}

bool Resampler::chain_left_inside(std::size_t c) {
  if (chain_side_.empty()) chain_side_.assign(chains_.size(), -1);
  if (chain_side_[c] >= 0) return chain_side_[c] == 1;
  const Index ia = chains_[c].first_a, ib = chains_[c].first_b;
  const bool mirror = in_.points[ia].y == in_.points[ib].y;
  auto pt = [&](Index i) { const Point2 q = in_.points[i]; return mirror ? Point2{q.y, q.x} : q; };
  const Point2 a = pt(ia), b = pt(ib);
  const Point2 m{0.5 * (a.x + b.x), 0.5 * (a.y + b.y)};
  const int o = predicates::orient2d(a, b, m);
  std::size_t count = 0;
  const auto [first, last] = band_segments(mirror, m.y);
  for (const std::uint32_t* it = first; it != last; ++it) {
    const auto& t = in_.segments[*it];
    if (o == 0 && ((t.a == ia && t.b == ib) || (t.a == ib && t.b == ia))) continue;
    Point2 lo = pt(t.a), hi = pt(t.b);
    if ((lo.y > m.y) == (hi.y > m.y)) continue;
    if (lo.y > hi.y) std::swap(lo, hi);
    if (predicates::orient2d(lo, hi, m) > 0) ++count;  // the segment passes right of m
  }
  const bool in_at = count % 2 == 1;  // m, or (o == 0) the point just right of m
  // Whether that point lies left of (a, b): by o, or for o == 0 (m + (e, 0) left iff b.y < a.y).
  const bool point_left = o != 0 ? o > 0 : b.y < a.y;
  bool left = point_left ? in_at : !in_at;
  if (mirror) left = !left;
  chain_side_[c] = left ? 1 : 0;
  return left;
}

std::pair<const std::uint32_t*, const std::uint32_t*> Resampler::band_segments(bool mirror, double y) {
  Bands& b = bands_[mirror ? 1 : 0];
  auto coord = [&](Index i) { return mirror ? in_.points[i].x : in_.points[i].y; };
  if (b.start.empty()) {
    b.lo = 1e300;
    double hi = -1e300;
    std::vector<std::uint32_t> segs;
    for (std::size_t k = 0; k < in_.segments.size(); ++k) {
      const auto& t = in_.segments[k];
      if (!t.is_boundary() || t.a == t.b) continue;
      segs.push_back(static_cast<std::uint32_t>(k));
      b.lo = std::min({b.lo, coord(t.a), coord(t.b)});
      hi = std::max({hi, coord(t.a), coord(t.b)});
    }
    const std::size_t nb = std::max<std::size_t>(1, segs.size() / 32);
    b.step = hi > b.lo ? (hi - b.lo) / static_cast<double>(nb) : 1.0;
    b.start.assign(nb + 1, 0);
    auto range = [&](std::uint32_t k) {
      const auto& t = in_.segments[k];
      const double y0 = std::min(coord(t.a), coord(t.b)), y1 = std::max(coord(t.a), coord(t.b));
      return std::pair<std::size_t, std::size_t>{b.band(y0, nb), b.band(y1, nb)};
    };
    for (std::uint32_t k : segs) {
      const auto [i0, i1] = range(k);
      for (std::size_t i = i0; i <= i1; ++i) ++b.start[i + 1];
    }
    for (std::size_t i = 0; i < nb; ++i) b.start[i + 1] += b.start[i];
    b.items.resize(b.start[nb]);
    std::vector<std::size_t> fill(b.start.begin(), b.start.end() - 1);
    for (std::uint32_t k : segs) {
      const auto [i0, i1] = range(k);
      for (std::size_t i = i0; i <= i1; ++i) b.items[fill[i]++] = k;
    }
  }
  const std::size_t nb = b.start.size() - 1;
  const std::size_t i = b.band(y, nb);
  return {b.items.data() + b.start[i], b.items.data() + b.start[i + 1]};
}

double Resampler::piece_min_angle(std::size_t q) {
  const auto& [c, k0, k1] = flat_[q];
  double m = std::numbers::pi;
  for (std::size_t k = k0; k <= k1; ++k) m = std::min(m, input_wedge(chains_[c].v[k]));
  return m;
}

double Resampler::input_wedge(Index v) {
  if (is_virtual(v)) return std::numbers::pi;  // on an input segment
  if (wedge_.empty()) {
    // Smallest angle between consecutive input segments around every input vertex.
    const std::size_t n = in_.points.size();
    wedge_.assign(n, std::numbers::pi);
    std::vector<std::vector<double>> dirs(n);
    for (const auto& sg : in_.segments) {
      if (sg.a == sg.b) continue;
      const Point2 a = in_.points[sg.a], b = in_.points[sg.b];
      dirs[sg.a].push_back(std::atan2(b.y - a.y, b.x - a.x));
      dirs[sg.b].push_back(std::atan2(a.y - b.y, a.x - b.x));
    }
    for (std::size_t u = 0; u < n; ++u) {
      auto& d = dirs[u];
      if (d.size() < 2) continue;
      std::sort(d.begin(), d.end());
      for (std::size_t i = 0; i < d.size(); ++i) {
        double w = d[(i + 1) % d.size()] - d[i];
        if (w <= 0) w += 2 * std::numbers::pi;
        wedge_[u] = std::min(wedge_[u], w);
      }
    }
  }
  return wedge_[v];
}

}  // namespace fdr::pslg::resampling
