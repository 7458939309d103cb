// The compact mesh of a triangulation, built while the triangulation's arrays are released.
#pragma once
#include "mesh/mesh_view.hpp"
#include "mesh/triangulation.hpp"

namespace fdr::mesh {

// Same MeshView as t.to_view() (same vertex, triangle and edge order, same markers), built in
// place: the positions, the corners and the twins are compacted and
// renumbered in their own arrays, which the view then takes over; the other arrays are freed.
// No second copy of the mesh, so no fresh pages and no rise of the peak. `t` is left empty.
MeshView take_view(Triangulation& t);

}  // namespace fdr::mesh
