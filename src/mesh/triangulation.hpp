// Triangulation: index-based triangle mesh (structure of arrays) used by cdt and refine.
//
// Index convention (one triangle t, counter-clockwise):
//
//              v[3t+2]
//               /  \   .
//      edge 2  /    \  edge 1          half-edge h = 3t+k runs from v[h] to v[next(h)],
//             /      \                 next(h) = 3t + (k+1)%3, prev(h) = 3t + (k+2)%3.
//        v[3t] ------ v[3t+1]          twin[h] = the opposite half-edge in the neighbouring
//               edge 0                 triangle, or kNoId on the mesh boundary.
//
// A constrained half-edge (a subsegment of an input segment) has its bit set in flags[t];
// both halves of an interior subsegment carry the bit. seg_of maps an undirected constrained
// edge (min vertex, max vertex) to the index of the input segment it belongs to.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>
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

inline std::uint64_t edge_key(Index a, Index b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint64_t>(b);
}

struct InputSegmentInfo {
  Index a = 0, b = 0;        // input vertex ids (triangulation ids)
  std::int32_t marker = 0;
  std::int32_t part = -1;
};

// The corners of the triangle slots: tv[3t + k] is corner k of slot t (the origin of half-edge
// 3t + k). Stored as one std::array per slot, MeshView::triangles' element type, so that the
// compaction hands the array itself to the mesh view instead of copying it into fresh pages
// (take_view: 12 MiB at 1 M triangles, each 4 KiB page a fault). Read and written as Index
// values (as before, when it was a std::vector<Index>), so no access changes type.
class SlotCorners {
 public:
  Index& operator[](std::size_t h) { return reinterpret_cast<Index*>(slots_.data())[h]; }
  const Index& operator[](std::size_t h) const { return reinterpret_cast<const Index*>(slots_.data())[h]; }
  std::size_t size() const { return 3 * slots_.size(); }
  void add_slot() { slots_.emplace_back(); }
  std::vector<std::array<Index, 3>>& slots() { return slots_; }
  const std::vector<std::array<Index, 3>>& slots() const { return slots_; }

 private:
  static_assert(sizeof(std::array<Index, 3>) == 3 * sizeof(Index) && alignof(std::array<Index, 3>) == alignof(Index));
  std::vector<std::array<Index, 3>> slots_;
};

class Triangulation {
 public:
  // Per-triangle flag bits.
  static constexpr std::uint8_t kConstrained0 = 1, kDead = 8, kMarkA = 16, kMarkB = 32;

  // Vertices.
  std::vector<Point2> pts;
  std::vector<VertexKind> vkind;
  std::vector<HalfEdge> vhe;  // some half-edge leaving the vertex (kNoId if none)
  // Triangles.
  SlotCorners tv;                // 3 per triangle
  std::vector<HalfEdge> twin;    // 3 per triangle
  std::vector<std::uint8_t> flags;
  std::vector<TriangleId> free_list;
  // Constraints.
  std::unordered_map<std::uint64_t, Index> seg_of;
  std::vector<InputSegmentInfo> input_segments;
  Point2 origin{0, 0};
  std::vector<std::int32_t> point_marker;  // input point markers (0 for Steiner points)
  // Empty, or per triangle slot the index of the Pslg::regions entry whose seed lies in its
  // region (-1: none). Set by cdt::build_cdt, inherited by triangles the Inserter creates.
  std::vector<std::int32_t> region;

  std::size_t num_slots() const { return flags.size(); }
  std::size_t num_live_triangles() const { return flags.size() - free_list.size(); }
  bool dead(TriangleId t) const { return flags[t] & kDead; }
  bool constrained(HalfEdge h) const { return flags[h / 3] & (kConstrained0 << (h % 3)); }
  void set_constrained(HalfEdge h, bool on) {
    const std::uint8_t bit = static_cast<std::uint8_t>(kConstrained0 << (h % 3));
    if (on) flags[h / 3] |= bit; else flags[h / 3] &= static_cast<std::uint8_t>(~bit);
  }
  Index org(HalfEdge h) const { return tv[h]; }
  Index dst(HalfEdge h) const { return tv[next_he(h)]; }
  Index apex(HalfEdge h) const { return tv[prev_he(h)]; }

  Index add_vertex(Point2 p, VertexKind k) {
    pts.push_back(p);
    vkind.push_back(k);
    vhe.push_back(kNoId);
    point_marker.push_back(0);
    return static_cast<Index>(pts.size() - 1);
  }
  // Allocates a triangle slot (from the free list if possible) with the given vertices.
  TriangleId new_triangle(Index a, Index b, Index c) {
    TriangleId t;
    if (!free_list.empty()) {
      t = free_list.back();
      free_list.pop_back();
    } else {
      t = static_cast<TriangleId>(flags.size());
      flags.push_back(0);
      tv.add_slot();
      twin.resize(twin.size() + 3);
    }
    flags[t] = 0;
    tv[3 * t] = a; tv[3 * t + 1] = b; tv[3 * t + 2] = c;
    twin[3 * t] = twin[3 * t + 1] = twin[3 * t + 2] = kNoId;
    vhe[a] = 3 * t; vhe[b] = 3 * t + 1; vhe[c] = 3 * t + 2;
    return t;
  }
  void kill_triangle(TriangleId t) {
    flags[t] = kDead;
    free_list.push_back(t);
  }
  void link(HalfEdge a, HalfEdge b) {
    twin[a] = b;
    if (b != kNoId) twin[b] = a;
  }
  // Finds the half-edge a->b, or else b->a (a boundary edge has only one), or kNoId. Rotates
  // around a and b; falls back to a scan for vertices with two separate fans (pinches).
  HalfEdge find_edge(Index a, Index b) const;
  // find_edge, then (only if the fans miss it) a scan of all triangles: O(n), for edges known to
  // exist at a pinched vertex (two parts of the domain touching at one vertex).
  HalfEdge find_edge_anywhere(Index a, Index b) const;
  // Makes vhe[v] valid for every vertex that still has a triangle (kNoId for the others).
  void rebuild_vertex_map();

  // Signed area (compensated sum) of all live triangles.
  double area() const;
  // Compacts into a MeshView: drops dead triangles, super vertices and unused vertices.
  MeshView to_view() const;
};

}  // namespace fdr::mesh
