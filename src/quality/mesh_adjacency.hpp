// Triangle adjacency of a MeshView and the exact nearest-neighbour search that walks it (the
// quality report's nn(p), FDR paper Definition 2.1, without a global search structure).
#pragma once
#include <memory>
#include <vector>
#include "base/large_array.hpp"
#include "mesh/mesh_view.hpp"

namespace fdr::quality {

// Per half-edge 3t+k the half-edge of the neighbouring triangle running the other way, or kNoId
// (MeshView::neighbours' convention): m.neighbours when it is filled, else built from the
// triangles (half-edges grouped by tail vertex and sorted by head; the first match wins on
// non-manifold edges). Vertex ids must be < m.vertices.size().
std::vector<Index> half_edge_neighbours(const mesh::MeshView& m);

// What one pass over the triangles (compute_orthogonality with `prep`) gathers for the search.
struct MeshWalkPrep {
  LargeArray<double> nn2;           // per vertex: squared length of its shortest mesh edge (+inf: none)
  LargeArray<Index> tri_of_vertex;  // per vertex: one triangle with that corner (kNoId: none)
  std::vector<Index> not_delaunay;   // interior half-edges (one per edge) whose far apex lies strictly
                                     // inside the triangle's circumcircle (exact incircle)
  bool ccw = true;                   // every triangle counter-clockwise (exact orient2d)
};

// Squared distance from every vertex to the nearest other vertex (+inf when there is none),
// exactly the minimum of norm2(p_q - p_v) over all vertices q != v, found by walking the mesh:
// from v's triangles, across every edge that comes closer to v than the best distance so far,
// and, when the walk meets the mesh boundary that close, also from every boundary edge that
// close (the region near v may continue across a hole or the exterior). Needs a valid planar
// triangulation (consistently oriented, edge-manifold, as the mesher makes) with `nb` its
// adjacency and every vertex a corner of some triangle; returns an empty vector when some vertex
// is on no triangle or a vertex id is out of range (then use a global search). When the mesh is
// constrained Delaunay with respect to its boundary and m.edges (checked here with exact
// predicates), a vertex with no such edge nearer than its nearest mesh neighbour needs no walk.
// `threads` > 1 searches two halves of the vertices at once (same values).
// `prep`, when given, comes from compute_orthogonality(m, nb, prep) (else it is gathered here).
std::vector<double> mesh_nearest_neighbour_sq(const mesh::MeshView& m, const std::vector<Index>& nb,
                                              unsigned threads = 1, MeshWalkPrep* prep = nullptr);

// The same search in pieces: the constructor checks the mesh and builds the index of the
// boundary and constrained edges (taking prep.nn2 when usable()), search(lo, hi) finds the
// nearest neighbours of the vertices [lo, hi) (disjoint ranges may run on different threads),
// take() gives the squared distances. Not usable (then use a global search) in the cases where
// mesh_nearest_neighbour_sq returns an empty vector (vertex ids must be valid: the caller checks);
// `m`, `nb` and `prep` must outlive it.
class MeshNearestNeighbours {
 public:
  MeshNearestNeighbours(const mesh::MeshView& m, const std::vector<Index>& nb, MeshWalkPrep& prep);
  ~MeshNearestNeighbours();
  bool usable() const;
  void search(std::size_t lo, std::size_t hi);
  std::vector<double> take();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fdr::quality
