// Orthogonality and smoothness of a triangle mesh, the two grid checks Delft3D FM users make:
// a flow link joins the cell centres of the two triangles of an interior edge and should cross
// that edge at a right angle; neighbouring cells should have similar areas.
//
// Why not raw circumcentres: both circumcentres of the triangles sharing an edge lie on that
// edge's perpendicular bisector, so their link is always orthogonal (cos = 0 up to rounding).
// D-Flow FM, however, moves a circumcentre that falls outside its triangle back into the cell
// (its default dcenterinside = 1); obtuse triangles then give non-orthogonal links. The cell
// centre used here is therefore the circumcentre, or when it lies outside the triangle the
// nearest point of the triangle's boundary.
#pragma once
#include <cstddef>
#include <optional>
#include <vector>
#include "mesh/mesh_view.hpp"

namespace fdr::quality {

struct OrthogonalityStats {
  std::size_t interior_edges = 0;  // edges shared by two triangles
  // |cos| of the angle between an interior edge and the link joining the cell centres (above) of
  // its two triangles: 0 is orthogonal. A link of zero length (two right triangles sharing their
  // hypotenuse) counts as 0. nullopt without interior edges.
  std::optional<double> orthogonality_max, orthogonality_p99;
  // Area ratio of the two triangles of an interior edge, larger over smaller (>= 1).
  std::optional<double> smoothness_max, smoothness_p99;
};

// Over the interior edges through the mesh adjacency (MeshView::neighbours, else built from the
// triangles), cell centres from geom::circumcentre (base/triangle_geometry.hpp) in the local
// frame. p99 is the nearest-rank 99th percentile over the interior edges.
// `threads` > 1 measures two halves of the triangles at once (same figures).
OrthogonalityStats compute_orthogonality(const mesh::MeshView& m, unsigned threads = 1);

struct MeshWalkPrep;  // quality/mesh_adjacency.hpp
// The same with the adjacency `nb` (MeshView::neighbours' convention, vertex ids valid); when
// `prep` is not null it also gets, from the same pass, what mesh_nearest_neighbour_sq needs
// (then one thread).
OrthogonalityStats compute_orthogonality(const mesh::MeshView& m, const std::vector<Index>& nb, MeshWalkPrep* prep,
                                         unsigned threads = 1);

}  // namespace fdr::quality
