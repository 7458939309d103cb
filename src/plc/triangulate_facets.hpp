// Facet triangulation: each facet of a PLC as a constrained Delaunay triangulation in its own
// plane, and the subsegments (polygon edges) with the facets that share them.
#pragma once
#include <array>
#include <cstdint>
#include <vector>
#include "plc/facet_frame.hpp"
#include "plc/plc.hpp"

namespace fdr::plc {

using Triangle = std::array<VertexId, 3>;
using Edge = std::array<VertexId, 2>;  // a < b

struct Subsegment {
  VertexId a = 0, b = 0;               // a < b
  std::vector<std::uint32_t> facets;   // facets with this edge on a polygon, increasing; empty: a free segment
};

struct FacetTriangulation {
  // Per facet its triangles (ids of Plc::points), counter-clockwise seen from the side its frame's
  // normal (p1 - p0) x (p2 - p0) points to (facet_frame.hpp).
  std::vector<std::vector<Triangle>> triangles;
  std::vector<FacetFrame> frames;  // per facet its plane and projection (facet_frame.hpp)
  // Every polygon edge once, split where a vertex of its facet lies on it, then every free
  // segment (Plc::segments) once; sorted by (a, b).
  std::vector<Subsegment> subsegments;
};

// One facet in its projection (FacetFrame::drop_axis): the 2D constrained Delaunay triangulation
// of its polygons (src/cdt) with the regions of its hole points and the outside removed
// (Triangle's .poly semantics: a polygon without a hole point inside bounds part of the facet).
// Triangles are counter-clockwise in the projection; `constrained` gets the polygon edges as
// they appear in the triangulation (split at vertices on them), each once.
std::vector<Triangle> triangulate_in_projection(const Plc& plc, std::size_t f, const FacetFrame& frame,
                                                std::vector<Edge>& constrained);

// Lawson flips until every edge that is not in `constrained` is locally Delaunay in the facet's
// true plane, decided by incircle_in_plane (exact). Triangles keep their orientation.
void make_delaunay_in_plane(const Plc& plc, const FacetFrame& frame, const std::vector<Edge>& constrained,
                            std::vector<Triangle>& tris);

// Every facet (expects a PLC that passed check(); bad input that check() would report may throw
// here from the 2D triangulation, with the facet named). A facet left without triangles (no
// closed polygon, or hole points removing all of it) is an Error(kInvalidGeometry). Crossing polygons of different facets
// are not split here: check() reports them as bad input.
FacetTriangulation triangulate_facets(const Plc& plc);

}  // namespace fdr::plc
