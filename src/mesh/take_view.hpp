// The compact mesh of a triangulation, built while the triangulation's arrays are released.
#pragma once
#include "mesh/mesh_view.hpp"
#include "mesh/triangulation.hpp"

namespace fdr::mesh {

// Same MeshView as t.to_view() (same vertex, triangle and edge order, same markers), but each
// array of `t` is freed as soon as it has been copied, so the peak is the triangulation plus
// about a third of the copy instead of both whole. `t` is left empty.
MeshView take_view(Triangulation& t);

}  // namespace fdr::mesh
