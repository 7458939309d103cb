// The mesher's output from the refined state: the tetrahedra of the domain with their materials,
// the subfacets and subsegments, and the per-tetrahedron quality fields.
#pragma once
#include "base/point3.hpp"
#include "tet/refiner3.hpp"
#include "tet/tet_mesh.hpp"

namespace fdr::tet {

// The smallest of the six dihedral angles, in degrees (double precision: a measurement).
double min_dihedral_deg(Point3 a, Point3 b, Point3 c, Point3 d);

// Tetrahedra outside the domain are left out, and vertices no tetrahedron uses; faces carry their
// facet's marker, edges the marker of their first facet (0 for a free segment). Cell fields
// (when asked for): r_over_f, radius_edge, min_dihedral_deg.
TetMesh make_tet_mesh(const Refiner3& r, bool cell_fields = true);

}  // namespace fdr::tet
