// The compact mesh of a triangulation, built while its arrays are released (see take_view.hpp).
#include "mesh/take_view.hpp"

#include <utility>

#include "base/memory.hpp"
#include "base/parallel.hpp"

namespace fdr::mesh {

namespace {
// Frees a container; a vector's huge-page advice is taken back first (base/memory.hpp).
template <class V>
void release(V& v) {
  if constexpr (requires { v.capacity(); }) release_huge(v);
  else V().swap(v);
}
}  // namespace

MeshView take_view(Triangulation& t) {
  MeshView m;
  m.origin = t.origin;
  // Vertices in order of first use by a live triangle keeps ids stable and dense (as to_view).
  std::vector<Index> remap;
  assign_huge(remap, t.pts.size(), kNoId);
  const std::size_t ns = t.num_slots();
  // Why the prefetches in the loops below: the corners and the neighbours of consecutive slots
  // are scattered over arrays much larger than the cache.
  constexpr std::size_t kAhead = 16;
  for (TriangleId s = 0; s < ns; ++s) {
    if (s + kAhead < ns)
      for (int k = 0; k < 3; ++k) __builtin_prefetch(&remap[t.tv[3 * (s + kAhead) + k]], 1);
    if (t.dead(s)) continue;
    for (int k = 0; k < 3; ++k) remap[t.tv[3 * s + k]] = 0;
  }
  Index n = 0;
  for (Index v = 0; v < t.pts.size(); ++v)
    if (remap[v] != kNoId) remap[v] = n++;
  const bool remap_is_identity = n == t.pts.size();  // no vertex dropped
  // The vertices and their markers compacted in place (remap[v] <= v: a write never overwrites
  // a vertex still to be read) and moved into the view: no second array of fresh pages (8 MiB of
  // positions at 0.5 M vertices, faulted in while the triangulation is still there).
  t.point_marker.resize(t.pts.size(), 0);
  for (Index v = 0; v < t.pts.size(); ++v) {
    if (remap[v] == kNoId || remap[v] == v) continue;
    t.pts[remap[v]] = t.pts[v];
    t.point_marker[remap[v]] = t.point_marker[v];
  }
  t.pts.resize(n);
  t.point_marker.resize(n);
  m.vertices = std::move(t.pts);
  m.vertex_marker = std::move(t.point_marker);
  release(t.vkind);
  release(t.vhe);
  // Constrained edges, each once, in slot order (as to_view); vertices on a marked segment inherit
  // its marker when they have none. The slots in two halves at once (the input segment of each
  // edge is a hash lookup that misses the cache: 15-17 ms on one thread for the 63 k coast edges
  // of a 1 M-triangle GIS mesh, 7-12 ms on two), the markers then in slot order.
  auto collect = [&t, &remap](TriangleId lo, TriangleId hi, std::vector<MeshEdge>& out) {
    for (TriangleId s = lo; s < hi; ++s) {
      if (t.dead(s)) continue;
      for (int k = 0; k < 3; ++k) {
        const HalfEdge h = 3 * s + k;
        if (!t.constrained(h)) continue;
        if (t.twin[h] != kNoId && t.twin[h] < h) continue;
        MeshEdge e;
        e.a = remap[t.org(h)];
        e.b = remap[t.dst(h)];
        auto it = t.seg_of.find(edge_key(t.org(h), t.dst(h)));
        if (it != t.seg_of.end() && it->second < t.input_segments.size()) {
          e.marker = t.input_segments[it->second].marker;
          e.part = t.input_segments[it->second].part;
        }
        out.push_back(e);
      }
    }
  };
  const TriangleId nslots = static_cast<TriangleId>(t.num_slots());
  if (max_threads() > 1 && nslots >= 65536) {
    std::vector<MeshEdge> back;
    run_beside([&] { collect(nslots / 2, nslots, back); }, [&] { collect(0, nslots / 2, m.edges); });
    m.edges.insert(m.edges.end(), back.begin(), back.end());
  } else {
    collect(0, nslots, m.edges);
  }
  for (const MeshEdge& e : m.edges) {
    if (m.vertex_marker[e.a] == 0) m.vertex_marker[e.a] = e.marker;
    if (m.vertex_marker[e.b] == 0) m.vertex_marker[e.b] = e.marker;
  }
  release(t.seg_of);
  release(t.input_segments);
  release(t.region);
  // Compaction once, in place: live triangles keep their slot order (as to_view); their twins,
  // renumbered to the compact triangle ids, become the view's neighbours (moved, not copied).
  // Writing slot s's entries to position i <= s only overwrites slots already read. Without dead
  // slots (the usual end of a refinement: new triangles reuse freed slots first) ids are kept.
  const bool dense = t.free_list.empty();
  std::vector<Index> slot(dense ? 0 : t.num_slots(), kNoId);
  Index nt = 0;
  if (!dense)
    for (TriangleId s = 0; s < t.num_slots(); ++s)
      if (!t.dead(s)) slot[s] = nt++;
  if (dense) nt = static_cast<Index>(t.num_slots());
  // The triangles' corners, renumbered in place, and their array moved into the view: no second
  // copy (12 MiB of fresh pages at 1 M triangles, a page fault each 4 KiB, 35-50 ms on this
  // project's machine, and the process's peak where the compaction held both). Without dead slots
  // (the usual end of a refinement) each triangle keeps its slot: the two halves of the slots are
  // renumbered at once (nothing at all when no vertex was dropped); with dead slots in slot order,
  // the twins renumbered in place as they go.
  auto& corners = t.tv.slots();
  if (dense) {
    if (!remap_is_identity) {
      auto renumber = [&corners, &remap](std::size_t lo, std::size_t hi) {
        for (std::size_t s = lo; s < hi; ++s)
          for (Index& v : corners[s]) v = remap[v];
      };
      if (max_threads() > 1 && nt >= 65536) run_beside([&] { renumber(nt / 2, nt); }, [&] { renumber(0, nt / 2); });
      else renumber(0, nt);
    }
  } else {
    for (TriangleId s = 0; s < t.num_slots(); ++s) {
      if (s + kAhead < ns)
        for (int k = 0; k < 3; ++k) {
          __builtin_prefetch(&remap[t.tv[3 * (s + kAhead) + k]]);
          const HalfEdge tw = t.twin[3 * (s + kAhead) + k];
          if (tw != kNoId) __builtin_prefetch(&slot[tri_of(tw)]);
        }
      if (t.dead(s)) continue;
      const Index i = slot[s];
      corners[i] = {remap[corners[s][0]], remap[corners[s][1]], remap[corners[s][2]]};
      for (int k = 0; k < 3; ++k) {
        const HalfEdge tw = t.twin[3 * s + k];
        t.twin[3 * i + k] = tw == kNoId || slot[tri_of(tw)] == kNoId ? kNoId : 3 * slot[tri_of(tw)] + tw % 3;
      }
    }
    corners.resize(nt);
  }
  m.triangles = std::move(corners);
  release(slot);
  release(remap);
  release(t.flags);
  t.twin.resize(3 * static_cast<std::size_t>(nt));
  m.neighbours = std::move(t.twin);
  t = Triangulation{};
  return m;
}

}  // namespace fdr::mesh
