// Reprojection of a finished mesh's nodes into another CRS (--output-crs), same topology.
#pragma once
#include <string>
#include "gis/crs.hpp"
#include "mesh/mesh_view.hpp"

namespace fdr::gis {

// Throws Error(kCrsError) if `crs` (EPSG:n, PROJ string, WKT) is not a usable CRS.
void check_crs(const std::string& crs);

// Transforms every vertex (world = frame.origin() + local) from the frame's CRS to `crs`; the
// result has origin (0,0), vertices in `crs` (x = lon/easting) and crs_wkt set to `crs`.
void reproject_mesh(mesh::MeshView& m, const Frame& frame, const std::string& crs);

}  // namespace fdr::gis
