// CDT construction: incremental insertion in a biased randomized Hilbert order, segment recovery by edge flips
// (regions.cpp then removes the regions outside the domain).
#include "cdt/cdt.hpp"
#include <algorithm>
#include <bit>
#include <cmath>
#include <deque>
#include <sstream>
#include "base/error.hpp"
#include "cdt/insert.hpp"
#include "cdt/locate.hpp"
#include "cdt/steps.hpp"
#include "predicates/predicates.hpp"

namespace fdr::cdt {

std::string point_text(Point2 p) {
  std::ostringstream s;
  s.precision(15);
  s << "(" << p.x << ", " << p.y << ")";
  return s.str();
}
using mesh::Triangulation;
using mesh::VertexKind;
using predicates::diametral;
using predicates::incircle;
using predicates::orient2d;

namespace {


// Hilbert index of (x, y) in a 2^16 grid: insertion order with good locality for walking.
std::uint64_t hilbert(std::uint32_t x, std::uint32_t y) {
  std::uint64_t d = 0;
  for (std::uint32_t s = 1u << 15; s > 0; s >>= 1) {
    const std::uint32_t rx = (x & s) ? 1 : 0, ry = (y & s) ? 1 : 0;
    d += static_cast<std::uint64_t>(s) * s * ((3 * rx) ^ ry);
    if (ry == 0) {
      if (rx == 1) { x = s - 1 - x; y = s - 1 - y; }
      std::swap(x, y);
    }
  }
  return d;
}

// A fixed mix of a 64-bit value (splitmix64's finaliser): the same pseudo-random rounds on every
// platform, unlike the standard distributions.
std::uint64_t mix(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

[[noreturn]] void crossing_error(const Triangulation& T, Index a, Index b, Index sid, HalfEdge h,
                                 const std::string& source) {
  const Index other = T.segment_of(T.org(h), T.dst(h));
  std::ostringstream s;
  s << source << ": segment " << sid << " " << point_text(T.point(a)) << "-" << point_text(T.point(b)) << " crosses ";
  if (other < T.input_segments().size())
    s << "segment " << other << " " << point_text(T.point(T.input_segments()[other].a)) << "-"
      << point_text(T.point(T.input_segments()[other].b));
  else
    s << "a constrained edge";
  s << " near " << point_text(T.point(T.org(h))) << "-" << point_text(T.point(T.dst(h)));
  throw Error(ExitCode::kInvalidGeometry, s.str());
}

void mark_constrained(Triangulation& T, HalfEdge h, Index sid, const std::string& source) {
  if (T.constrained(h)) {
    // Already part of another input segment: the two segments overlap (or repeat).
    const Index other = T.segment_of(T.org(h), T.dst(h));
    if (other != sid && other < T.input_segments().size()) {
      const auto& o = T.input_segments()[other];
      throw Error(ExitCode::kInvalidGeometry,
                  source + ": segment " + std::to_string(sid) + " overlaps segment " + std::to_string(other) +
                      " " + point_text(T.point(o.a)) + "-" + point_text(T.point(o.b)) + " along " + point_text(T.point(T.org(h))) + "-" +
                      point_text(T.point(T.dst(h))));
    }
  }
  T.set_constrained(h, true);
  if (T.twin(h) != kNoId) T.set_constrained(T.twin(h), true);
  T.set_segment(T.org(h), T.dst(h), sid);
}

}  // namespace

void insert_segment(Triangulation& T, Index a, Index b, Index sid, const std::string& source, CdtStats* stats) {
  std::size_t guard = 0;
  while (a != b) {
    if (++guard > T.num_vertices() + 2) throw Error(ExitCode::kInternal, source + ": segment insertion did not finish");
    // Rotate around a to find the edge a-b, a vertex on the segment, or the wedge containing b.
    const HalfEdge h0 = T.vertex_edge(a);
    HalfEdge h = h0, start = kNoId;
    Index next_a = kNoId;
    do {
      if (stats) ++stats->recovery_steps;
      const Index u = T.dst(h), w = T.apex(h);
      if (u == b) { mark_constrained(T, h, sid, source); return; }
      if (orient2d(T.point(a), T.point(b), T.point(u)) == 0 && diametral(T.point(a), T.point(b), T.point(u)) > 0) {
        mark_constrained(T, h, sid, source);  // u lies on the segment: split it there
        if (stats) ++stats->segments_split_at_vertices;
        next_a = u;
        break;
      }
      if (orient2d(T.point(a), T.point(u), T.point(b)) > 0 && orient2d(T.point(a), T.point(w), T.point(b)) < 0) {
        start = h;
        break;
      }
      h = T.twin(mesh::prev_he(h));
    } while (h != h0 && h != kNoId);
    if (next_a != kNoId) { a = next_a; continue; }
    if (start == kNoId) throw Error(ExitCode::kInternal, source + ": segment " + std::to_string(sid) + " start not found");
    // Walk along a-b collecting the crossed edges (as vertex pairs: flips renumber half-edges)
    // up to b or to the first vertex lying on the segment.
    std::deque<std::pair<Index, Index>> crossing;
    HalfEdge cur = mesh::next_he(start);  // right -> left
    Index end = kNoId;
    while (true) {
      if (stats) ++stats->recovery_steps;
      if (T.constrained(cur)) crossing_error(T, a, b, sid, cur, source);
      crossing.push_back({T.org(cur), T.dst(cur)});
      const HalfEdge n = T.twin(cur);
      if (n == kNoId) throw Error(ExitCode::kInternal, source + ": segment walk left the mesh");
      const Index o = T.apex(n);
      if (o == b) { end = b; break; }
      const int s = orient2d(T.point(a), T.point(b), T.point(o));
      if (s == 0) { end = o; if (stats) ++stats->segments_split_at_vertices; break; }
      cur = s > 0 ? mesh::next_he(n) : mesh::prev_he(n);
    }
    // Sloan's edge flipping: flip crossed edges whose quadrilateral is strictly convex until
    // none crosses a-end (always possible, so the loop ends); then Lawson flips restore the
    // constrained Delaunay property around the new edges. Unlike re-triangulating the two
    // pseudo-polygons, this needs no simple-polygon assumption (a vertex whose whole star is
    // crossed, with its edges hanging into the cavity, is handled like any other).
    const Point2 pa = T.point(a), pe = T.point(end);
    std::vector<std::pair<Index, Index>> fresh;
    std::size_t stall = 0;
    while (!crossing.empty()) {
      if (++stall > crossing.size() + 1)  // a whole pass without a flip: impossible in theory
        throw Error(ExitCode::kInternal, source + ": segment recovery by flips did not converge");
      const auto [u, w] = crossing.front();
      crossing.pop_front();
      if (stats) ++stats->recovery_steps;
      const HalfEdge e = T.find_edge(u, w);
      if (e == kNoId) continue;
      const Index c = T.apex(e), d = T.apex(T.twin(e));
      // Convex iff the diagonal c-d separates u and w strictly.
      if (orient2d(T.point(c), T.point(d), T.point(u)) * orient2d(T.point(c), T.point(d), T.point(w)) >= 0) {
        crossing.push_back({u, w});
        continue;
      }
      flip_edge(T, e);
      stall = 0;
      const int sc = orient2d(pa, pe, T.point(c)), sd = orient2d(pa, pe, T.point(d));
      if ((c == a || c == end || d == a || d == end) || sc * sd >= 0) fresh.push_back({c, d});
      else crossing.push_back({c, d});
    }
    const HalfEdge ae = T.find_edge(a, end);
    if (ae == kNoId) throw Error(ExitCode::kInternal, source + ": recovered segment edge missing");
    mark_constrained(T, ae, sid, source);
    // Lawson: restore local Delaunay on the new edges (constrained edges are never flipped).
    while (!fresh.empty()) {
      const auto [u, w] = fresh.back();
      fresh.pop_back();
      if (stats) ++stats->recovery_steps;
      const HalfEdge e = T.find_edge(u, w);
      if (e == kNoId || T.constrained(e) || T.twin(e) == kNoId) continue;
      const Index c = T.apex(e), d = T.apex(T.twin(e));
      if (incircle(T.point(u), T.point(w), T.point(c), T.point(d)) <= 0) continue;
      flip_edge(T, e);
      fresh.push_back({u, c});
      fresh.push_back({c, w});
      fresh.push_back({w, d});
      fresh.push_back({d, u});
    }
    a = end;
  }
}

namespace {

// The bounding box of the input points; throws on too few points or a non-finite coordinate.
Box2 check_points(const pslg::Pslg& in, const std::string& source) {
  const std::size_t n = in.points.size();
  if (n < 3) throw Error(ExitCode::kInvalidGeometry, source + ": needs at least 3 vertices, got " + std::to_string(n));
  Box2 box;
  for (std::size_t i = 0; i < n; ++i) {
    const Point2 p = in.points[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y))
      throw Error(ExitCode::kInvalidGeometry, source + ": vertex " + std::to_string(i) + " has a non-finite coordinate");
    box.add(p);
  }
  return box;
}

}  // namespace

void start_triangulation(Triangulation& T, const pslg::Pslg& in, const Box2& box) {
  const std::size_t n = in.points.size();
  T.origin = in.origin;
  T.reserve(0, n + 3);
  for (std::size_t i = 0; i < n; ++i) {
    T.add_vertex(in.points[i], VertexKind::kInput);
    if (!in.point_markers.empty()) T.set_point_marker(static_cast<Index>(i), in.point_markers[i]);
  }
  // Super-triangle far outside the box; exact predicates make its size irrelevant to correctness.
  double d = std::max(box.width(), box.height());
  if (!(d > 0)) d = 1;
  const Point2 c = box.center();
  const Index s0 = T.add_vertex({c.x - 64 * d, c.y - 48 * d}, VertexKind::kSuper);
  const Index s1 = T.add_vertex({c.x + 64 * d, c.y - 48 * d}, VertexKind::kSuper);
  const Index s2 = T.add_vertex({c.x, c.y + 96 * d}, VertexKind::kSuper);
  T.new_triangle(s0, s1, s2);
}

std::vector<Index> insertion_order(const std::vector<Point2>& points, const Box2& box, bool rounds) {
  const std::size_t n = points.size();
  // A point's round comes from the trailing one bits of a hash of its index: about half the
  // points are in the last round, a quarter in the one before, ...; rounds beyond
  // log2(n / kFirstRound) merge into the first, and an input under 2 * kFirstRound points is a
  // single round.
  constexpr std::size_t kFirstRound = 64;
  int levels = 0;
  while (rounds && (kFirstRound << (levels + 1)) <= n) ++levels;
  struct Key {
    int round;
    std::uint64_t hilbert;
    Index id;
  };
  std::vector<Key> keys(n);
  const double sx = box.width() > 0 ? 65535.0 / box.width() : 0, sy = box.height() > 0 ? 65535.0 / box.height() : 0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto hx = static_cast<std::uint32_t>((points[i].x - box.lo.x) * sx);
    const auto hy = static_cast<std::uint32_t>((points[i].y - box.lo.y) * sy);
    int round = 0;
    if (levels > 0) round = levels - std::min(levels, std::countr_one(mix(i)));
    keys[i] = {round, hilbert(hx, hy), static_cast<Index>(i)};
  }
  std::sort(keys.begin(), keys.end(), [](const Key& a, const Key& b) {
    return a.round != b.round ? a.round < b.round : a.hilbert != b.hilbert ? a.hilbert < b.hilbert : a.id < b.id;
  });
  std::vector<Index> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = keys[i].id;
  return order;
}

// Inserts the points in `order`; false (the triangulation half built) as soon as the work, walk
// steps plus new triangles, exceeds work_per_point per point inserted so far plus a start
// allowance (0: no limit).
bool insert_in_order(Triangulation& T, const pslg::Pslg& in, const std::vector<Index>& order,
                     std::size_t work_per_point, std::vector<Index>* alias, const std::string& source,
                     CdtStats* stats) {
  Inserter ins(T);
  TriangleId last = 0;
  std::size_t work = 0, budget = 4096;
  for (const Index i : order) {
    budget += work_per_point;
    const Point2 p = in.points[i];
    std::size_t steps = 0;
    Location loc = locate_visibility(T, last, p, &steps);
    work += steps;
    if (stats) stats->walk_steps += steps;
    if (loc.kind == LocateKind::kOnVertex) {
      (*alias)[i] = T.org(loc.he);
      if (stats) ++stats->duplicate_points;
      continue;
    }
    if (!ins.build_cavity(p, loc))
      throw Error(ExitCode::kInternal, source + ": could not insert vertex " + std::to_string(i) + " " + point_text(p));
    ins.commit_vertex(i);
    work += ins.new_triangles().size();
    if (stats) stats->new_triangles += ins.new_triangles().size();
    if (work_per_point > 0 && work > budget) return false;
    last = ins.new_triangles().front();
  }
  return true;
}

std::vector<Index> insert_points(Triangulation& T, const pslg::Pslg& in, const Box2& box, const std::string& source,
                                 CdtStats* stats) {
  const std::size_t n = in.points.size();
  std::vector<Index> alias(n);
  for (std::size_t i = 0; i < n; ++i) alias[i] = static_cast<Index>(i);
  // Why two orders: along the Hilbert curve alone, a chain of points inserted one after the
  // other beside a dense chain (the far side of a finely resampled square) takes over most of
  // its neighbour's fan at every step, a quadratic total. Random rounds (a
  // biased randomized insertion order, Amenta, Choi and Rote 2003) bound the expected work on
  // any input, but give cocircular points another of their equally valid triangulations and
  // every triangle another slot, which the refinement's order follows; so the Hilbert order is
  // kept for the inputs it handles in linear work, and the points are inserted anew in random
  // rounds as soon as its work exceeds kWorkPerPoint per point (coastlines take about 12).
  constexpr std::size_t kWorkPerPoint = 24;
  const std::size_t duplicates = stats ? stats->duplicate_points : 0;
  if (insert_in_order(T, in, insertion_order(in.points, box, false), kWorkPerPoint, &alias, source, stats))
    return alias;
  T = Triangulation{};
  start_triangulation(T, in, box);
  for (std::size_t i = 0; i < n; ++i) alias[i] = static_cast<Index>(i);
  if (stats) {
    stats->duplicate_points = duplicates;
    stats->random_rounds = true;
  }
  insert_in_order(T, in, insertion_order(in.points, box, true), 0, &alias, source, stats);
  return alias;
}

void insert_segments(Triangulation& T, const pslg::Pslg& in, const std::vector<Index>& alias,
                     const std::string& source, CdtStats* stats) {
  const std::size_t n = in.points.size();
  T.reserve_input_segments(in.segments.size());
  for (std::size_t s = 0; s < in.segments.size(); ++s) {
    const auto& sg = in.segments[s];
    if (sg.a >= n || sg.b >= n)
      throw Error(ExitCode::kInvalidGeometry, source + ": segment " + std::to_string(s) + " has a vertex index out of range");
    T.add_input_segment({alias[sg.a], alias[sg.b], sg.marker, sg.part});
  }
  for (std::size_t s = 0; s < T.input_segments().size(); ++s) {
    const auto sg = T.input_segments()[s];
    if (sg.a == sg.b) continue;
    insert_segment(T, sg.a, sg.b, static_cast<Index>(s), source, stats);
  }
}

Triangulation build_cdt(const pslg::Pslg& in, const CdtOptions& opt, CdtStats* stats) {
  if (opt.resolve) {
    pslg::ResolveOptions ro;
    ro.source = opt.source;
    const pslg::Pslg resolved = pslg::resolve(in, ro, opt.repairs);
    CdtOptions o2 = opt;
    o2.resolve = false;
    return build_cdt(resolved, o2, stats);
  }
  CdtStats local;
  if (!stats) stats = &local;
  const Box2 box = check_points(in, opt.source);
  Triangulation T;
  start_triangulation(T, in, box);
  const std::vector<Index> alias = insert_points(T, in, box, opt.source, stats);
  insert_segments(T, in, alias, opt.source, stats);
  remove_regions(T, in, opt, stats);
  T.rebuild_vertex_map();
  return T;
}

}  // namespace fdr::cdt
