// Facet intersections: facets of a PLC may meet only in shared vertices and shared polygon edges.
#pragma once
#include "plc/plc.hpp"
#include "plc/triangulate_facets.hpp"

namespace fdr::plc {

// Whether triangles s and t (ids of plc.points) meet other than in their common vertices and, if
// they share two vertices, their common edge; exact (CGAL's filtered predicates).
bool improper_triangle_pair(const Plc& plc, const Triangle& s, const Triangle& t);

// Whether segment s meets triangle t other than in their common vertices; exact.
bool improper_segment_triangle(const Plc& plc, const Edge& s, const Triangle& t);

// Whether segments s and t meet other than in a common end; exact.
bool improper_segment_pair(const Plc& plc, const Edge& s, const Edge& t);

// Throws Error(kInvalidGeometry) when triangles of two different facets meet improperly (a
// crossing, a vertex of one inside the other, an overlap, the same facet twice), or a free
// segment meets a facet or another free segment improperly, naming both facets (index and marker) and the vertices of
// both triangles. The candidate pairs come from CGAL's box intersection (O(n log^3 n + pairs));
// the first bad pair in (facet, triangle) order is reported, so the message does not depend on
// the search. Polygons of different facets are never split where they cross: that is bad input.
void check_intersections(const Plc& plc, const FacetTriangulation& ft);

}  // namespace fdr::plc
