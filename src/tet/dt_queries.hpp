// Queries over a Delaunay3 that refinement needs (stars, edges, faces, conflict regions), as free
// functions over its public interface.
#pragma once
#include <array>
#include <functional>
#include <vector>
#include "base/point3.hpp"
#include "base/threads.hpp"
#include "tet/delaunay3.hpp"

namespace fdr::tet {

// Every live tetrahedron (ghosts included) with v as a vertex, by a walk across the faces at v.
// Empty while dimension() < 3.
void vertex_star(const Delaunay3& dt, VertexId v, std::vector<TetId>& out);

// The tetrahedra (ghosts included) with edge ab; false when ab is not an edge.
bool edge_tets(const Delaunay3& dt, VertexId a, VertexId b, std::vector<TetId>& out);
// The first of those (the same as edge_tets' first), by a's star walked only until one turns up;
// kNoId when ab is not an edge.
TetId edge_tet(const Delaunay3& dt, VertexId a, VertexId b);
// The vertices of the tetrahedra around edge ab other than a and b (kInfinite included), each
// once, in their order around the edge starting from tetrahedron t (which has edge ab).
void edge_ring(const Delaunay3& dt, TetId t, VertexId a, VertexId b, std::vector<VertexId>& out);

// The vertices opposite face abc in the (at most two) tetrahedra that have it (kInfinite for a
// ghost); returns how many there are (0: abc is not a face).
int face_apexes(const Delaunay3& dt, VertexId a, VertexId b, VertexId c, std::array<VertexId, 2>& apex);

// The tetrahedra that inserting p would destroy, without changing dt: from `start` (a finite
// tetrahedron whose closed circumsphere holds p, e.g. the one p lies in or the one p is the
// circumcentre of), those in conflict with p (in_conflict) connected through faces.
void conflict_region(const Delaunay3& dt, Point3 p, TetId start, std::vector<TetId>& out);
// The same, giving up (false) once the region would hold more than `max_size` tetrahedra: e.g. a
// candidate point that would destroy that many is no local repair.
bool conflict_region(const Delaunay3& dt, Point3 p, TetId start, std::vector<TetId>& out, std::size_t max_size);

// Whether inserting p destroys t, by Delaunay3's own test: a finite tetrahedron whose circumsphere
// holds p strictly inside; a ghost whose hull face p lies strictly beyond or, on the face's plane,
// whose finite neighbour is in conflict (points split into a facet on the hull lie on that plane,
// and their cavity may join its finite tetrahedra only through such ghosts).
bool in_conflict(const Delaunay3& dt, TetId t, Point3 p);

// Frees the calling thread's marks that the walks above keep between calls (4 bytes per
// tetrahedron slot), e.g. once refinement is over and the mesh is copied out.
void release_query_scratch();

// Over the vertices of the finite tetrahedra that `keep` accepts: the shortest and the longest
// edge of those tetrahedra at each vertex, over f at the vertex; the least shortest (nn/f, Theorem
// 4.4) and the greatest longest (el/f, Theorem 4.5). Both 0 when no tetrahedron is kept. `keep`
// is called on up to `threads` threads at once; the result is the same for any count.
struct VertexEdgeRatios {
  double nn_over_f_min = 0;
  double el_over_f_max = 0;
};
VertexEdgeRatios vertex_edge_ratios(const Delaunay3& dt, const std::function<bool(TetId)>& keep,
                                    const std::function<double(Point3)>& f, unsigned threads = max_threads());

// Whether p lies strictly beyond ghost g's hull face.
bool beyond_hull_face(const Delaunay3& dt, TetId g, Point3 p);

}  // namespace fdr::tet
