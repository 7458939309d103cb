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

void mark_constrained(Triangulation& T, HalfEdge h, Index sid, const std::string& source) {
  if (T.constrained(h)) {
    // Already part of another input segment: the two segments overlap (or repeat).
    auto it = T.seg_of.find(mesh::edge_key(T.org(h), T.dst(h)));
    if (it != T.seg_of.end() && it->second != sid && it->second < T.input_segments.size()) {
      const auto& o = T.input_segments[it->second];
      throw Error(ExitCode::kInvalidGeometry,
                  source + ": segment " + std::to_string(sid) + " overlaps segment " + std::to_string(it->second) +
                      " " + pt(T.pts[o.a]) + "-" + pt(T.pts[o.b]) + " along " + pt(T.pts[T.org(h)]) + "-" +
                      pt(T.pts[T.dst(h)]));
    }
  }
  T.set_constrained(h, true);
  if (T.twin[h] != kNoId) T.set_constrained(T.twin[h], true);
  T.seg_of[mesh::edge_key(T.org(h), T.dst(h))] = sid;
}

}  // namespace

void insert_segment(Triangulation& T, Index a, Index b, Index sid, const std::string& source, CdtStats* stats) {
  std::size_t guard = 0;
  while (a != b) {
    if (++guard > T.pts.size() + 2) throw Error(ExitCode::kInternal, source + ": segment insertion did not finish");
    // Rotate around a to find the edge a-b, a vertex on the segment, or the wedge containing b.
    const HalfEdge h0 = T.vhe[a];
    HalfEdge h = h0, start = kNoId;
    Index next_a = kNoId;
    do {
      const Index u = T.dst(h), w = T.apex(h);
      if (u == b) { mark_constrained(T, h, sid, source); return; }
      if (orient2d(T.pts[a], T.pts[b], T.pts[u]) == 0 && diametral(T.pts[a], T.pts[b], T.pts[u]) > 0) {
        mark_constrained(T, h, sid, source);  // u lies on the segment: split it there
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
    // Walk along a-b collecting the crossed edges (as vertex pairs: flips renumber half-edges)
    // up to b or to the first vertex lying on the segment.
    std::deque<std::pair<Index, Index>> crossing;
    HalfEdge cur = mesh::next_he(start);  // right -> left
    Index end = kNoId;
    while (true) {
      if (T.constrained(cur)) crossing_error(T, a, b, sid, cur, source);
      crossing.push_back({T.org(cur), T.dst(cur)});
      const HalfEdge n = T.twin[cur];
      if (n == kNoId) throw Error(ExitCode::kInternal, source + ": segment walk left the mesh");
      const Index o = T.apex(n);
      if (o == b) { end = b; break; }
      const int s = orient2d(T.pts[a], T.pts[b], T.pts[o]);
      if (s == 0) { end = o; if (stats) ++stats->segments_split_at_vertices; break; }
      cur = s > 0 ? mesh::next_he(n) : mesh::prev_he(n);
    }
    // Sloan's edge flipping: flip crossed edges whose quadrilateral is strictly convex until
    // none crosses a-end (always possible, so the loop ends); then Lawson flips restore the
    // constrained Delaunay property around the new edges. Unlike re-triangulating the two
    // pseudo-polygons, this needs no simple-polygon assumption (a vertex whose whole star is
    // crossed, with its edges hanging into the cavity, is handled like any other).
    const Point2 pa = T.pts[a], pe = T.pts[end];
    std::vector<std::pair<Index, Index>> fresh;
    std::size_t stall = 0;
    while (!crossing.empty()) {
      if (++stall > crossing.size() + 1)  // a whole pass without a flip: impossible in theory
        throw Error(ExitCode::kInternal, source + ": segment recovery by flips did not converge");
      const auto [u, w] = crossing.front();
      crossing.pop_front();
      const HalfEdge e = T.find_edge(u, w);
      if (e == kNoId) continue;
      const Index c = T.apex(e), d = T.apex(T.twin[e]);
      // Convex iff the diagonal c-d separates u and w strictly.
      if (orient2d(T.pts[c], T.pts[d], T.pts[u]) * orient2d(T.pts[c], T.pts[d], T.pts[w]) >= 0) {
        crossing.push_back({u, w});
        continue;
      }
      flip_edge(T, e);
      stall = 0;
      const int sc = orient2d(pa, pe, T.pts[c]), sd = orient2d(pa, pe, T.pts[d]);
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
      const HalfEdge e = T.find_edge(u, w);
      if (e == kNoId || T.constrained(e) || T.twin[e] == kNoId) continue;
      const Index c = T.apex(e), d = T.apex(T.twin[e]);
      if (incircle(T.pts[u], T.pts[w], T.pts[c], T.pts[d]) <= 0) continue;
      flip_edge(T, e);
      fresh.push_back({u, c});
      fresh.push_back({c, w});
      fresh.push_back({w, d});
      fresh.push_back({d, u});
    }
    a = end;
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
  std::vector<std::vector<std::pair<Index, int>>> comp_adj;  // neighbour, depth step
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
      if (w == kNoId || !T.constrained(h) || comp[mesh::tri_of(w)] == comp[t]) continue;
      // Breaklines (marker 4) are interior constraints: crossing one does not change the depth.
      auto it = T.seg_of.find(mesh::edge_key(T.org(h), T.dst(h)));
      const bool breakline = it != T.seg_of.end() && it->second < T.input_segments.size() &&
                             T.input_segments[it->second].marker == pslg::kBreaklineMarker;
      comp_adj[comp[t]].push_back({comp[mesh::tri_of(w)], breakline ? 0 : 1});
    }
  }
  // Nesting depth: fewest boundary (non-breakline) constraints crossed from the outside
  // (0-1 breadth-first search).
  std::vector<int> depth(ncomp, -1);
  std::deque<Index> q;
  for (Index k = 0; k < ncomp; ++k)
    if (comp_super[k]) { depth[k] = 0; q.push_back(k); }
  while (!q.empty()) {
    const Index k = q.front();
    q.pop_front();
    for (const auto& [j, step] : comp_adj[k]) {
      if (depth[j] >= 0 && depth[j] <= depth[k] + step) continue;
      depth[j] = depth[k] + step;
      if (step == 0) q.push_front(j); else q.push_back(j);
    }
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
    else if (mode == CdtOptions::Regions::kHull) remove[k] = false;  // super triangles go below
    else remove[k] = depth[k] == 0 || depth[k] < 0;
  }
  if (mode == CdtOptions::Regions::kSeeds || mode == CdtOptions::Regions::kHull) {
    for (std::size_t h = 0; h < in.holes.size(); ++h) {
      const Point2 hp = in.holes[h];
      auto hole_error = [&](const std::string& what) {
        throw Error(ExitCode::kInvalidGeometry, opt.source + ": hole " + std::to_string(h) + " seed at " +
                                                    pt(T.origin + hp) + " " + what);
      };
      if (!std::isfinite(hp.x) || !std::isfinite(hp.y)) hole_error("has a non-finite coordinate");
      TriangleId start = 0;
      while (T.dead(start)) ++start;
      const Location loc = locate_visibility(T, start, hp);
      if (loc.he == kNoId || loc.kind == LocateKind::kBlocked)
        hole_error("lies outside the domain (outside the convex hull of the vertices)");
      if (loc.kind == LocateKind::kOnVertex) hole_error("lies on vertex " + std::to_string(T.org(loc.he)));
      if (loc.kind == LocateKind::kOnEdge && T.constrained(loc.he)) {
        auto it = T.seg_of.find(mesh::edge_key(T.org(loc.he), T.dst(loc.he)));
        hole_error("lies on segment " +
                   (it != T.seg_of.end() ? std::to_string(it->second) : std::string("(a constrained edge)")) +
                   " (a seed must be strictly inside the region to remove)");
      }
      const TriangleId t = mesh::tri_of(loc.he);
      bool sup = false;
      for (int k = 0; k < 3; ++k) sup |= T.vkind[T.tv[3 * t + k]] == VertexKind::kSuper;
      const Index k = comp[t];
      if (sup || (mode == CdtOptions::Regions::kSeeds && depth[k] <= 0))
        hole_error(mode == CdtOptions::Regions::kHull
                       ? "lies outside the domain (outside the convex hull of the vertices)"
                       : "lies outside the domain (in no region enclosed by segments)");
      remove[k] = true;
    }
  }
  // Regional attributes / area constraints (Triangle semantics): a seed marks the whole region
  // bounded by segments around it; a later seed in the same region wins. Seeds outside every
  // triangle are ignored, as Triangle does.
  if (!in.regions.empty()) {
    std::vector<std::int32_t> region_of_comp(ncomp, -1);
    TriangleId start = 0;
    while (T.dead(start)) ++start;
    for (std::size_t r = 0; r < in.regions.size(); ++r) {
      const Point2 rp = in.regions[r].seed;
      if (!std::isfinite(rp.x) || !std::isfinite(rp.y)) continue;
      const Location loc = locate_visibility(T, start, rp);
      if (loc.he == kNoId || loc.kind == LocateKind::kBlocked) continue;
      region_of_comp[comp[mesh::tri_of(loc.he)]] = static_cast<std::int32_t>(r);
    }
    T.region.assign(nt, -1);
    for (TriangleId t = 0; t < nt; ++t)
      if (!T.dead(t)) T.region[t] = region_of_comp[comp[t]];
  }
  // Delete removed triangles; touching super-vertex triangles always go.
  auto removed = [&](TriangleId t) {
    if (remove[comp[t]]) return true;
    for (int k = 0; k < 3; ++k)
      if (T.vkind[T.tv[3 * t + k]] == VertexKind::kSuper) return true;
    return false;
  };
  // An input segment with an edge between two removed triangles lies (partly) outside the
  // domain, e.g. a boundary segment between two even-depth regions (parity) or between a hole and
  // the exterior: it is marked gone (b = a), so checkers and refinement ignore it.
  for (TriangleId t = 0; t < nt; ++t) {
    if (T.dead(t) || !removed(t)) continue;
    for (int k = 0; k < 3; ++k) {
      const HalfEdge h = 3 * t + static_cast<Index>(k);
      if (!T.constrained(h) || T.twin[h] == kNoId || !removed(mesh::tri_of(T.twin[h]))) continue;
      auto it = T.seg_of.find(mesh::edge_key(T.org(h), T.dst(h)));
      if (it != T.seg_of.end() && it->second < T.input_segments.size())
        T.input_segments[it->second].b = T.input_segments[it->second].a;
    }
  }
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
