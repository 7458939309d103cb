// Vertex insertion by Bowyer-Watson cavities bounded by constrained edges.
#pragma once
#include <vector>
#include "cdt/locate.hpp"
#include "mesh/triangulation.hpp"

namespace fdr::cdt {

// Two-phase insertion so that refinement can inspect the cavity (e.g. for subsegments the new
// vertex would encroach) before committing:
//   Inserter ins(tri);
//   if (ins.build_cavity(p, loc)) { ... inspect ins.boundary() ...; v = ins.commit(p, kind); }
//   else ins.abort();
// Flips the edge of half-edge h (and its twin): triangles (a,b,c) + (b,a,d) become (c,a,d) +
// (d,b,c). The caller guarantees a strictly convex quadrilateral.
void flip_edge(mesh::Triangulation& T, HalfEdge h);

class Inserter {
 public:
  explicit Inserter(mesh::Triangulation& tri) : tri_(tri) {}

  // Collects the triangles whose circumcircle strictly contains p, reachable from the located
  // triangle(s) without crossing constrained edges, then grows the cavity until every boundary
  // edge sees p strictly on its left (so the fan from p is valid). Returns false (and leaves the
  // mesh untouched, marks cleared) if p lies on a vertex or behind a constrained/boundary edge
  // of the cavity.
  bool build_cavity(Point2 p, Location loc);
  // Boundary half-edges of the cavity (each belongs to a cavity triangle; its twin is outside).
  const std::vector<HalfEdge>& boundary() const { return boundary_; }
  const std::vector<TriangleId>& cavity() const { return cavity_; }
  // The edge being split when p was located on an edge (kNoId otherwise).
  HalfEdge split_edge() const { return split_he_; }
  // Replaces the cavity by the fan from the new vertex; returns its id. new_triangles() lists
  // the created triangles. Splitting a constrained edge keeps both halves constrained and
  // updates the segment map.
  Index commit(Point2 p, mesh::VertexKind kind);
  // The same for a vertex already in the triangulation but in no triangle yet (the CDT adds its
  // input vertices first, so that vertex i of the input is vertex i of the triangulation).
  void commit_vertex(Index v);
  void abort();
  const std::vector<TriangleId>& new_triangles() const { return new_tris_; }

 private:
  void grow(TriangleId seed, Point2 p);
  void restore_delaunay();
  bool needs_flips_ = false;  // p off its split edge, or the repair loop ran (see build_cavity)
  void clear_marks();

  mesh::Triangulation& tri_;
  std::vector<TriangleId> cavity_, stack_, rejected_, new_tris_;
  std::vector<HalfEdge> boundary_;
  HalfEdge split_he_ = kNoId, split_twin_ = kNoId;
  struct Rim { Index x, y; HalfEdge outer; bool cons; };
  std::vector<Rim> rim_;
  std::vector<std::int32_t> rim_region_;  // Triangulation::region per rim edge (if regions are used)
};

}  // namespace fdr::cdt
