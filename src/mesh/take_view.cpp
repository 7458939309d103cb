// The compact mesh of a triangulation, built while its arrays are released (see take_view.hpp).
#include "base/prefetch.hpp"
#include "mesh/take_view.hpp"

#include <utility>

#include "base/parallel.hpp"

namespace fdr::mesh {

namespace {
// Why the prefetches in the loops below: the corners and the neighbours of consecutive slots
// are scattered over arrays much larger than the cache.
constexpr std::size_t kAhead = 16;
// Below this many slots the halves are not worth a second thread.
constexpr std::size_t kTwoThreads = 65536;
}  // namespace

// Per vertex its compact id (kNoId: unused), in order of first use by a live triangle (as
// to_view), so that ids stay stable and dense. Returns the number of vertices kept.
static Index number_vertices(const Triangulation& t, const LargeArray<std::array<Index, 3>>& corners,
                             LargeArray<Index>& remap) {
  remap.assign(t.num_vertices(), kNoId);
  const std::size_t ns = t.num_slots();
  for (TriangleId s = 0; s < ns; ++s) {
    if (s + kAhead < ns)
      for (const Index v : corners[s + kAhead]) fdr::prefetch_for_write(&remap[v]);
    if (t.dead(s)) continue;
    for (const Index v : corners[s]) remap[v] = 0;
  }
  Index n = 0;
  for (Index v = 0; v < t.num_vertices(); ++v)
    if (remap[v] != kNoId) remap[v] = n++;
  return n;
}

// The constrained edges, each once, in slot order (as to_view), renumbered; the slots in two
// halves at once when there are many (the segment of each edge is a lookup that misses the cache).
static void collect_edges(const Triangulation& t, const LargeArray<Index>& remap, std::vector<MeshEdge>& edges) {
  auto collect = [&](TriangleId lo, TriangleId hi, std::vector<MeshEdge>& out) {
    for (TriangleId s = lo; s < hi; ++s) {
      if (t.dead(s)) continue;
      for (int k = 0; k < 3; ++k) {
        const HalfEdge h = 3 * s + k;
        if (!t.constrained(h)) continue;
        if (t.twin(h) != kNoId && t.twin(h) < h) continue;
        MeshEdge e = t.mesh_edge(h);
        e.a = remap[e.a];
        e.b = remap[e.b];
        out.push_back(e);
      }
    }
  };
  const TriangleId nslots = static_cast<TriangleId>(t.num_slots());
  if (max_threads() > 1 && nslots >= kTwoThreads) {
    std::vector<MeshEdge> back;
    run_beside([&] { collect(nslots / 2, nslots, back); }, [&] { collect(0, nslots / 2, edges); });
    edges.insert(edges.end(), back.begin(), back.end());
  } else {
    collect(0, nslots, edges);
  }
}

MeshView take_view(Triangulation& t) {
  MeshView m;
  m.origin = t.origin;
  LargeArray<Index> remap;
  const Index n = number_vertices(t, t.corners_, remap);
  const bool remap_is_identity = n == t.num_vertices();  // no vertex dropped
  t.vhe_.release();
  // The edges first: their segments are read from the vertices' own words, which the compaction
  // below turns into markers.
  collect_edges(t, remap, m.edges);
  // The vertices and their markers compacted in place (remap[v] <= v: a write never overwrites
  // a vertex still to be read) and moved into the view: no second array of fresh pages.
  for (Index v = 0; v < t.num_vertices(); ++v) {
    if (remap[v] == kNoId) continue;
    t.vinfo_[remap[v]] = t.point_marker(v);
    if (remap[v] != v) t.pts_[remap[v]] = t.pts_[v];
  }
  t.pts_.resize(n);
  t.vinfo_.resize(n);
  m.vertices = std::move(t.pts_).take();
  m.vertex_marker = std::move(t.vinfo_).take();
  t.vkind_.release();
  // Vertices on a marked segment inherit its marker when they have none, in slot order.
  for (const MeshEdge& e : m.edges) {
    if (m.vertex_marker[e.a] == 0) m.vertex_marker[e.a] = e.marker;
    if (m.vertex_marker[e.b] == 0) m.vertex_marker[e.b] = e.marker;
  }
  t.on_segment_.release();
  t.edge_head_.release();
  t.input_edges_.release();
  std::vector<InputSegmentInfo>().swap(t.input_segments_);
  t.region_.release();
  // Compaction once, in place: live triangles keep their slot order (as to_view); their twins,
  // renumbered to the compact triangle ids, become the view's neighbours (moved, not copied).
  // Writing slot s's entries to position i <= s only overwrites slots already read. Without dead
  // slots (the usual end of a refinement: new triangles reuse freed slots first) ids are kept.
  const bool dense = t.free_list_.empty();
  LargeArray<Index> slot;
  Index nt = static_cast<Index>(t.num_slots());
  if (!dense) {
    slot.assign(t.num_slots(), kNoId);
    nt = 0;
    for (TriangleId s = 0; s < t.num_slots(); ++s)
      if (!t.dead(s)) slot[s] = nt++;
  }
  // The triangles' corners, renumbered in place, and their array moved into the view: no second
  // copy, so no fresh pages and no rise of the peak. Without dead slots the two halves of the
  // slots are renumbered at once (nothing at all when no vertex was dropped); with dead slots in
  // slot order, the twins renumbered in place as they go.
  auto& corners = t.corners_;
  if (dense) {
    if (!remap_is_identity) {
      auto renumber = [&corners, &remap](std::size_t lo, std::size_t hi) {
        for (std::size_t s = lo; s < hi; ++s)
          for (Index& v : corners[s]) v = remap[v];
      };
      if (max_threads() > 1 && nt >= kTwoThreads) run_beside([&] { renumber(nt / 2, nt); }, [&] { renumber(0, nt / 2); });
      else renumber(0, nt);
    }
  } else {
    const std::size_t ns = t.num_slots();
    for (TriangleId s = 0; s < ns; ++s) {
      if (s + kAhead < ns)
        for (int k = 0; k < 3; ++k) {
          fdr::prefetch(&remap[corners[s + kAhead][k]]);
          const HalfEdge tw = t.twin_[3 * (s + kAhead) + k];
          if (tw != kNoId) fdr::prefetch(&slot[tri_of(tw)]);
        }
      if (t.dead(s)) continue;
      const Index i = slot[s];
      corners[i] = {remap[corners[s][0]], remap[corners[s][1]], remap[corners[s][2]]};
      for (int k = 0; k < 3; ++k) {
        const HalfEdge tw = t.twin_[3 * s + k];
        t.twin_[3 * i + k] = tw == kNoId || slot[tri_of(tw)] == kNoId ? kNoId : 3 * slot[tri_of(tw)] + tw % 3;
      }
    }
    corners.resize(nt);
  }
  m.triangles = std::move(corners).take();
  slot.release();
  remap.release();
  t.flags_.release();
  t.twin_.resize(3 * static_cast<std::size_t>(nt));
  m.neighbours = std::move(t.twin_).take();
  t = Triangulation{};
  return m;
}

}  // namespace fdr::mesh
