// --check in 3D: an independent re-check, with exact predicates, that a tetrahedral mesh is a valid,
// Delaunay tetrahedralization conforming to its PLC with R/f(c) <= B. Each step returns its first
// failure as a message naming the tetrahedron, face or facet and coordinates (nullopt: it holds).
#pragma once
#include <optional>
#include <string>
#include "plc/plc.hpp"
#include "sizing/spacing3d.hpp"
#include "tet/tet_mesh.hpp"

namespace fdr::quality {

// Every tetrahedron has positive volume (orient3d > 0, exactly) and four distinct vertices in range.
std::optional<std::string> check_orientation(const tet::TetMesh& m);

// Every face is shared by at most two tetrahedra, and the boundary faces (used once) close up:
// every edge of theirs is used by an even number of them.
std::optional<std::string> check_faces_closed(const tet::TetMesh& m);

// Every face shared by two tetrahedra is locally Delaunay: the vertex of one opposite the face is
// not strictly inside the other's circumsphere (insphere, exactly).
std::optional<std::string> check_delaunay(const tet::TetMesh& m);

// Conformity to the PLC (skipped for a PLC without facets, a point set meshed as its hull):
//  - per boundary marker, the input facets' area equals the summed area of the mesh's subfacets
//    of that marker (relative 1e-9);
//  - every subfacet lies in the plane of a facet with its marker: a vertex that is an input point
//    exactly (orient3d = 0 against the facet's first triangle), an inserted vertex within
//    1e-9 of the PLC's bounding-box diagonal, since an inserted point is a rounded circumcentre or
//    midpoint whose distance from the plane is a few units of the last place, far below that;
//  - every boundary face of the mesh is a subfacet;
//  - every input segment (facet polygon edges and free segments) is a chain of mesh edges from
//    one end to the other, each vertex on the segment within the same tolerance.
std::optional<std::string> check_conforming(const tet::TetMesh& m, const plc::Plc& plc);

// R/f(c) <= B for every tetrahedron; a relative 1e-9 allows for the rounding of the circumsphere,
// which the refiner computes in the same double precision.
std::optional<std::string> check_r_over_f(const tet::TetMesh& m, const sizing::SizingField3& f, double B);

// Every check above in order; throws Error(kCheckFailed) with the first failure.
void check_tets(const tet::TetMesh& m, const plc::Plc& plc, const sizing::SizingField3& f, double B);

}  // namespace fdr::quality
