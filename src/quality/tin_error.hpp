// Terrain runs: vertical error of the linear TIN (mesh + vertex elevations) against the DEM grid.
#pragma once
#include <utility>
#include "mesh/mesh_view.hpp"
#include "sizing/grid.hpp"

namespace fdr::quality {

// (max, RMS) of |TIN - DEM| over every DEM cell centre inside a triangle (m.z are the vertex
// elevations, same frame as the grid); (0, 0) when no cell centre falls inside the mesh.
std::pair<double, double> tin_vertical_error(const mesh::MeshView& m, const sizing::Grid& dem);

}  // namespace fdr::quality
