// Triangulation: index-based triangle mesh (structure of arrays) used by cdt and refine.
//
// Index convention (one triangle t, counter-clockwise):
//
//              corner(t, 2)
//               /  \   .
//      edge 2  /    \  edge 1          half-edge h = 3t+k runs from corner(t, k) to corner(t, k+1 mod 3),
//             /      \                 next(h) = 3t + (k+1)%3, prev(h) = 3t + (k+2)%3.
//   corner(t, 0) -- corner(t, 1)       twin(h) = the opposite half-edge in the neighbouring
//               edge 0                 triangle, or kNoId on the mesh boundary.
//
// A constrained half-edge (a subsegment of an input segment) has its bit set in the triangle's
// flags; both halves of an interior subsegment carry the bit. segment_of(a, b) names the input
// segment of the constrained edge a-b (see "Constraints" below for how it is stored).
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>
#include "base/prefetch.hpp"
#include "base/large_array.hpp"
#include "base/types.hpp"
#include "mesh/mesh_view.hpp"

namespace fdr::mesh {

enum class VertexKind : std::uint8_t {
  kInput = 0,    // a vertex of the input PSLG
  kSegment = 1,  // a Steiner point inserted on a segment
  kFree = 2,     // a Steiner point inserted at a circumcenter
  kSuper = 3,    // a vertex of the enclosing super-triangle (never in the output)
};

inline constexpr HalfEdge next_he(HalfEdge h) { return (h % 3 == 2) ? h - 2 : h + 1; }
inline constexpr HalfEdge prev_he(HalfEdge h) { return (h % 3 == 0) ? h + 2 : h - 1; }
inline constexpr TriangleId tri_of(HalfEdge h) { return h / 3; }

struct InputSegmentInfo {
  Index a = 0, b = 0;        // input vertex ids (triangulation ids); b == a: outside the domain
  std::int32_t marker = 0;
  std::int32_t part = -1;
};

class Triangulation {
 public:
  // Per-triangle flag bits: constrained edge k is bit kConstrained0 << k.
  static constexpr std::uint8_t kConstrained0 = 1, kDead = 8, kMarkA = 16, kMarkB = 32;

  Point2 origin{0, 0};  // world = origin + point(v)

  // --- Vertices ---
  std::size_t num_vertices() const { return pts_.size(); }
  const Point2& point(Index v) const { return pts_[v]; }
  void set_point(Index v, Point2 p) { pts_[v] = p; }
  const LargeArray<Point2>& points() const { return pts_; }
  VertexKind kind(Index v) const { return vkind_[v]; }
  // Some half-edge leaving v (kNoId if none).
  HalfEdge vertex_edge(Index v) const { return vhe_[v]; }
  void set_vertex_edge(Index v, HalfEdge h) { vhe_[v] = h; }
  // The input point marker (0 for every Steiner point).
  std::int32_t point_marker(Index v) const { return input_like(v) ? vinfo_[v] : 0; }
  void set_point_marker(Index v, std::int32_t m) {
    if (input_like(v)) vinfo_[v] = m;
  }
  Index add_vertex(Point2 p, VertexKind k) {
    pts_.push_back(p);
    vkind_.push_back(k);
    vhe_.push_back(kNoId);
    vinfo_.push_back(k == VertexKind::kInput || k == VertexKind::kSuper ? 0 : -1);
    return static_cast<Index>(pts_.size() - 1);
  }
  // Room for this many triangle slots and vertices (each array's buffer advised before it is
  // written; base/large_array.hpp), so that growth does not hold old and new arrays at once.
  void reserve(std::size_t triangles, std::size_t vertices);

  // --- Triangles ---
  std::size_t num_slots() const { return flags_.size(); }
  std::size_t num_live_triangles() const { return flags_.size() - free_list_.size(); }
  bool dead(TriangleId t) const { return flags_[t] & kDead; }
  Index corner(TriangleId t, int k) const { return corners_[t][static_cast<std::size_t>(k)]; }
  Index org(HalfEdge h) const { return corners_[h / 3][h % 3]; }
  Index dst(HalfEdge h) const { return corners_[h / 3][h % 3 == 2 ? 0 : h % 3 + 1]; }
  Index apex(HalfEdge h) const { return corners_[h / 3][h % 3 == 0 ? 2 : h % 3 - 1]; }
  void set_corners(TriangleId t, Index a, Index b, Index c) { corners_[t] = {a, b, c}; }
  const LargeArray<std::array<Index, 3>>& corners() const { return corners_; }
  HalfEdge twin(HalfEdge h) const { return twin_[h]; }
  void set_twin(HalfEdge h, HalfEdge w) { twin_[h] = w; }
  void link(HalfEdge a, HalfEdge b) {
    twin_[a] = b;
    if (b != kNoId) twin_[b] = a;
  }
  bool constrained(HalfEdge h) const { return flags_[h / 3] & (kConstrained0 << (h % 3)); }
  void set_constrained(HalfEdge h, bool on) {
    const std::uint8_t bit = static_cast<std::uint8_t>(kConstrained0 << (h % 3));
    if (on) flags_[h / 3] |= bit; else flags_[h / 3] &= static_cast<std::uint8_t>(~bit);
  }
  void clear_constraints(TriangleId t) { flags_[t] &= static_cast<std::uint8_t>(~7u); }
  // Scratch marks (kMarkA, kMarkB) of the cavity search.
  bool marked(TriangleId t, std::uint8_t bits) const { return (flags_[t] & bits) != 0; }
  void mark(TriangleId t, std::uint8_t bits) { flags_[t] |= bits; }
  void unmark(TriangleId t, std::uint8_t bits) { flags_[t] &= static_cast<std::uint8_t>(~bits); }
  // Allocates a triangle slot (the last one freed if any) with the given corners; their
  // vertex_edge is set to the new triangle's half-edges.
  TriangleId new_triangle(Index a, Index b, Index c) {
    TriangleId t;
    if (!free_list_.empty()) {
      t = free_list_.back();
      free_list_.pop_back();
    } else {
      t = static_cast<TriangleId>(flags_.size());
      flags_.push_back(0);
      corners_.emplace_back();
      for (int k = 0; k < 3; ++k) twin_.push_back(kNoId);
    }
    flags_[t] = 0;
    corners_[t] = {a, b, c};
    twin_[3 * t] = twin_[3 * t + 1] = twin_[3 * t + 2] = kNoId;
    vhe_[a] = 3 * t; vhe_[b] = 3 * t + 1; vhe_[c] = 3 * t + 2;
    return t;
  }
  void kill_triangle(TriangleId t) {
    flags_[t] = kDead;
    free_list_.push_back(t);
  }

  // Asks for the cache lines of triangle t and of vertex v's point, for a caller that knows
  // early which triangle it will read next.
  void prefetch(TriangleId t, Index v) const {
    fdr::prefetch(&corners_[t]);
    fdr::prefetch(&twin_[3 * t]);
    fdr::prefetch(&flags_[t]);
    fdr::prefetch(&pts_[v]);
  }

  // --- Regions: empty, or per triangle slot the index of the Pslg::regions entry whose seed
  // lies in its region (-1: none); set by cdt::build_cdt, inherited by new triangles. ---
  bool has_regions() const { return !region_.empty(); }
  std::int32_t region(TriangleId t) const { return t < region_.size() ? region_[t] : -1; }
  // Starts the regions: -1 for every slot.
  void init_regions() { region_.assign(num_slots(), -1); }
  void set_region(TriangleId t, std::int32_t r) {
    if (region_.size() <= t) grow_regions();
    region_[t] = r;
  }

  // --- Constraints ---
  // Why no map from vertex pairs: a Steiner point on a segment lies on exactly one input segment,
  // so every subsegment with such an endpoint takes that endpoint's segment, stored per Steiner
  // point on a segment; only subsegments between two input vertices need a pair lookup, and those
  // are made by the CDT alone and are few per vertex (a list per smaller end). Nothing is hashed,
  // and the per-vertex word is the input point marker's (Steiner points have none).
  const std::vector<InputSegmentInfo>& input_segments() const { return input_segments_; }
  Index add_input_segment(const InputSegmentInfo& s) {
    input_segments_.push_back(s);
    return static_cast<Index>(input_segments_.size() - 1);
  }
  void reserve_input_segments(std::size_t n) { input_segments_.reserve(n); }
  // Marks input segment s as outside the domain (b = a), so that checkers and refinement skip it.
  void drop_input_segment(Index s) { input_segments_[s].b = input_segments_[s].a; }
  // The input segment of the constrained edge a-b: kNoId for a hull edge that belongs to no
  // input segment, and unspecified when a-b is not a subsegment.
  Index segment_of(Index a, Index b) const;
  // Records a-b (a new constrained edge between two vertices that are no Steiner points on
  // segments) as a subsegment of input segment s (kNoId: of none, e.g. a hull edge).
  void set_segment(Index a, Index b, Index s);
  // Subsegment a-b was split at the new vertex v: v lies on a-b's input segment.
  void split_segment(Index a, Index b, Index v);
  // The input segment of a Steiner point placed on a segment (kNoId for other vertices).
  Index segment_of_vertex(Index v) const {
    const Index i = segment_vertex_index(v);
    return i == kNoId ? kNoId : on_segment_[i];
  }
  // The index of v among the Steiner points placed on segments, in order of creation (kNoId if
  // v is none): callers keep their own data about those points in a plain array.
  Index segment_vertex_index(Index v) const {
    return input_like(v) || vinfo_[v] < 0 ? kNoId : static_cast<Index>(vinfo_[v]);
  }
  // The constrained half-edge a->b (else b->a) when a-b is a subsegment now, else kNoId (e.g.
  // a stale one, split since).
  HalfEdge find_subsegment(Index a, Index b) const;
  // The constrained edge h with its input segment's marker and part (this triangulation's vertex
  // ids; marker and part 0 without a segment).
  MeshEdge mesh_edge(HalfEdge h) const;

  // --- Queries ---
  // Finds the half-edge a->b, or else b->a (a boundary edge has only one), or kNoId. Rotates
  // around a and b; falls back to a scan for vertices with two separate fans (pinches).
  HalfEdge find_edge(Index a, Index b) const;
  // find_edge, then (only if the fans miss it) a scan of all triangles: O(n), for edges known to
  // exist at a pinched vertex (two parts of the domain touching at one vertex).
  HalfEdge find_edge_anywhere(Index a, Index b) const;
  // Makes vertex_edge(v) valid for every vertex that still has a triangle (kNoId for the others).
  void rebuild_vertex_map();
  // Signed area (compensated sum) of all live triangles.
  double area() const;
  // Compacts into a MeshView: drops dead triangles, super vertices and unused vertices.
  MeshView to_view() const;
  // The same MeshView, built in place from this triangulation's arrays (take_view.hpp).
  friend MeshView take_view(Triangulation& t);

 private:
  bool input_like(Index v) const { return vkind_[v] == VertexKind::kInput || vkind_[v] == VertexKind::kSuper; }
  // A subsegment between two input vertices: kept in a list per smaller end.
  struct InputEdge {
    Index other;  // the larger end (kNoId: split since)
    Index segment;
    Index next;   // next entry of the same smaller end (kNoId: none)
  };
  Index input_edge(Index a, Index b) const;  // the entry of a-b in input_edges_, or kNoId
  void add_input_edge(Index a, Index b, Index s);
  void grow_regions();  // to num_slots(), the buffer grown geometrically (one slot at a time is quadratic)

  // Vertices.
  LargeArray<Point2> pts_;
  LargeArray<VertexKind> vkind_;
  LargeArray<HalfEdge> vhe_;
  // Input and super vertices: the input point marker. Other vertices: their index among the
  // Steiner points on segments (on_segment_), or -1.
  LargeArray<std::int32_t> vinfo_;
  // Triangles. The corners as one array per slot, MeshView::triangles' element type, so that the
  // compaction hands the array itself to the view (take_view).
  LargeArray<std::array<Index, 3>> corners_;
  LargeArray<HalfEdge> twin_;  // 3 per slot
  LargeArray<std::uint8_t> flags_;
  std::vector<TriangleId> free_list_;
  LargeArray<std::int32_t> region_;
  // Constraints.
  std::vector<InputSegmentInfo> input_segments_;
  LargeArray<Index> on_segment_;    // per Steiner point on a segment: its input segment
  LargeArray<Index> edge_head_;     // per vertex: its first InputEdge as the smaller end
  LargeArray<InputEdge> input_edges_;
};

}  // namespace fdr::mesh
