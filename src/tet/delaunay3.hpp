// Delaunay tetrahedralization of points in 3D, built incrementally (Bowyer-Watson) with exact
// predicates: the core that 3D refinement inserts its points into.
//
// The convex hull is closed by ghost tetrahedra: each hull face together with one infinite
// vertex, so that every tetrahedron has four neighbours and points outside the hull need no
// bounding box (which would change the Delaunay tetrahedralization near the hull).
// Conventions: finite tetrahedra have positive orientation (predicates::orient3d > 0); a ghost
// keeps the infinite vertex at position 3 and its hull face (positions 0-2) is ordered so that
// the ghost would be positive with the infinite vertex moved to any point beyond the face.
// Neighbour i lies across the face opposite vertex i. Vertex ids count the inserted points in
// insertion order (duplicates get none).
#pragma once
#include <array>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>
#include "base/large_array.hpp"
#include "base/point3.hpp"
#include "base/types.hpp"
#include "tet/tet_mesh.hpp"

namespace fdr::tet {

using TetId = Index;
inline constexpr VertexId kInfinite = kNoId - 1;

// What one insertion did: the new vertex, or the vertex the point duplicates (then nothing
// changed).
struct Insertion {
  VertexId vertex = kNoId;
  bool duplicate = false;
};

// What a bulk insertion did: each input point's vertex (a duplicate's is the vertex it repeats)
// and the inputs that were duplicates, in increasing order.
struct BulkInsertion {
  std::vector<VertexId> vertex_of;
  std::vector<Index> duplicates;
};

class Delaunay3 {
 public:
  // Inserts all points in a spatially sorted biased randomized order (tet/spatial_sort.hpp).
  // A non-finite coordinate (here or in insert) throws fdr::Error (kInvalidGeometry) before
  // anything changes.
  BulkInsertion insert_all(std::span<const Point3> pts);

  // Room for about `vertices` vertices in all, and the tetrahedra they make, without the copies
  // that growing the arrays would make (a copy holds the old and the new buffer at once, at the
  // largest size: the run's peak). Room reserved and never used costs address space, not memory.
  void reserve(std::size_t vertices);

  // Inserts one point, starting the search at `hint` (any live tetrahedron; kNoId: the last one
  // made). The tetrahedra it makes, ghosts included, are appended to *created when given. Until
  // four points span 3D, points are only kept (dimension() < 3) and no tetrahedron exists.
  Insertion insert(Point3 p, TetId hint = kNoId, std::vector<TetId>* created = nullptr);

  // Insertion in two steps, for a caller that inspects the conflict region before it decides:
  // dig(p, located) finds the tetrahedra that inserting p would destroy (cavity(); `located` is
  // locate(p)'s answer), changing nothing a query sees; then insert_dug() inserts p from them,
  // or abandon() forgets them. Nothing else may change the structure in between. When p repeats
  // a vertex of `located`, dig returns that vertex as a duplicate and digs nothing.
  Insertion dig(Point3 p, TetId located);
  const std::vector<TetId>& cavity() const { return cavity_; }
  Insertion insert_dug(std::vector<TetId>* created = nullptr);
  void abandon();

  // A tetrahedron whose closure holds p, or a ghost whose hull face p lies strictly beyond;
  // kNoId while dimension() < 3. A visibility walk from `hint` (kNoId: the last tetrahedron made).
  TetId locate(Point3 p, TetId hint = kNoId) const;

  // -1 empty, 0 one point, 1 collinear, 2 coplanar, 3 tetrahedra exist.
  int dimension() const { return dim_; }
  std::size_t num_vertices() const { return pts_.size(); }
  Point3 point(VertexId v) const { return pts_[v]; }
  std::size_t num_finite_tets() const { return finite_; }
  // Tetrahedron slots: ids below this are live (finite or ghost) or free (alive() false).
  std::size_t tet_slots() const { return cells_.size(); }
  // Slots that exist or have room reserved (reserve()).
  std::size_t tet_capacity() const { return cells_.capacity(); }
  bool alive(TetId t) const { return cells_[t].v[0] != kNoId; }
  bool is_ghost(TetId t) const { return cells_[t].v[3] == kInfinite; }
  const std::array<VertexId, 4>& vertices(TetId t) const { return cells_[t].v; }
  TetId neighbour(TetId t, int i) const { return cells_[t].n[i] >> 2; }
  // The index, in neighbour(t, i), of the vertex opposite the shared face.
  int mirror_index(TetId t, int i) const { return static_cast<int>(cells_[t].n[i] & 3); }
  // A live tetrahedron (possibly a ghost) with v as a vertex; kNoId while dimension() < 3.
  TetId vertex_tet(VertexId v) const { return vtet_[v]; }

  template <class Fn>
  void for_each_finite_tet(Fn&& fn) const {
    for (TetId t = 0; t < cells_.size(); ++t)
      if (alive(t) && !is_ghost(t)) fn(t);
  }

  // Every tetrahedron's circumsphere is empty of the vertices across its faces, and the hull is
  // locally convex, decided exactly (local Delaunay on every face implies global Delaunay).
  bool is_delaunay(std::string* why = nullptr) const;
  // The structure holds: positive finite tetrahedra, ghosts with their face ordered as above,
  // symmetric neighbours sharing a face, vertex tetrahedra that hold their vertex.
  bool check_valid(std::string* why = nullptr) const;
  // The finite tetrahedra and every vertex (in vertex id order).
  TetMesh to_mesh() const;
  // Bytes held by the structure's arrays (capacity, not size).
  std::size_t bytes() const;

 private:
  struct Cell {
    std::array<VertexId, 4> v;
    std::array<Index, 4> n;  // neighbour across face i as 4 * tet + mirror index
  };
  struct NewCell {
    std::array<VertexId, 4> v;
    Index outside;  // neighbour across the face opposite the new vertex
    int i;          // position of the new vertex
  };

  Insertion insert_low_dim(Point3 p, std::vector<TetId>* created);
  void build_first_tet(VertexId a, VertexId b, VertexId c, VertexId d);
  void insert_vertex(VertexId v, TetId start, std::vector<TetId>* created);
  TetId walk(Point3 p, TetId t) const;
  TetId scan(Point3 p) const;
  void require_finite(Point3 p) const;
  bool conflict(TetId t, Point3 p) const;
  void dig_cavity(TetId start, Point3 p, VertexId v);
  void clear_cavity_marks();
  void fill_cavity(VertexId v, std::vector<TetId>* created);
  void link_new_faces(std::span<const TetId> ids);
  void link_by_hash(std::span<const TetId> ids);
  TetId new_slot();
  VertexId add_vertex(Point3 p);

  LargeArray<Point3> pts_;
  LargeArray<TetId> vtet_;
  LargeArray<Index> vlocal_;  // kNoId, or the vertex's local number during an insertion
  LargeArray<Cell> cells_;
  LargeArray<std::uint8_t> in_cavity_;
  std::vector<TetId> free_;
  std::size_t finite_ = 0;
  TetId last_ = kNoId;
  int dim_ = -1;
  // Points kept while dimension() < 3, and the ones that span the dimension reached so far.
  std::vector<VertexId> pending_;
  std::map<std::array<double, 3>, VertexId> pending_at_;
  std::array<VertexId, 3> span_{kNoId, kNoId, kNoId};
  // Scratch of one insertion, kept to reuse its memory.
  std::vector<TetId> cavity_;
  Point3 dug_{};
  bool dug_live_ = false;  // between dig and insert_dug or abandon
  std::vector<NewCell> ball_;
  std::vector<TetId> ball_ids_;
  struct EdgeSlot {
    VertexId a = kNoId, b = kNoId;  // a < b; kNoId: empty
    Index code = 0;
  };
  std::vector<EdgeSlot> edge_table_;
  struct DenseSlot {
    std::uint32_t stamp = 0;  // the insertion that wrote it
    Index code = 0;
  };
  static constexpr Index kMaxDenseLocals = 64;
  std::vector<DenseSlot> edge_dense_ = std::vector<DenseSlot>(kMaxDenseLocals * kMaxDenseLocals);
  std::uint32_t stamp_ = 0;
  std::vector<VertexId> local_verts_;
  std::vector<std::size_t> edge_used_;
};

}  // namespace fdr::tet
