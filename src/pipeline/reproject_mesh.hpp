// --output-crs: a reprojected copy of a finished mesh (same topology), over gis::reproject_points.
#pragma once
#include <string>
#include "gis/reproject.hpp"  // check_crs, Frame
#include "mesh/mesh_view.hpp"

namespace fdr::pipeline {

// Transforms every vertex (world = m.origin + local) from the frame's CRS to `crs`; the result
// has origin (0,0), vertices in `crs` (x = lon/easting) and crs_wkt set to `crs`.
void reproject_mesh(mesh::MeshView& m, const gis::Frame& frame, const std::string& crs);

}  // namespace fdr::pipeline
