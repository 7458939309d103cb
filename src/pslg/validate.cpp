// PSLG validation with a uniform grid; every geometric decision by predicates::orient2d.
#include "pslg/validate.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include "base/error.hpp"
#include "pslg/segment_grid.hpp"

namespace fdr::pslg {
namespace {

std::string fmt_point(const Pslg& g, Point2 p) {
  const Point2 w = g.origin + p;
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.17g, %.17g)", w.x, w.y);
  return buf;
}

std::string seg_str(const Pslg& g, Index s) {
  const Segment& sg = g.segments[s];
  return "segment " + std::to_string(s) + " (" + std::to_string(sg.a) + " " +
         fmt_point(g, g.points[sg.a]) + " -> " + std::to_string(sg.b) + " " +
         fmt_point(g, g.points[sg.b]) + ")";
}

const char* contact_name(Contact c) {
  switch (c) {
    case Contact::kProper: return "cross";
    case Contact::kTouch: return "touch (an endpoint lies inside the other segment)";
    case Contact::kOverlap: return "overlap (collinear)";
    default: return "meet";
  }
}

[[noreturn]] void fail(const std::string& source, const std::string& what) {
  throw Error(ExitCode::kInvalidGeometry, source + ": " + what);
}

std::string count_prefix(std::size_t n, const char* what) {
  return n > 1 ? std::to_string(n) + " " + what + ", first: " : std::string();
}

}  // namespace

Contacts find_contacts(const std::vector<Point2>& points, const std::vector<Segment>& segments,
                       const std::vector<char>* point_alive) {
  Contacts out;
  Box2 box;
  std::vector<double> lengths;
  lengths.reserve(segments.size());
  for (const Segment& s : segments) {
    const Point2 a = points[s.a], b = points[s.b];
    if (s.a == s.b || a == b) continue;
    box.add(a);
    box.add(b);
    lengths.push_back(dist(a, b));
  }
  if (lengths.empty()) return out;
  // Median length sizes the cells: a few very long segments (region box edges) do not matter.
  std::nth_element(lengths.begin(), lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2), lengths.end());
  SegmentGrid grid(box, lengths.size(), lengths[lengths.size() / 2]);
  for (Index i = 0; i < segments.size(); ++i) {
    const Segment& s = segments[i];
    if (s.a == s.b || points[s.a] == points[s.b]) continue;
    grid.add_segment(i, points[s.a], points[s.b]);
  }
  // Why per cell: two segments that meet share at least one cell (registration is padded).
  // Why a sweep in each cell: the segments of a long straight chain crowd the cells it passes
  // (a cell holds ~sqrt(n) of them when the chain is alone in a large box), and all pairs would
  // be quadratic in that; sorted by their lower end along the cell's longer extent, a segment
  // is compared only with those whose range overlaps its own (the others classify as kNone).
  std::vector<std::pair<double, Index>> by_lo;
  for (std::size_t c = 0; c < grid.num_cells(); ++c) {
    const auto& ids = grid.segments_in(c);
    if (ids.size() < 2) continue;
    Box2 cb;
    for (Index i : ids) cb.add(points[segments[i].a]), cb.add(points[segments[i].b]);
    const bool along_x = cb.width() >= cb.height();
    auto lo = [&](Index i) {
      const Point2 a = points[segments[i].a], b = points[segments[i].b];
      return along_x ? std::min(a.x, b.x) : std::min(a.y, b.y);
    };
    auto hi = [&](Index i) {
      const Point2 a = points[segments[i].a], b = points[segments[i].b];
      return along_x ? std::max(a.x, b.x) : std::max(a.y, b.y);
    };
    by_lo.clear();
    for (Index i : ids) by_lo.push_back({lo(i), i});
    std::sort(by_lo.begin(), by_lo.end());
    for (std::size_t u = 0; u < by_lo.size(); ++u) {
      const Index su = by_lo[u].second;
      const Segment& s = segments[su];
      const double end = hi(su);
      for (std::size_t v = u + 1; v < by_lo.size() && by_lo[v].first <= end; ++v) {
        const Index sv = by_lo[v].second;
        const Segment& t = segments[sv];
        const Contact k = classify(points[s.a], points[s.b], points[t.a], points[t.b]);
        if (k == Contact::kNone || k == Contact::kEndpoint) continue;
        out.segment_pairs.emplace_back(std::min(su, sv), std::max(su, sv));
        out.kinds.push_back(k);
      }
    }
  }
  // Deduplicate pairs found in several cells.
  std::vector<std::size_t> order(out.segment_pairs.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](std::size_t x, std::size_t y) { return out.segment_pairs[x] < out.segment_pairs[y]; });
  Contacts uniq;
  for (std::size_t k : order) {
    if (!uniq.segment_pairs.empty() && uniq.segment_pairs.back() == out.segment_pairs[k]) continue;
    uniq.segment_pairs.push_back(out.segment_pairs[k]);
    uniq.kinds.push_back(out.kinds[k]);
  }
  // Vertices in segment interiors. An endpoint of a listed segment s inside segment t makes the
  // pair (s, t) touch or overlap, so it is among the pairs found above: only those are checked.
  // Other points (on no listed segment) are looked up in their cell, which lists every segment
  // through it.
  std::vector<char> on_segment(points.size(), 0);
  for (Index i = 0; i < segments.size(); ++i) {
    const Segment& s = segments[i];
    if (s.a == s.b || points[s.a] == points[s.b]) continue;
    on_segment[s.a] = on_segment[s.b] = 1;
  }
  for (std::size_t k = 0; k < uniq.segment_pairs.size(); ++k) {
    if (uniq.kinds[k] != Contact::kTouch && uniq.kinds[k] != Contact::kOverlap) continue;
    const auto [i, j] = uniq.segment_pairs[k];
    for (const auto& [s, t] : {std::pair{i, j}, std::pair{j, i}}) {
      const Segment& st = segments[s];
      const Segment& tt = segments[t];
      for (const Index p : {st.a, st.b}) {
        if (point_alive && !(*point_alive)[p]) continue;
        if (tt.a == p || tt.b == p) continue;
        if (in_interior(points[tt.a], points[tt.b], points[p])) uniq.vertex_on_segment.emplace_back(p, t);
      }
    }
  }
  for (Index p = 0; p < points.size(); ++p) {
    if (on_segment[p]) continue;
    if (point_alive && !(*point_alive)[p]) continue;
    const Point2 q = points[p];
    if (!box.contains(q)) continue;
    for (Index s : grid.segments_in(grid.cell_of(q))) {
      const Segment& sg = segments[s];
      if (sg.a == p || sg.b == p) continue;
      if (in_interior(points[sg.a], points[sg.b], q)) uniq.vertex_on_segment.emplace_back(p, s);
    }
  }
  std::sort(uniq.vertex_on_segment.begin(), uniq.vertex_on_segment.end());
  uniq.vertex_on_segment.erase(
      std::unique(uniq.vertex_on_segment.begin(), uniq.vertex_on_segment.end()),
      uniq.vertex_on_segment.end());
  return uniq;
}

std::vector<std::pair<Index, Index>> find_crossings(const Pslg& pslg) {
  return find_contacts(pslg.points, pslg.segments, nullptr).segment_pairs;
}

std::vector<std::pair<Index, Index>> find_vertices_on_segments(const Pslg& pslg) {
  return find_contacts(pslg.points, pslg.segments, nullptr).vertex_on_segment;
}

void validate(const Pslg& g, const std::string& source) {
  const std::size_t n = g.points.size();
  for (Index i = 0; i < n; ++i)
    if (!std::isfinite(g.points[i].x) || !std::isfinite(g.points[i].y))
      fail(source, "vertex " + std::to_string(i) + " has a non-finite coordinate");
  for (Index s = 0; s < g.segments.size(); ++s)
    if (g.segments[s].a >= n || g.segments[s].b >= n)
      fail(source, "segment " + std::to_string(s) + " refers to vertex " +
                       std::to_string(std::max(g.segments[s].a, g.segments[s].b)) + " but there are only " +
                       std::to_string(n) + " vertices");
  // Duplicate vertices: sort by coordinates, compare neighbours.
  {
    std::vector<Index> order(n);
    std::iota(order.begin(), order.end(), Index{0});
    auto less = [&](Index a, Index b) {
      const Point2 p = g.points[a], q = g.points[b];
      return p.x < q.x || (p.x == q.x && (p.y < q.y || (p.y == q.y && a < b)));
    };
    std::sort(order.begin(), order.end(), less);
    std::size_t count = 0;
    Index fa = 0, fb = 0;
    for (std::size_t k = 1; k < n; ++k)
      if (g.points[order[k - 1]] == g.points[order[k]]) {
        if (count == 0 || std::min(order[k - 1], order[k]) < std::min(fa, fb)) {
          fa = order[k - 1];
          fb = order[k];
        }
        ++count;
      }
    if (count)
      fail(source, count_prefix(count, "duplicate vertex pairs") + "vertices " + std::to_string(fa) +
                       " and " + std::to_string(fb) + " are both at " + fmt_point(g, g.points[fa]));
  }
  for (Index s = 0; s < g.segments.size(); ++s) {
    const Segment& sg = g.segments[s];
    if (sg.a == sg.b || g.points[sg.a] == g.points[sg.b])
      fail(source, "zero-length " + seg_str(g, s));
  }
  {
    std::vector<std::pair<std::pair<Index, Index>, Index>> keys;
    keys.reserve(g.segments.size());
    for (Index s = 0; s < g.segments.size(); ++s)
      keys.push_back({{std::min(g.segments[s].a, g.segments[s].b), std::max(g.segments[s].a, g.segments[s].b)}, s});
    std::sort(keys.begin(), keys.end());
    for (std::size_t k = 1; k < keys.size(); ++k)
      if (keys[k].first == keys[k - 1].first)
        fail(source, "duplicate segments " + std::to_string(keys[k - 1].second) + " and " +
                         std::to_string(keys[k].second) + ": " + seg_str(g, keys[k].second));
  }
  const Contacts c = find_contacts(g.points, g.segments, nullptr);
  if (!c.vertex_on_segment.empty()) {
    const auto [v, s] = c.vertex_on_segment.front();
    fail(source, count_prefix(c.vertex_on_segment.size(), "vertices on segment interiors") + "vertex " +
                     std::to_string(v) + " " + fmt_point(g, g.points[v]) + " lies inside " + seg_str(g, s));
  }
  if (!c.segment_pairs.empty()) {
    const auto [s, t] = c.segment_pairs.front();
    std::string where;
    if (c.kinds.front() == Contact::kProper) {
      const Segment &a = g.segments[s], &b = g.segments[t];
      where = " at about " + fmt_point(g, crossing_point(g.points[a.a], g.points[a.b], g.points[b.a], g.points[b.b]));
    }
    fail(source, count_prefix(c.segment_pairs.size(), "intersecting segment pairs") + seg_str(g, s) + " and " +
                     seg_str(g, t) + " " + contact_name(c.kinds.front()) + where);
  }
}

}  // namespace fdr::pslg
