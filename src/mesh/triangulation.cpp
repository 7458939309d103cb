// Triangulation helpers: edge lookup, vertex map, area, compaction to MeshView.
#include "mesh/triangulation.hpp"
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

HalfEdge Triangulation::find_edge(Index a, Index b) const {
  const HalfEdge h0 = vhe[a];
  if (h0 == kNoId) return kNoId;
  // Counter-clockwise around a: the half-edge after h is twin(prev(h)).
  HalfEdge h = h0;
  do {
    if (dst(h) == b) return h;
    const HalfEdge p = twin[prev_he(h)];
    if (p == kNoId) break;
    h = p;
  } while (h != h0);
  if (h != h0 || twin[prev_he(h)] == kNoId) {
    // Hit the boundary: rotate clockwise from the start: next(twin(h)).
    h = h0;
    while (true) {
      const HalfEdge t = twin[h];
      if (t == kNoId) break;
      h = next_he(t);
      if (h == h0) break;
      if (dst(h) == b) return h;
    }
  }
  return kNoId;
}

void Triangulation::rebuild_vertex_map() {
  std::fill(vhe.begin(), vhe.end(), kNoId);
  for (TriangleId t = 0; t < num_slots(); ++t) {
    if (dead(t)) continue;
    for (int k = 0; k < 3; ++k) vhe[tv[3 * t + k]] = 3 * t + k;
  }
}

double Triangulation::area() const {
  // Kahan-Babuska (Neumaier) summation of triangle areas.
  double sum = 0, comp = 0;
  for (TriangleId t = 0; t < num_slots(); ++t) {
    if (dead(t)) continue;
    const Point2 a = pts[tv[3 * t]], b = pts[tv[3 * t + 1]], c = pts[tv[3 * t + 2]];
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
  std::vector<Index> remap(pts.size(), kNoId);
  // Vertices in order of first use by a live triangle keeps ids stable and dense.
  Index n = 0;
  for (TriangleId t = 0; t < num_slots(); ++t) {
    if (dead(t)) continue;
    for (int k = 0; k < 3; ++k) {
      const Index v = tv[3 * t + k];
      if (remap[v] == kNoId) remap[v] = 0;  // mark used
    }
  }
  for (Index v = 0; v < pts.size(); ++v)
    if (remap[v] != kNoId) remap[v] = n++;
  m.vertices.resize(n);
  m.vertex_marker.assign(n, 0);
  for (Index v = 0; v < pts.size(); ++v) {
    if (remap[v] == kNoId) continue;
    m.vertices[remap[v]] = pts[v];
    m.vertex_marker[remap[v]] = point_marker[v];
  }
  m.triangles.reserve(num_live_triangles());
  for (TriangleId t = 0; t < num_slots(); ++t) {
    if (dead(t)) continue;
    m.triangles.push_back({remap[tv[3 * t]], remap[tv[3 * t + 1]], remap[tv[3 * t + 2]]});
    for (int k = 0; k < 3; ++k) {
      const HalfEdge h = 3 * t + k;
      if (!constrained(h)) continue;
      if (twin[h] != kNoId && twin[h] < h) continue;  // report each edge once
      MeshEdge e;
      e.a = remap[org(h)];
      e.b = remap[dst(h)];
      auto it = seg_of.find(edge_key(org(h), dst(h)));
      if (it != seg_of.end() && it->second < input_segments.size()) {
        e.marker = input_segments[it->second].marker;
        e.part = input_segments[it->second].part;
      }
      m.edges.push_back(e);
      // Vertices on a marked segment inherit its marker when they have none (Triangle -B style).
      if (m.vertex_marker[e.a] == 0) m.vertex_marker[e.a] = e.marker;
      if (m.vertex_marker[e.b] == 0) m.vertex_marker[e.b] = e.marker;
    }
  }
  return m;
}

}  // namespace fdr::mesh
