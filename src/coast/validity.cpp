// Validity test and contact finder of the coast generalisation (validity.hpp).
#include "coast/validity.hpp"

#include <algorithm>
#include <cmath>

#include "base/parallel.hpp"
#include "predicates/predicates.hpp"

namespace fdr::coast {

// pslg::find_contacts on two cores: the segments are split at the median of their left ends into
// those reaching left of it and those reaching right of it (a segment across it goes to both),
// each half is searched on its own, and the results are concatenated (segment indices into
// `segs`; a contact may be listed twice). The same contacts as one search: two segments that
// meet share a point, and both reach that point's side; a point inside a segment lies in its
// x-range, so it and the segments ending at it are in a half with that segment. For callers that
// use the contacts as a set (or only whether there are any). Small inputs: one search.
pslg::Contacts find_contacts_2(const std::vector<Point2>& pts, const std::vector<pslg::Segment>& segs,
                               const std::vector<char>* alive) {
  if (segs.size() < 20000 || max_threads() < 2) return pslg::find_contacts(pts, segs, alive);
  std::vector<double> lo(segs.size());
  for (std::size_t i = 0; i < segs.size(); ++i)
    lo[i] = std::min(pts[static_cast<std::size_t>(segs[i].a)].x, pts[static_cast<std::size_t>(segs[i].b)].x);
  std::vector<double> sorted = lo;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
  const double split = sorted[sorted.size() / 2];
  auto half = [&](bool left) {
    std::vector<pslg::Segment> sub;
    std::vector<std::size_t> id;
    std::vector<char> live(pts.size(), 0);
    for (std::size_t i = 0; i < segs.size(); ++i) {
      const double hi = std::max(pts[static_cast<std::size_t>(segs[i].a)].x, pts[static_cast<std::size_t>(segs[i].b)].x);
      if (left ? !(lo[i] <= split) : !(hi >= split)) continue;
      sub.push_back(segs[i]);
      id.push_back(i);
      for (const Index e : {segs[i].a, segs[i].b})
        if (!alive || (*alive)[static_cast<std::size_t>(e)]) live[static_cast<std::size_t>(e)] = 1;
    }
    pslg::Contacts c = pslg::find_contacts(pts, sub, &live);
    for (auto& [x, y] : c.segment_pairs) {
      x = static_cast<Index>(id[static_cast<std::size_t>(x)]);
      y = static_cast<Index>(id[static_cast<std::size_t>(y)]);
    }
    for (auto& vs : c.vertex_on_segment) vs.second = static_cast<Index>(id[static_cast<std::size_t>(vs.second)]);
    return c;
  };
  pslg::Contacts out, r;
  run_beside([&] { r = half(false); }, [&] { out = half(true); });
  out.segment_pairs.insert(out.segment_pairs.end(), r.segment_pairs.begin(), r.segment_pairs.end());
  out.kinds.insert(out.kinds.end(), r.kinds.begin(), r.kinds.end());
  out.vertex_on_segment.insert(out.vertex_on_segment.end(), r.vertex_on_segment.begin(), r.vertex_on_segment.end());
  return out;
}

// A sufficient test of validity with the mesher's exact contact finder: every ring simple, no
// two rings meeting at all, every hole inside the outer ring and none inside another hole.
// Why: GEOS's IsValid on a polygon with thousands of holes costs far more. False does not
// mean invalid, only that GEOS must decide.
bool surely_valid(const Rings& rings) {
  if (rings.empty()) return false;
  std::vector<Point2> pts;
  std::vector<pslg::Segment> segs;
  for (const auto& r : rings) {
    std::size_t n = r.size();
    if (n >= 2 && r.front() == r.back()) --n;  // closed copy
    if (n < 3) return false;
    const auto base = static_cast<Index>(pts.size());
    for (std::size_t i = 0; i < n; ++i) {
      if (r[i] == r[(i + 1) % n] || !std::isfinite(r[i].x) || !std::isfinite(r[i].y)) return false;
      pts.push_back(r[i]);
    }
    for (std::size_t i = 0; i < n; ++i)
      segs.push_back({base + static_cast<Index>(i), base + static_cast<Index>((i + 1) % n)});
  }
  {  // rings touching at a shared vertex: GEOS decides (they may cut the interior in two)
    std::vector<Point2> sorted = pts;
    std::sort(sorted.begin(), sorted.end(), [](Point2 a, Point2 b) { return a.x != b.x ? a.x < b.x : a.y < b.y; });
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) return false;
  }
  const pslg::Contacts ct = find_contacts_2(pts, segs, nullptr);
  if (!ct.segment_pairs.empty() || !ct.vertex_on_segment.empty()) return false;
  if (rings.size() == 1) return true;
  // Rings are disjoint: one vertex decides on which side of another ring a ring lies.
  OGRPolygon shell;
  {
    Rings outer{rings[0]};
    shell = to_ogr(outer);
  }
  Prepared ps(&shell);
  std::vector<OGREnvelope> env(rings.size());
  for (std::size_t k = 1; k < rings.size(); ++k) {
    OGRPoint q(rings[k][0].x, rings[k][0].y);
    if (!ps.intersects(&q)) return false;  // a hole outside the shell
    for (const Point2 v : rings[k]) env[k].Merge(v.x, v.y);
  }
  // Nested holes: a hole's vertex inside another hole (candidates by envelope, sorted by x).
  std::vector<std::size_t> order;
  for (std::size_t k = 1; k < rings.size(); ++k) order.push_back(k);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return env[a].MinX != env[b].MinX ? env[a].MinX < env[b].MinX : a < b;
  });
  for (std::size_t a = 0; a < order.size(); ++a)
    for (std::size_t b = a + 1; b < order.size(); ++b) {
      const std::size_t i = order[a], j = order[b];
      if (env[j].MinX > env[i].MaxX) break;
      if (!env[i].Intersects(env[j])) continue;
      // The one whose envelope contains the other's may contain it.
      for (const auto& [outer, inner] : {std::pair{i, j}, std::pair{j, i}}) {
        if (!env[outer].Contains(env[inner])) continue;
        const Point2 p = rings[inner][0];
        bool in = false;
        const auto& r = rings[outer];
        for (std::size_t e = 0, m = r.size(); e < m; ++e) {
          const Point2 u = r[e], w = r[(e + 1) % m];
          if ((u.y > p.y) == (w.y > p.y)) continue;
          const int o = predicates::orient2d(u, w, p);  // exact: p is on no ring
          if ((w.y > u.y) ? (o > 0) : (o < 0)) in = !in;
        }
        if (in) return false;
      }
    }
  return true;
}

}  // namespace fdr::coast
