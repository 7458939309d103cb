// CDT construction: Hilbert-ordered incremental insertion, segment recovery by cavity
// re-triangulation (Anglada's pseudo-polygon algorithm), region removal by seeds or parity.
#include "cdt/cdt.hpp"
#include <algorithm>
#include <cmath>
#include <deque>
#include <sstream>
#include <unordered_map>
#include "base/error.hpp"
#include "cdt/insert.hpp"
#include "cdt/locate.hpp"
#include "predicates/predicates.hpp"

namespace fdr::cdt {
using mesh::Triangulation;
using mesh::VertexKind;
using predicates::diametral;
using predicates::incircle;
using predicates::orient2d;

namespace {

std::string pt(Point2 p) {
  std::ostringstream s;
  s.precision(15);
  s << "(" << p.x << ", " << p.y << ")";
  return s.str();
}

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

// Triangulates the pseudo-polygon a -> e with `chain` (from a to e) lying left of a->e.
void triangulate_left(Triangulation& T, Index a, Index e, const Index* chain, std::size_t n,
                      std::vector<std::array<Index, 3>>& out) {
  if (n == 0) return;
  std::size_t ci = 0;
  for (std::size_t i = 1; i < n; ++i)
    if (incircle(T.pts[a], T.pts[e], T.pts[chain[ci]], T.pts[chain[i]]) > 0) ci = i;
  const Index c = chain[ci];
  out.push_back({a, e, c});
  triangulate_left(T, a, c, chain, ci, out);
  triangulate_left(T, c, e, chain + ci + 1, n - ci - 1, out);
}

[[noreturn]] void crossing_error(const Triangulation& T, Index a, Index b, Index sid, HalfEdge h,
                                 const std::string& source) {
  auto it = T.seg_of.find(mesh::edge_key(T.org(h), T.dst(h)));
  std::ostringstream s;
  s << source << ": segment " << sid << " " << pt(T.pts[a]) << "-" << pt(T.pts[b]) << " crosses ";
  if (it != T.seg_of.end())
    s << "segment " << it->second << " " << pt(T.pts[T.input_segments[it->second].a]) << "-"
      << pt(T.pts[T.input_segments[it->second].b]);
  else
    s << "a constrained edge";
  s << " near " << pt(T.pts[T.org(h)]) << "-" << pt(T.pts[T.dst(h)]);
  throw Error(ExitCode::kInvalidGeometry, s.str());
}

void mark_constrained(Triangulation& T, HalfEdge h, Index sid) {
  T.set_constrained(h, true);
  if (T.twin[h] != kNoId) T.set_constrained(T.twin[h], true);
  T.seg_of[mesh::edge_key(T.org(h), T.dst(h))] = sid;
}

}  // namespace

void insert_segment(Triangulation& T, Index a, Index b, Index sid, const std::string& source, CdtStats* stats) {
  std::vector<Index> left, right;
  std::vector<TriangleId> crossed;
  std::vector<std::array<Index, 3>> tris;
  std::size_t guard = 0;
  while (a != b) {
    if (++guard > T.pts.size() + 2) throw Error(ExitCode::kInternal, source + ": segment insertion did not finish");
    // Rotate around a to find the edge a-b, a vertex on the segment, or the wedge containing b.
    const HalfEdge h0 = T.vhe[a];
    HalfEdge h = h0, start = kNoId;
    Index next_a = kNoId;
    do {
      const Index u = T.dst(h), w = T.apex(h);
      if (u == b) { mark_constrained(T, h, sid); return; }
      if (orient2d(T.pts[a], T.pts[b], T.pts[u]) == 0 && diametral(T.pts[a], T.pts[b], T.pts[u]) > 0) {
        mark_constrained(T, h, sid);  // u lies on the segment: split it there
        if (stats) ++stats->segments_split_at_vertices;
        next_a = u;
        break;
      }
      if (orient2d(T.pts[a], T.pts[u], T.pts[b]) > 0 && orient2d(T.pts[a], T.pts[w], T.pts[b]) < 0) {
        start = h;
        break;
      }
      h = T.twin[mesh::prev_he(h)];
    } while (h != h0 && h != kNoId);
    if (next_a != kNoId) { a = next_a; continue; }
    if (start == kNoId) throw Error(ExitCode::kInternal, source + ": segment " + std::to_string(sid) + " start not found");
    // Walk through the triangles crossed by a-b; u (right) / w (left) are the crossed edge's ends.
    left.clear(); right.clear(); crossed.clear();
    crossed.push_back(mesh::tri_of(start));
    right.push_back(T.dst(start));
    left.push_back(T.apex(start));
    HalfEdge cur = mesh::next_he(start);  // u -> w
    Index end = kNoId;
    while (true) {
      if (T.constrained(cur)) crossing_error(T, a, b, sid, cur, source);
      const HalfEdge n = T.twin[cur];
      if (n == kNoId) throw Error(ExitCode::kInternal, source + ": segment walk left the mesh");
      crossed.push_back(mesh::tri_of(n));
      const Index o = T.apex(n);
      if (o == b) { end = b; break; }
      const int s = orient2d(T.pts[a], T.pts[b], T.pts[o]);
      if (s == 0) { end = o; if (stats) ++stats->segments_split_at_vertices; break; }
      if (s > 0) { left.push_back(o); cur = mesh::next_he(n); }
      else { right.push_back(o); cur = mesh::prev_he(n); }
    }
    // Record the rim of the crossed region (edge -> outside twin) before freeing it.
    for (TriangleId t : crossed) T.flags[t] |= Triangulation::kMarkA;
    std::unordered_map<std::uint64_t, std::pair<HalfEdge, bool>> rim;
    for (TriangleId t : crossed)
      for (int k = 0; k < 3; ++k) {
        const HalfEdge e = 3 * t + static_cast<Index>(k);
        const HalfEdge n = T.twin[e];
        if (n != kNoId && (T.flags[mesh::tri_of(n)] & Triangulation::kMarkA)) continue;
        rim[(static_cast<std::uint64_t>(T.org(e)) << 32) | T.dst(e)] = {n, T.constrained(e)};
      }
    for (TriangleId t : crossed) T.kill_triangle(t);
    tris.clear();
    triangulate_left(T, a, end, left.data(), left.size(), tris);
    std::reverse(right.begin(), right.end());
    triangulate_left(T, end, a, right.data(), right.size(), tris);
    std::unordered_map<std::uint64_t, HalfEdge> open;
    for (const auto& tv : tris) {
      const TriangleId t = T.new_triangle(tv[0], tv[1], tv[2]);
      for (int k = 0; k < 3; ++k) {
        const HalfEdge e = 3 * t + static_cast<Index>(k);
        const Index x = T.org(e), y = T.dst(e);
        auto r = rim.find((static_cast<std::uint64_t>(x) << 32) | y);
        if (r != rim.end()) {
          T.link(e, r->second.first);
          if (r->second.second) T.set_constrained(e, true);
          continue;
        }
        auto o = open.find((static_cast<std::uint64_t>(y) << 32) | x);
        if (o != open.end()) { T.link(e, o->second); open.erase(o); }
        else open[(static_cast<std::uint64_t>(x) << 32) | y] = e;
      }
    }
    const HalfEdge ae = T.find_edge(a, end);
    if (ae == kNoId) throw Error(ExitCode::kInternal, source + ": recovered segment edge missing");
    mark_constrained(T, ae, sid);
    a = end;
  }
}

Triangulation build_cdt(const pslg::Pslg& in, const CdtOptions& opt, CdtStats* stats) {
  CdtStats local;
  if (!stats) stats = &local;
  Triangulation T;
  T.origin = in.origin;
  const std::size_t n = in.points.size();
  if (n < 3) throw Error(ExitCode::kInvalidGeometry, opt.source + ": needs at least 3 vertices, got " + std::to_string(n));
  Box2 box;
  for (std::size_t i = 0; i < n; ++i) {
    const Point2 p = in.points[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y))
      throw Error(ExitCode::kInvalidGeometry, opt.source + ": vertex " + std::to_string(i) + " has a non-finite coordinate");
    box.add(p);
  }
  T.pts.reserve(n + 3);
  for (std::size_t i = 0; i < n; ++i) {
    T.add_vertex(in.points[i], VertexKind::kInput);
    if (!in.point_markers.empty()) T.point_marker[i] = in.point_markers[i];
  }
  // Super-triangle far outside the box; exact predicates make its size irrelevant to correctness.
  double d = std::max(box.width(), box.height());
  if (!(d > 0)) d = 1;
  const Point2 c = box.center();
  const Index s0 = T.add_vertex({c.x - 64 * d, c.y - 48 * d}, VertexKind::kSuper);
  const Index s1 = T.add_vertex({c.x + 64 * d, c.y - 48 * d}, VertexKind::kSuper);
  const Index s2 = T.add_vertex({c.x, c.y + 96 * d}, VertexKind::kSuper);
  T.new_triangle(s0, s1, s2);

  std::vector<std::pair<std::uint64_t, Index>> order(n);
  const double sx = box.width() > 0 ? 65535.0 / box.width() : 0, sy = box.height() > 0 ? 65535.0 / box.height() : 0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto hx = static_cast<std::uint32_t>((in.points[i].x - box.lo.x) * sx);
    const auto hy = static_cast<std::uint32_t>((in.points[i].y - box.lo.y) * sy);
    order[i] = {hilbert(hx, hy), static_cast<Index>(i)};
  }
  std::sort(order.begin(), order.end());
  std::vector<Index> alias(n);
  for (std::size_t i = 0; i < n; ++i) alias[i] = static_cast<Index>(i);
  Inserter ins(T);
  TriangleId last = 0;
  for (const auto& [key, i] : order) {
    const Point2 p = in.points[i];
    Location loc = locate_visibility(T, last, p);
    if (loc.kind == LocateKind::kOnVertex) {
      alias[i] = T.org(loc.he);
      ++stats->duplicate_points;
      continue;
    }
    if (!ins.build_cavity(p, loc))
      throw Error(ExitCode::kInternal, opt.source + ": could not insert vertex " + std::to_string(i) + " " + pt(p));
    // commit appends a new vertex id; re-point the fan to vertex i instead.
    const Index v = ins.commit(p, VertexKind::kInput);
    for (TriangleId t : ins.new_triangles()) {
      T.tv[3 * t + 2] = i;
      T.vhe[i] = 3 * t + 2;
    }
    (void)v;
    T.pts.pop_back(); T.vkind.pop_back(); T.vhe.pop_back(); T.point_marker.pop_back();
    last = ins.new_triangles().front();
  }
  // Segments.
  T.input_segments.reserve(in.segments.size());
  for (std::size_t s = 0; s < in.segments.size(); ++s) {
    const auto& sg = in.segments[s];
    if (sg.a >= n || sg.b >= n)
      throw Error(ExitCode::kInvalidGeometry, opt.source + ": segment " + std::to_string(s) + " has a vertex index out of range");
    T.input_segments.push_back({alias[sg.a], alias[sg.b], sg.marker, sg.part});
  }
  for (std::size_t s = 0; s < T.input_segments.size(); ++s) {
    const auto sg = T.input_segments[s];
    if (sg.a == sg.b) continue;
    insert_segment(T, sg.a, sg.b, static_cast<Index>(s), opt.source, stats);
  }
  // Regions: connected components of triangles across unconstrained edges.
  const std::size_t nt = T.num_slots();
  std::vector<Index> comp(nt, kNoId);
  std::vector<std::vector<Index>> comp_adj;
  std::vector<bool> comp_super;
  std::vector<TriangleId> stack;
  Index ncomp = 0;
  for (TriangleId t0 = 0; t0 < nt; ++t0) {
    if (T.dead(t0) || comp[t0] != kNoId) continue;
    comp_adj.emplace_back();
    comp_super.push_back(false);
    comp[t0] = ncomp;
    stack.push_back(t0);
    while (!stack.empty()) {
      const TriangleId t = stack.back();
      stack.pop_back();
      for (int k = 0; k < 3; ++k) {
        if (T.vkind[T.tv[3 * t + k]] == VertexKind::kSuper) comp_super[ncomp] = true;
        const HalfEdge h = 3 * t + static_cast<Index>(k);
        const HalfEdge w = T.twin[h];
        if (w == kNoId || T.constrained(h)) continue;
        const TriangleId u = mesh::tri_of(w);
        if (comp[u] == kNoId) { comp[u] = ncomp; stack.push_back(u); }
      }
    }
    ++ncomp;
  }
  for (TriangleId t = 0; t < nt; ++t) {
    if (T.dead(t)) continue;
    for (int k = 0; k < 3; ++k) {
      const HalfEdge h = 3 * t + static_cast<Index>(k);
      const HalfEdge w = T.twin[h];
      if (w != kNoId && T.constrained(h) && comp[mesh::tri_of(w)] != comp[t]) comp_adj[comp[t]].push_back(comp[mesh::tri_of(w)]);
    }
  }
  // Nesting depth: breadth-first from the outside, +1 per constraint crossed.
  std::vector<int> depth(ncomp, -1);
  std::deque<Index> q;
  for (Index k = 0; k < ncomp; ++k)
    if (comp_super[k]) { depth[k] = 0; q.push_back(k); }
  while (!q.empty()) {
    const Index k = q.front();
    q.pop_front();
    for (Index j : comp_adj[k])
      if (depth[j] < 0) { depth[j] = depth[k] + 1; q.push_back(j); }
  }
  auto mode = opt.regions;
  if (mode == CdtOptions::Regions::kAuto) {
    if (in.segments.empty()) mode = CdtOptions::Regions::kNone;
    else if (!in.holes.empty()) mode = CdtOptions::Regions::kSeeds;
    else mode = CdtOptions::Regions::kParity;
  }
  std::vector<bool> remove(ncomp, false);
  for (Index k = 0; k < ncomp; ++k) {
    if (mode == CdtOptions::Regions::kParity) remove[k] = depth[k] < 0 || depth[k] % 2 == 0;
    else remove[k] = depth[k] == 0 || depth[k] < 0;
  }
  if (mode == CdtOptions::Regions::kSeeds) {
    for (const Point2& hp : in.holes) {
      if (!std::isfinite(hp.x) || !std::isfinite(hp.y)) continue;
      TriangleId start = 0;
      while (T.dead(start)) ++start;
      const Location loc = locate_visibility(T, start, hp);
      if (loc.he == kNoId) continue;
      remove[comp[mesh::tri_of(loc.he)]] = true;
    }
  }
  // Delete removed triangles; touching super-vertex triangles always go.
  for (TriangleId t = 0; t < nt; ++t) {
    if (T.dead(t)) continue;
    bool sup = false;
    for (int k = 0; k < 3; ++k) sup |= T.vkind[T.tv[3 * t + k]] == VertexKind::kSuper;
    if (!remove[comp[t]] && !sup) continue;
    for (int k = 0; k < 3; ++k) {
      const HalfEdge w = T.twin[3 * t + k];
      if (w != kNoId) T.twin[w] = kNoId;
    }
    T.kill_triangle(t);
    ++stats->removed_triangles;
  }
  // A removed region can leave an unconstrained boundary edge only for kNone (convex hull):
  // mark such edges constrained so refinement treats the hull as a boundary.
  for (TriangleId t = 0; t < nt; ++t) {
    if (T.dead(t)) continue;
    for (int k = 0; k < 3; ++k) {
      const HalfEdge h = 3 * t + static_cast<Index>(k);
      if (T.twin[h] == kNoId && !T.constrained(h)) {
        T.set_constrained(h, true);
        T.seg_of[mesh::edge_key(T.org(h), T.dst(h))] = kNoId;
      }
    }
  }
  T.rebuild_vertex_map();
  return T;
}

}  // namespace fdr::cdt
