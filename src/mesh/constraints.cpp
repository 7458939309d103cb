// The input segment of every subsegment: per Steiner point on a segment, and per pair of input
// vertices (see Triangulation, "Constraints").
#include <algorithm>
#include <utility>

#include "mesh/triangulation.hpp"

namespace fdr::mesh {

Index Triangulation::input_edge(Index a, Index b) const {
  if (a > b) std::swap(a, b);
  if (a >= edge_head_.size()) return kNoId;
  for (Index i = edge_head_[a]; i != kNoId; i = input_edges_[i].next)
    if (input_edges_[i].other == b) return i;
  return kNoId;
}

void Triangulation::add_input_edge(Index a, Index b, Index s) {
  if (a > b) std::swap(a, b);
  if (a >= edge_head_.size()) edge_head_.resize(std::max<std::size_t>(a + 1, pts_.size()), kNoId);
  input_edges_.push_back({b, s, edge_head_[a]});
  edge_head_[a] = static_cast<Index>(input_edges_.size() - 1);
}

Index Triangulation::segment_of(Index a, Index b) const {
  if (const Index i = segment_vertex_index(a); i != kNoId) return on_segment_[i];
  if (const Index i = segment_vertex_index(b); i != kNoId) return on_segment_[i];
  const Index e = input_edge(a, b);
  return e != kNoId ? input_edges_[e].segment : kNoId;
}

void Triangulation::set_segment(Index a, Index b, Index s) {
  // A Steiner point on a segment carries its segment: the edge needs no entry of its own.
  bool steiner = false;
  for (const Index v : {a, b})
    if (const Index i = segment_vertex_index(v); i != kNoId) {
      on_segment_[i] = s;
      steiner = true;
    }
  if (steiner) return;
  if (const Index e = input_edge(a, b); e != kNoId) input_edges_[e].segment = s;
  else add_input_edge(a, b, s);
}

void Triangulation::split_segment(Index a, Index b, Index v) {
  const Index s = segment_of(a, b);
  if (segment_vertex_index(a) == kNoId && segment_vertex_index(b) == kNoId)
    if (const Index e = input_edge(a, b); e != kNoId) input_edges_[e].other = kNoId;  // a-b is gone
  if (input_like(v)) {  // (not made by refinement) the two halves as input-vertex pairs
    set_segment(a, v, s);
    set_segment(v, b, s);
    return;
  }
  vinfo_[v] = static_cast<std::int32_t>(on_segment_.size());
  on_segment_.push_back(s);
}

HalfEdge Triangulation::find_subsegment(Index a, Index b) const {
  HalfEdge h = kNoId;
  if (segment_vertex_index(a) != kNoId || segment_vertex_index(b) != kNoId) {
    // A Steiner point inside a segment has one fan (two parts of the domain touch only at input
    // vertices), so the fans find the edge if it is there.
    h = find_edge(a, b);
  } else if (input_edge(a, b) != kNoId) {
    h = find_edge_anywhere(a, b);
  }
  return h != kNoId && constrained(h) ? h : kNoId;
}

MeshEdge Triangulation::mesh_edge(HalfEdge h) const {
  MeshEdge e;
  e.a = org(h);
  e.b = dst(h);
  const Index s = segment_of(e.a, e.b);
  if (s < input_segments_.size()) {
    e.marker = input_segments_[s].marker;
    e.part = input_segments_[s].part;
  }
  return e;
}

}  // namespace fdr::mesh
