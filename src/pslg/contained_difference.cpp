// a - b for polygon sets with b inside a and boundaries running together (see the header).
#include "pslg/contained_difference.hpp"
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <tuple>
#include "predicates/predicates.hpp"
#include "pslg/contained_difference_steps.hpp"
#include "pslg/segment_grid.hpp"

namespace fdr::pslg {

using predicates::orient2d;

namespace cd_steps {
namespace {

bool lex_less(Point2 p, Point2 q) { return p.x < q.x || (p.x == q.x && p.y < q.y); }

// Segments in the cells of a uniform grid, as one sorted array of (cell, segment): no
// per-cell allocation. A segment is listed in every cell its box (grown by pad) meets.
class CellIndex {
 public:
  CellIndex(const std::vector<Point2>& from, const std::vector<Point2>& to, double pad) : pad_(pad) {
    const std::size_t n = from.size();
    Box2 box;
    double len = 0;
    for (std::size_t i = 0; i < n; ++i) {
      box.add(from[i]);
      box.add(to[i]);
      len += std::fabs(to[i].x - from[i].x) + std::fabs(to[i].y - from[i].y);
    }
    if (box.empty()) box.add({0, 0});
    x0_ = box.lo.x - 2 * pad - 1e-300;
    y0_ = box.lo.y - 2 * pad - 1e-300;
    cs_ = n ? std::max(len / static_cast<double>(n), 1e-300) : 1.0;
    cs_ = std::max({cs_, (box.width() + 4 * pad) / 1e6, (box.height() + 4 * pad) / 1e6});
    for (;;) {  // at most ~8 cells per segment on average
      std::size_t cells = 0;
      for (std::size_t i = 0; i < n && cells <= 8 * n + 64; ++i) {
        const auto [c0, r0, c1, r1] = span(from[i], to[i]);
        cells += static_cast<std::size_t>((c1 - c0 + 1) * (r1 - r0 + 1));
      }
      if (cells <= 8 * n + 64) break;
      cs_ *= 2;
    }
    for (std::size_t i = 0; i < n; ++i) {
      const auto [c0, r0, c1, r1] = span(from[i], to[i]);
      for (std::int64_t r = r0; r <= r1; ++r)
        for (std::int64_t c = c0; c <= c1; ++c) items_.push_back({key(c, r), static_cast<std::uint32_t>(i)});
    }
    std::sort(items_.begin(), items_.end());
  }
  // The segments listed in p's cell (each segment whose padded box holds p is among them).
  template <class F>
  void near_point(Point2 p, F&& f) const {
    const std::uint64_t k = key(cell(p.x - x0_), cell(p.y - y0_));
    auto it = std::lower_bound(items_.begin(), items_.end(), std::make_pair(k, std::uint32_t{0}));
    for (; it != items_.end() && it->first == k; ++it) f(it->second);
  }
  // Each pair of segments that share a cell, once (in the cell holding the low corner of the
  // intersection of their padded boxes).
  template <class F>
  void pairs(const std::vector<Point2>& from, const std::vector<Point2>& to, F&& f) const {
    for (std::size_t g = 0; g < items_.size();) {
      std::size_t e = g + 1;
      while (e < items_.size() && items_[e].first == items_[g].first) ++e;
      for (std::size_t x = g; x < e; ++x)
        for (std::size_t y = x + 1; y < e; ++y) {
          const std::uint32_t i = items_[x].second, j = items_[y].second;
          const double lx = std::max(std::min(from[i].x, to[i].x), std::min(from[j].x, to[j].x)) - pad_;
          const double ly = std::max(std::min(from[i].y, to[i].y), std::min(from[j].y, to[j].y)) - pad_;
          if (key(cell(lx - x0_), cell(ly - y0_)) != items_[g].first) continue;
          f(i, j);
        }
      g = e;
    }
  }

 private:
  std::int64_t cell(double d) const {
    return static_cast<std::int64_t>(std::clamp(std::floor(d / cs_), 0.0, 2147483647.0));
  }
  static std::uint64_t key(std::int64_t c, std::int64_t r) {
    return (static_cast<std::uint64_t>(r) << 32) | static_cast<std::uint64_t>(c);
  }
  std::array<std::int64_t, 4> span(Point2 a, Point2 b) const {
    return {cell(std::min(a.x, b.x) - pad_ - x0_), cell(std::min(a.y, b.y) - pad_ - y0_),
            cell(std::max(a.x, b.x) + pad_ - x0_), cell(std::max(a.y, b.y) + pad_ - y0_)};
  }
  double pad_, x0_ = 0, y0_ = 0, cs_ = 1;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> items_;
};

// Segments of rings as (from, to) arrays, with (ring, index) of each.
struct Segs {
  std::vector<Point2> from, to;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> at;
};
Segs segments_of(const std::vector<Ring>& rings, bool from_a) {
  Segs s;
  for (std::uint32_t r = 0; r < rings.size(); ++r) {
    if (rings[r].from_a != from_a) continue;
    const auto& p = rings[r].p;
    for (std::uint32_t i = 0; i < p.size(); ++i) {
      s.from.push_back(p[i]);
      s.to.push_back(p[(i + 1) % p.size()]);
      s.at.push_back({r, i});
    }
  }
  return s;
}

// Drops consecutive repeats (and a closing repeat); false when fewer than 3 vertices remain.
bool tidy(std::vector<Point2>& p) {
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (k == 0 || !(p[i] == p[k - 1])) p[k++] = p[i];
  while (k > 1 && p[k - 1] == p[0]) --k;
  p.resize(k);
  return k >= 3;
}

// +1 counter-clockwise, -1 clockwise, 0 degenerate: the turn at the lexicographically smallest
// vertex (a convex corner of a simple ring).
int orientation(const std::vector<Point2>& p) {
  std::size_t m = 0;
  for (std::size_t i = 1; i < p.size(); ++i)
    if (lex_less(p[i], p[m])) m = i;
  const std::size_t n = p.size();
  return orient2d(p[(m + n - 1) % n], p[m], p[(m + 1) % n]);
}

// Inserts the vertices of `src` rings that lie within eps of a segment of `dst` rings (not
// within eps of either end, and not a vertex of dst already) into that segment.
std::size_t insert_near(std::vector<Ring>& rings, bool src_a, double eps) {
  const Segs d = segments_of(rings, !src_a);
  if (d.from.empty()) return 0;
  const CellIndex idx(d.from, d.to, eps);
  // (segment, parameter, point)
  std::vector<std::tuple<std::uint32_t, double, Point2>> ins;
  for (const Ring& r : rings) {
    if (r.from_a != src_a) continue;
    for (const Point2 v : r.p) {
      bool vertex = false;
      double best = eps;
      std::int64_t bs = -1;
      double bt = 0;
      idx.near_point(v, [&](std::uint32_t s) {
        const Point2 a = d.from[s], b = d.to[s];
        if (a == v || b == v) { vertex = true; return; }
        if (dist(a, v) <= eps || dist(b, v) <= eps) return;
        const Point2 ab = b - a;
        const double l2 = norm2(ab);
        if (!(l2 > 0)) return;
        const double t = std::clamp(dot(v - a, ab) / l2, 0.0, 1.0);
        const double dd = dist(v, a + t * ab);
        if (dd <= best && (bs < 0 || dd < best || s < bs)) {
          best = dd;
          bs = s;
          bt = t;
        }
      });
      if (!vertex && bs >= 0) ins.emplace_back(static_cast<std::uint32_t>(bs), bt, v);
    }
  }
  if (ins.empty()) return 0;
  std::sort(ins.begin(), ins.end(), [](const auto& x, const auto& y) {
    if (std::get<0>(x) != std::get<0>(y)) return std::get<0>(x) < std::get<0>(y);
    if (std::get<1>(x) != std::get<1>(y)) return std::get<1>(x) < std::get<1>(y);
    return lex_less(std::get<2>(x), std::get<2>(y));
  });
  std::size_t q = 0;
  std::size_t count = 0;
  // Walk the segments of dst in order (segments_of lists them ring by ring, in ring order).
  std::vector<Point2> out;
  std::uint32_t cur = std::numeric_limits<std::uint32_t>::max();
  for (std::uint32_t s = 0; s < d.from.size(); ++s) {
    const auto [r, i] = d.at[s];
    if (r != cur) {
      if (cur != std::numeric_limits<std::uint32_t>::max()) rings[cur].p.swap(out);
      out.clear();
      cur = r;
    }
    out.push_back(d.from[s]);
    for (; q < ins.size() && std::get<0>(ins[q]) == s; ++q) {
      const Point2 v = std::get<2>(ins[q]);
      if (!(out.back() == v) && !(v == d.to[s])) {
        out.push_back(v);
        ++count;
      }
    }
  }
  if (cur != std::numeric_limits<std::uint32_t>::max()) rings[cur].p.swap(out);
  return count;
}

double area2(const std::vector<Point2>& p) {
  double s = 0;
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Point2 a = p[i] - p[0], b = p[(i + 1) % n] - p[0];
    s += a.x * b.y - a.y * b.x;
  }
  return s;
}

// The input rings, tidied, each with the orientation that puts the result's interior on its
// left: a's shells counter-clockwise and holes clockwise, b's the other way round.
const char* input_rings(PolygonSet& a, PolygonSet& b, std::vector<Ring>& rings) {
  for (int set = 0; set < 2; ++set)
    for (auto& poly : set == 0 ? a : b)
      for (std::size_t k = 0; k < poly.size(); ++k) {
        Ring r{std::move(poly[k]), set == 0, (set == 0) == (k == 0) ? 1 : -1};
        for (const Point2& q : r.p)
          if (!std::isfinite(q.x) || !std::isfinite(q.y)) return "a coordinate is not finite";
        if (!tidy(r.p)) {
          if (k == 0) return "a shell with fewer than 3 vertices";
          continue;
        }
        rings.push_back(std::move(r));
      }
  std::size_t nv = 0;
  for (const Ring& r : rings) nv += r.p.size();
  if (nv >= std::numeric_limits<std::uint32_t>::max() / 4) return "too many vertices";
  return nullptr;
}

// Moves each vertex of a within eps of a vertex of b onto the nearest one (of equally near
// ones the lexicographically smallest, so the result does not depend on the order of b).
const char* snap_a_onto_b(std::vector<Ring>& rings, double eps, std::size_t& snapped) {
  const Segs sb = segments_of(rings, false);
  if (sb.from.empty()) return nullptr;
  const CellIndex idx(sb.from, sb.to, eps);
  for (Ring& r : rings) {
    if (!r.from_a) continue;
    for (Point2& v : r.p) {
      double best = eps;
      Point2 to = v;
      idx.near_point(v, [&](std::uint32_t s) {
        for (const Point2 q : {sb.from[s], sb.to[s]}) {
          const double d = q == v ? 0.0 : dist(q, v);
          if (d < best || (d == best && lex_less(q, to))) {
            best = d;
            to = q;
          }
        }
      });
      if (!(to == v)) {
        v = to;
        ++snapped;
      }
    }
    if (!tidy(r.p)) return "a ring of a collapsed when snapped onto b";
  }
  return nullptr;
}

// Tidies every ring and turns it to the orientation it wants.
const char* orient_rings(std::vector<Ring>& rings) {
  for (Ring& r : rings) {
    if (!tidy(r.p)) return "a ring collapsed";
    const int o = orientation(r.p);
    if (o == 0) return "a ring without area";
    if (o != r.want) std::reverse(r.p.begin(), r.p.end());
  }
  return nullptr;
}

}  // namespace

// The steps declared in contained_difference_steps.hpp.

bool cw_before(Point2 v, Point2 r, Point2 w, Point2 z) {
  auto half = [&](Point2 q) {
    const int o = orient2d(v, r, q);
    if (o < 0) return 0;  // right of the ray: reached first turning clockwise
    if (o > 0) return 2;
    const bool same = (q.x - v.x) * (r.x - v.x) + (q.y - v.y) * (r.y - v.y) > 0;
    return same ? 3 : 1;
  };
  const int hw = half(w), hz = half(z);
  if (hw != hz) return hw < hz;
  if (hw == 1 || hw == 3) return false;
  return orient2d(v, w, z) < 0;  // z clockwise of w: w first
}

int locate(Point2 h, const std::vector<Point2>& ring) {
  int wn = 0;
  const std::size_t n = ring.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Point2 p = ring[i], q = ring[(i + 1) % n];
    if (p == h) return 0;
    if (p.y <= h.y) {
      if (q.y > h.y) {
        const int o = orient2d(p, q, h);
        if (o > 0) ++wn;
        else if (o == 0) return 0;
      }
    } else if (q.y <= h.y) {
      const int o = orient2d(p, q, h);
      if (o < 0) --wn;
      else if (o == 0) return 0;
    }
    if (p.y == h.y && q.y == h.y && std::min(p.x, q.x) <= h.x && h.x <= std::max(p.x, q.x)) return 0;
  }
  return wn != 0 ? 1 : -1;
}

const char* cancel_shared(const std::vector<Ring>& rings, std::vector<Edge>& rest, std::size_t& cancelled) {
  std::vector<Edge> edges;
  for (std::uint32_t r = 0; r < rings.size(); ++r) {
    const auto& p = rings[r].p;
    for (std::uint32_t i = 0; i < p.size(); ++i) edges.push_back({p[i], p[(i + 1) % p.size()], r, i});
  }
  auto lo = [&](const Edge& e) { return lex_less(e.u, e.v) ? e.u : e.v; };
  auto hi = [&](const Edge& e) { return lex_less(e.u, e.v) ? e.v : e.u; };
  std::vector<std::uint32_t> ord(edges.size());
  for (std::uint32_t i = 0; i < ord.size(); ++i) ord[i] = i;
  // Sorted by the undirected segment (smaller end first), then by index.
  std::sort(ord.begin(), ord.end(), [&](std::uint32_t i, std::uint32_t j) {
    const Point2 xl = lo(edges[i]), yl = lo(edges[j]);
    if (!(xl == yl)) return lex_less(xl, yl);
    const Point2 xh = hi(edges[i]), yh = hi(edges[j]);
    if (!(xh == yh)) return lex_less(xh, yh);
    return i < j;
  });
  std::vector<char> live(edges.size(), 1);
  cancelled = 0;
  for (std::size_t g = 0; g < ord.size();) {
    std::size_t e = g + 1;
    const Edge& first = edges[ord[g]];
    while (e < ord.size() && lo(edges[ord[e]]) == lo(first) && hi(edges[ord[e]]) == hi(first)) ++e;
    if (e - g == 2) {
      const Edge &x = edges[ord[g]], &y = edges[ord[g + 1]];
      if (rings[x.ring].from_a == rings[y.ring].from_a) return "a segment twice in one set";
      if (x.u == y.u) return "b lies beside a along a shared segment";
      live[ord[g]] = live[ord[g + 1]] = 0;
      ++cancelled;
    } else if (e - g > 2) {
      return "a segment in more than two rings";
    }
    g = e;
  }
  rest.clear();
  for (std::size_t i = 0; i < edges.size(); ++i)
    if (live[i]) rest.push_back(edges[i]);
  return nullptr;
}

std::vector<std::vector<std::uint32_t>> split_closed_walk(const std::vector<std::uint32_t>& walk,
                                                          const std::vector<Edge>& rest) {
  std::vector<std::vector<std::uint32_t>> parts;
  std::vector<Point2> sorted;
  sorted.reserve(walk.size());
  for (const std::uint32_t e : walk) sorted.push_back(rest[e].u);
  std::sort(sorted.begin(), sorted.end(), lex_less);
  bool repeats = false;
  for (std::size_t k = 0; k + 1 < sorted.size() && !repeats; ++k) repeats = sorted[k] == sorted[k + 1];
  if (!repeats) {
    parts.push_back(walk);
    return parts;
  }
  std::vector<std::uint32_t> stack;
  std::vector<std::pair<Point2, std::size_t>> at;  // vertex -> index in stack
  for (const std::uint32_t e : walk) {
    const Point2 p = rest[e].u;
    std::ptrdiff_t k = -1;
    for (std::size_t q = at.size(); q-- > 0;)
      if (at[q].first == p) {
        k = static_cast<std::ptrdiff_t>(q);
        break;
      }
    if (k >= 0) {  // back at p: the segments since p left form a loop
      const std::size_t from = at[static_cast<std::size_t>(k)].second;
      parts.emplace_back(stack.begin() + static_cast<std::ptrdiff_t>(from), stack.end());
      stack.resize(from);
      at.resize(static_cast<std::size_t>(k));
    }
    at.push_back({p, stack.size()});
    stack.push_back(e);
  }
  if (!stack.empty()) parts.push_back(stack);
  return parts;
}

namespace {

// A contact point to insert into segment `at` of ring `ring`.
struct Cut {
  std::uint32_t ring, at;
  Point2 q;
};

// Where a segment of one set crosses or touches one of the other (not just at shared ends),
// the contact point goes into both: a crossing rounded to the nearest doubles (which moves each
// segment by an ulp), a touch or overlap as the ends of each inside the other.
const char* find_cuts(const std::vector<Ring>& rings, const std::vector<Edge>& rest, std::vector<Cut>& cuts) {
  std::vector<Point2> from(rest.size()), to(rest.size());
  for (std::size_t i = 0; i < rest.size(); ++i) from[i] = rest[i].u, to[i] = rest[i].v;
  const CellIndex idx(from, to, 0.0);
  bool same_set = false;
  idx.pairs(from, to, [&](std::uint32_t i, std::uint32_t j) {
    const Contact c = classify(from[i], to[i], from[j], to[j]);
    if (c == Contact::kNone || c == Contact::kEndpoint) return;
    if (rings[rest[i].ring].from_a == rings[rest[j].ring].from_a) {
      same_set = true;
      return;
    }
    auto cut = [&](std::uint32_t k, Point2 q) {
      if (!(q == from[k]) && !(q == to[k])) cuts.push_back({rest[k].ring, rest[k].at, q});
    };
    if (c == Contact::kProper) {
      const Point2 q = crossing_point(from[i], to[i], from[j], to[j]);
      cut(i, q);
      cut(j, q);
    } else {
      for (const Point2 q : {from[j], to[j]})
        if (in_interior(from[i], to[i], q)) cut(i, q);
      for (const Point2 q : {from[i], to[i]})
        if (in_interior(from[j], to[j], q)) cut(j, q);
    }
  });
  return same_set ? "a set's own boundary crosses itself" : nullptr;
}

// Inserts the cuts into their segments, in order along each.
const char* insert_cuts(std::vector<Ring>& rings, std::vector<Cut>& cuts) {
  std::sort(cuts.begin(), cuts.end(), [&](const Cut& x, const Cut& y) {
    if (x.ring != y.ring) return x.ring < y.ring;
    if (x.at != y.at) return x.at < y.at;
    const Point2 a0 = rings[x.ring].p[x.at];
    const double dx = dist(a0, x.q), dy = dist(a0, y.q);
    if (dx != dy) return dx < dy;
    return lex_less(x.q, y.q);
  });
  std::size_t q = 0;
  for (std::uint32_t r = 0; r < rings.size() && q < cuts.size(); ++r) {
    if (cuts[q].ring != r) continue;
    const auto& p = rings[r].p;
    std::vector<Point2> out;
    out.reserve(p.size() + 8);
    for (std::uint32_t i = 0; i < p.size(); ++i) {
      out.push_back(p[i]);
      for (; q < cuts.size() && cuts[q].ring == r && cuts[q].at == i; ++q) {
        const Point2 c = cuts[q].q;
        if (!(out.back() == c) && !(c == p[(i + 1) % p.size()])) out.push_back(c);
      }
    }
    rings[r].p.swap(out);
    if (!tidy(rings[r].p)) return "a ring collapsed when cut";
  }
  return nullptr;
}

// Steps 2 and 3: the shared segments cancel (the same direction in both sets means b lies
// beside a there); the rest must meet at shared ends only, so where a segment of b crosses or
// touches one of a (b sticking out of a at a reflex corner by more than eps), the contact is
// cut into both and the round is redone, at most 4 times.
const char* meet_exactly(std::vector<Ring>& rings, std::vector<Edge>& rest, ContainedDifferenceStats& st) {
  for (int round = 0;; ++round) {
    std::size_t cancelled = 0;
    if (const char* why = cancel_shared(rings, rest, cancelled)) return why;
    st.cancelled = cancelled;
    if (rest.empty()) return nullptr;
    std::vector<Cut> cuts;
    if (const char* why = find_cuts(rings, rest, cuts)) return why;
    if (cuts.empty()) return nullptr;
    if (round >= 4) return "the boundaries still cross after 4 rounds of cuts";
    st.cut += cuts.size();
    if (const char* why = insert_cuts(rings, cuts)) return why;
  }
}

// Segment indices sorted by one end (then by index), for finding the segments at a vertex.
std::vector<std::uint32_t> order_by_end(const std::vector<Edge>& rest, Point2 Edge::*end) {
  std::vector<std::uint32_t> ord(rest.size());
  for (std::uint32_t i = 0; i < ord.size(); ++i) ord[i] = i;
  std::sort(ord.begin(), ord.end(), [&](std::uint32_t i, std::uint32_t j) {
    if (!(rest[i].*end == rest[j].*end)) return lex_less(rest[i].*end, rest[j].*end);
    return i < j;
  });
  return ord;
}

// Step 4: from each segment u -> v on to the segment leaving v that turns left most sharply
// (the first clockwise from v -> u). Where several segments meet (a pinch, or a cut crossing),
// the segment into v is followed by the first ray clockwise from it when that ray leaves v (the
// wedge between them, on the left of both, is in a - b); when that ray also enters v, the
// segment bounds a sliver of b outside a on its right, and is followed by the first ray
// counter-clockwise.
const char* link_segments(const std::vector<Edge>& rest, std::vector<std::uint32_t>& next) {
  const std::vector<std::uint32_t> out_ord = order_by_end(rest, &Edge::u), in_ord = order_by_end(rest, &Edge::v);
  auto first_at = [&](const std::vector<std::uint32_t>& ord, Point2 Edge::*end, Point2 v) {
    return std::lower_bound(ord.begin(), ord.end(), v,
                            [&](std::uint32_t i, Point2 p) { return lex_less(rest[i].*end, p); });
  };
  std::vector<std::uint32_t> in_count(rest.size(), 0);
  next.assign(rest.size(), 0);
  for (std::uint32_t i = 0; i < rest.size(); ++i) {
    const Point2 u = rest[i].u, v = rest[i].v;
    auto it = first_at(out_ord, &Edge::u, v);
    if (it == out_ord.end() || !(rest[*it].u == v)) return "a ring does not close";
    auto end = it;
    while (end != out_ord.end() && rest[*end].u == v) ++end;
    if (end - it == 1) {
      next[i] = *it;
      ++in_count[*it];
      continue;
    }
    // Every ray at v but this segment's own: (far end, leaves v?, segment).
    std::vector<std::tuple<Point2, bool, std::uint32_t>> rays;
    for (auto o = it; o != end; ++o) rays.emplace_back(rest[*o].v, true, *o);
    for (auto in0 = first_at(in_ord, &Edge::v, v); in0 != in_ord.end() && rest[*in0].v == v; ++in0)
      if (*in0 != i) rays.emplace_back(rest[*in0].u, false, *in0);
    std::size_t cw = 0, ccw = 0;
    for (std::size_t k = 1; k < rays.size(); ++k) {
      if (cw_before(v, u, std::get<0>(rays[k]), std::get<0>(rays[cw]))) cw = k;
      if (cw_before(v, u, std::get<0>(rays[ccw]), std::get<0>(rays[k]))) ccw = k;
    }
    const std::size_t pick = std::get<1>(rays[cw]) ? cw : ccw;
    if (!std::get<1>(rays[pick])) return "no segment leaves a vertex beside the one entering it";
    next[i] = std::get<2>(rays[pick]);
    ++in_count[next[i]];
  }
  for (const std::uint32_t c : in_count)
    if (c != 1) return "two faces leave a vertex by one segment";
  return nullptr;
}

struct Loop {
  std::vector<Point2> p;
  int o = 0;  // +1 counter-clockwise, -1 clockwise, 0 dropped
};

// The closed walks along `next`, each split into simple loops; loop_of[segment] = its loop.
const char* trace_loops(const std::vector<Edge>& rest, const std::vector<std::uint32_t>& next,
                        std::vector<Loop>& loops, std::vector<std::uint32_t>& loop_of) {
  std::vector<char> seen(rest.size(), 0);
  loop_of.assign(rest.size(), 0);
  std::vector<std::uint32_t> walk;
  for (std::uint32_t s0 = 0; s0 < rest.size(); ++s0) {
    if (seen[s0]) continue;
    walk.clear();
    for (std::uint32_t e = s0; !seen[e]; e = next[e]) {
      seen[e] = 1;
      walk.push_back(e);
    }
    if (!(rest[walk.back()].v == rest[walk.front()].u)) return "a walk does not close";
    for (const auto& part : split_closed_walk(walk, rest)) {
      Loop l;
      for (const std::uint32_t e : part) l.p.push_back(rest[e].u);
      if (l.p.size() < 3) return "a degenerate loop";
      l.o = orientation(l.p);
      if (l.o == 0) return "a loop without area";
      for (const std::uint32_t e : part) loop_of[e] = static_cast<std::uint32_t>(loops.size());
      loops.push_back(std::move(l));
    }
  }
  return nullptr;
}

// The segments listed by bands of y (each in every band its y range meets), for winding sums
// along rays to +x.
class YBands {
 public:
  explicit YBands(const std::vector<Edge>& rest) : rest_(rest) {
    Box2 all;
    for (const Edge& e : rest) all.add(e.u), all.add(e.v);
    nb_ = std::clamp<std::size_t>(rest.size() / 16, 1, 1u << 16);
    y0_ = all.lo.y;
    bh_ = std::max(all.height() / static_cast<double>(nb_), 1e-300);
    start_.assign(nb_ + 1, 0);
    for (const Edge& e : rest)
      for (std::size_t k = band(std::min(e.u.y, e.v.y)); k <= band(std::max(e.u.y, e.v.y)); ++k) ++start_[k + 1];
    for (std::size_t k = 0; k < nb_; ++k) start_[k + 1] += start_[k];
    list_.resize(start_[nb_]);
    std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
    for (std::uint32_t i = 0; i < rest.size(); ++i)
      for (std::size_t k = band(std::min(rest[i].u.y, rest[i].v.y)); k <= band(std::max(rest[i].u.y, rest[i].v.y)); ++k)
        list_[fill[k]++] = i;
  }

  // The sum of the winding numbers around q of the segments not on loop `skip` (exact, by a ray
  // to +x from q); nullopt when q lies on one of them.
  std::optional<int> winding_of_others(Point2 q, std::uint32_t skip, const std::vector<std::uint32_t>& loop_of) const {
    const std::size_t k = band(q.y);
    int w = 0;
    for (std::uint32_t x = start_[k]; x < start_[k + 1]; ++x) {
      const std::uint32_t i = list_[x];
      if (loop_of[i] == skip) continue;
      const Point2 p = rest_[i].u, r = rest_[i].v;
      if (p == q || r == q) return std::nullopt;
      if (std::max(p.x, r.x) < q.x) continue;
      if (p.y <= q.y) {
        if (r.y > q.y) {
          const int o = orient2d(p, r, q);
          if (o > 0) ++w;
          else if (o == 0) return std::nullopt;
        }
      } else if (r.y <= q.y) {
        const int o = orient2d(p, r, q);
        if (o < 0) --w;
        else if (o == 0) return std::nullopt;
      }
      if (p.y == q.y && r.y == q.y && std::min(p.x, r.x) <= q.x && q.x <= std::max(p.x, r.x)) return std::nullopt;
    }
    return w;
  }

 private:
  std::size_t band(double y) const {
    return static_cast<std::size_t>(std::clamp(std::floor((y - y0_) / bh_), 0.0, static_cast<double>(nb_ - 1)));
  }
  const std::vector<Edge>& rest_;
  std::size_t nb_ = 1;
  double y0_ = 0, bh_ = 1;
  std::vector<std::uint32_t> start_, list_;
};

// Step 5: which loops bound a - b. The loops are the boundary of [a] - [b] (each segment has
// the larger value on its left), so at a point the value is the sum of the winding numbers of
// the loops around it. At a vertex of loop L on no other loop, the other loops' sum c is the
// value just outside L: a counter-clockwise L bounds a - b when c = 0 (inside it the value is
// 1) and the hole of a sliver of b outside a when c = -1; a clockwise L is a hole of a - b when
// c = 1 and the edge of a sliver of b outside a when c = 0 (offsets that approximate arcs by
// chords cut reflex corners by a hair). Dropped loops get o = 0.
const char* judge_loops(const std::vector<Edge>& rest, const std::vector<std::uint32_t>& loop_of,
                        std::vector<Loop>& loops, std::size_t& dropped) {
  const YBands bands(rest);
  for (std::uint32_t li = 0; li < loops.size(); ++li) {
    Loop& l = loops[li];
    std::optional<int> c;
    for (std::size_t t = 0; t < l.p.size() && !c; ++t) c = bands.winding_of_others(l.p[t], li, loop_of);
    if (!c) return "a loop lies on other loops at every vertex";
    if (l.o > 0 ? *c == 0 : *c == 1) continue;  // kept
    if (l.o > 0 ? *c == -1 : *c == 0) {
      l.o = 0;
      ++dropped;
      continue;
    }
    return "the loops nest inconsistently";
  }
  return nullptr;
}

// The index of the smallest shell around a hole, judged at its first vertex on no shell; -1
// when there is no such vertex or no shell around it.
std::ptrdiff_t hole_owner(const std::vector<Point2>& hole, const std::vector<std::vector<Point2>>& shells,
                          const std::vector<Box2>& sbox, const std::vector<double>& sarea, const CellIndex& sidx) {
  for (const Point2 p : hole) {
    double best = std::numeric_limits<double>::infinity();
    std::ptrdiff_t who = -1;
    bool on = false;
    sidx.near_point(p, [&](std::uint32_t i) {
      if (on || !sbox[i].contains(p) || !(sarea[i] < best)) return;
      const int l = locate(p, shells[i]);
      if (l == 0) {
        on = true;
      } else if (l > 0) {
        best = sarea[i];
        who = static_cast<std::ptrdiff_t>(i);
      }
    });
    if (!on) return who;
  }
  return -1;
}

// Step 6: the kept loops as polygons, each hole in the smallest shell around it; shells
// clockwise and holes counter-clockwise, as the callers want them.
const char* nest_holes(std::vector<Loop>& loops, PolygonSet& out) {
  std::vector<std::vector<Point2>> shells, holes;
  for (Loop& l : loops) {
    if (l.o > 0) shells.push_back(std::move(l.p));
    else if (l.o < 0) holes.push_back(std::move(l.p));
  }
  loops.clear();
  std::vector<Box2> sbox(shells.size());
  std::vector<double> sarea(shells.size());
  for (std::size_t i = 0; i < shells.size(); ++i) {
    for (const Point2 q : shells[i]) sbox[i].add(q);
    sarea[i] = std::fabs(area2(shells[i]));
  }
  std::vector<std::vector<std::size_t>> shell_holes(shells.size());
  if (!holes.empty()) {
    std::vector<Point2> lo(shells.size()), hi(shells.size());
    for (std::size_t i = 0; i < shells.size(); ++i) lo[i] = sbox[i].lo, hi[i] = sbox[i].hi;
    const CellIndex sidx(lo, hi, 0.0);
    for (std::size_t h = 0; h < holes.size(); ++h) {
      const std::ptrdiff_t owner = hole_owner(holes[h], shells, sbox, sarea, sidx);
      if (owner < 0) return "a hole of a - b inside no shell";
      shell_holes[static_cast<std::size_t>(owner)].push_back(h);
    }
  }
  out.clear();
  out.reserve(shells.size());
  for (std::size_t i = 0; i < shells.size(); ++i) {
    PolygonRings pr;
    pr.push_back(std::move(shells[i]));
    std::reverse(pr.back().begin(), pr.back().end());
    for (const std::size_t h : shell_holes[i]) {
      pr.push_back(std::move(holes[h]));
      std::reverse(pr.back().begin(), pr.back().end());
    }
    out.push_back(std::move(pr));
  }
  return nullptr;
}

// Every step in turn; returns why it gave up, else null with the result in out.
const char* run_steps(PolygonSet& a, PolygonSet& b, double eps, ContainedDifferenceStats& st, PolygonSet& out) {
  std::vector<Ring> rings;
  if (const char* why = input_rings(a, b, rings)) return why;
  // 1. Near contacts made exact: a's vertices onto b's vertices, then each side's vertices into
  // the other's segments.
  if (eps > 0) {
    if (const char* why = snap_a_onto_b(rings, eps, st.snapped)) return why;
    st.inserted += insert_near(rings, true, eps);
    st.inserted += insert_near(rings, false, eps);
  }
  if (const char* why = orient_rings(rings)) return why;
  std::vector<Edge> rest;
  if (const char* why = meet_exactly(rings, rest, st)) return why;
  out.clear();
  if (rest.empty()) return nullptr;
  std::vector<std::uint32_t> next, loop_of;
  if (const char* why = link_segments(rest, next)) return why;
  std::vector<Loop> loops;
  if (const char* why = trace_loops(rest, next, loops, loop_of)) return why;
  if (const char* why = judge_loops(rest, loop_of, loops, st.dropped)) return why;
  return nest_holes(loops, out);
}

}  // namespace
}  // namespace cd_steps

std::optional<PolygonSet> contained_difference(PolygonSet a, PolygonSet b, double eps, ContainedDifferenceStats* stats) {
  // The predicate counters report the mesher's decisions: this one's are not counted (they
  // would depend on which thread ran it).
  struct KeepCounters {
    predicates::Counters saved = predicates::counters();
    ~KeepCounters() { predicates::counters() = saved; }
  } keep_counters;
  ContainedDifferenceStats st;
  PolygonSet out;
  st.refused = cd_steps::run_steps(a, b, eps, st, out);
  if (stats) *stats = st;
  if (st.refused) return std::nullopt;
  return out;
}

}  // namespace fdr::pslg
