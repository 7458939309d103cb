// Triangulation helpers: edge lookup, vertex map, area, compaction to MeshView.
#include "mesh/triangulation.hpp"
#include <algorithm>
#include <cmath>

namespace fdr::mesh {

const char* edge_kind_name(EdgeKind k) {
  switch (k) {
    case EdgeKind::kNone: return "none";
    case EdgeKind::kLand: return "land";
    case EdgeKind::kIsland: return "island";
    case EdgeKind::kOpen: return "open";
    case EdgeKind::kBreakline: return "breakline";
  }
  return "none";
}

// Scans the fan of vertex_edge(v) both ways (outgoing and incoming edges); returns a half-edge joining
// v and w (v->w preferred), or kNoId.
static HalfEdge find_in_fan(const Triangulation& T, Index v, Index w) {
  const HalfEdge h0 = T.vertex_edge(v);
  if (h0 == kNoId || T.dead(tri_of(h0)) || T.org(h0) != v) return kNoId;
  HalfEdge found = kNoId;
  auto visit = [&](HalfEdge h) {  // h leaves v
    if (T.dst(h) == w) { found = h; return true; }
    if (found == kNoId && T.org(prev_he(h)) == w) found = prev_he(h);  // incoming w->v
    return false;
  };
  HalfEdge h = h0;
  do {  // counter-clockwise: twin(prev(h))
    if (visit(h)) return found;
    const HalfEdge p = T.twin(prev_he(h));
    if (p == kNoId) break;
    h = p;
  } while (h != h0);
  for (h = h0;;) {  // clockwise: next(twin(h))
    const HalfEdge t = T.twin(h);
    if (t == kNoId) break;
    h = next_he(t);
    if (h == h0) break;
    if (visit(h)) return found;
  }
  return found;
}

HalfEdge Triangulation::find_edge(Index a, Index b) const {
  HalfEdge e = find_in_fan(*this, a, b);
  if (e != kNoId && org(e) == a) return e;
  const HalfEdge f = find_in_fan(*this, b, a);
  if (f != kNoId) {
    if (org(f) == a) return f;
    if (e == kNoId) e = f;
  }
  if (e != kNoId) return twin(e) != kNoId ? twin(e) : e;
  return kNoId;
}

HalfEdge Triangulation::find_edge_anywhere(Index a, Index b) const {
  const HalfEdge e = find_edge(a, b);
  if (e != kNoId) return e;
  // Why a full scan: a vertex where two parts of the domain touch (a "pinch", e.g. the knot of
  // a figure-eight coastline) has two separate fans and vertex_edge reaches only one of them.
  HalfEdge back = kNoId;
  for (TriangleId t = 0; t < num_slots(); ++t) {
    if (dead(t)) continue;
    for (int k = 0; k < 3; ++k) {
      const HalfEdge h = 3 * t + static_cast<Index>(k);
      if (org(h) == a && dst(h) == b) return h;
      if (org(h) == b && dst(h) == a) back = h;
    }
  }
  return back;
}

void Triangulation::rebuild_vertex_map() {
  std::fill(vhe_.begin(), vhe_.end(), kNoId);
  for (TriangleId t = 0; t < num_slots(); ++t) {
    if (dead(t)) continue;
    for (int k = 0; k < 3; ++k) vhe_[corners_[t][k]] = 3 * t + k;
  }
}

void Triangulation::grow_regions() {
  if (region_.capacity() < num_slots()) region_.reserve(std::max(corners_.capacity(), 2 * region_.capacity()));
  region_.resize(num_slots(), -1);
}

void Triangulation::reserve(std::size_t triangles, std::size_t vertices) {
  corners_.reserve(triangles);
  twin_.reserve(3 * triangles);
  flags_.reserve(triangles);
  pts_.reserve(vertices);
  vkind_.reserve(vertices);
  vhe_.reserve(vertices);
  vinfo_.reserve(vertices);
}

double Triangulation::area() const {
  // Kahan-Babuska (Neumaier) summation of triangle areas.
  double sum = 0, comp = 0;
  for (TriangleId t = 0; t < num_slots(); ++t) {
    if (dead(t)) continue;
    const Point2 a = pts_[corners_[t][0]], b = pts_[corners_[t][1]], c = pts_[corners_[t][2]];
    const double x = 0.5 * ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
    const double s = sum + x;
    comp += (std::fabs(sum) >= std::fabs(x)) ? (sum - s) + x : (x - s) + sum;
    sum = s;
  }
  return sum + comp;
}

MeshView Triangulation::to_view() const {
  MeshView m;
  m.origin = origin;
  std::vector<Index> remap(pts_.size(), kNoId);
  // Vertices in order of first use by a live triangle keeps ids stable and dense.
  Index n = 0;
  for (TriangleId t = 0; t < num_slots(); ++t) {
    if (dead(t)) continue;
    for (const Index v : corners_[t]) remap[v] = 0;  // mark used
  }
  for (Index v = 0; v < pts_.size(); ++v)
    if (remap[v] != kNoId) remap[v] = n++;
  m.vertices.resize(n);
  m.vertex_marker.assign(n, 0);
  for (Index v = 0; v < pts_.size(); ++v) {
    if (remap[v] == kNoId) continue;
    m.vertices[remap[v]] = pts_[v];
    m.vertex_marker[remap[v]] = point_marker(v);
  }
  m.triangles.reserve(num_live_triangles());
  // Compact triangle ids (slot order) for the neighbours (see take_view.cpp).
  std::vector<Index> slot(num_slots(), kNoId);
  Index nt = 0;
  for (TriangleId t = 0; t < num_slots(); ++t)
    if (!dead(t)) slot[t] = nt++;
  m.neighbours.reserve(3 * static_cast<std::size_t>(nt));
  for (TriangleId t = 0; t < num_slots(); ++t) {
    if (dead(t)) continue;
    m.triangles.push_back({remap[corners_[t][0]], remap[corners_[t][1]], remap[corners_[t][2]]});
    for (int k = 0; k < 3; ++k) {
      const HalfEdge tw = twin_[3 * t + k];
      m.neighbours.push_back(tw == kNoId || slot[tri_of(tw)] == kNoId ? kNoId : 3 * slot[tri_of(tw)] + tw % 3);
    }
    for (int k = 0; k < 3; ++k) {
      const HalfEdge h = 3 * t + k;
      if (!constrained(h)) continue;
      if (twin_[h] != kNoId && twin_[h] < h) continue;  // report each edge once
      MeshEdge e = mesh_edge(h);
      e.a = remap[e.a];
      e.b = remap[e.b];
      m.edges.push_back(e);
      // Vertices on a marked segment inherit its marker when they have none (Triangle -B style).
      if (m.vertex_marker[e.a] == 0) m.vertex_marker[e.a] = e.marker;
      if (m.vertex_marker[e.b] == 0) m.vertex_marker[e.b] = e.marker;
    }
  }
  return m;
}

}  // namespace fdr::mesh
