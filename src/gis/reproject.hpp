// Reprojection of a finished mesh's nodes into another CRS (--output-crs), same topology.
#pragma once
#include <string>
#include <vector>
#include "gis/crs.hpp"
#include "mesh/mesh_view.hpp"

namespace fdr::gis {

// Throws Error(kCrsError) if `crs` (EPSG:n, PROJ string, WKT) is not a usable CRS.
void check_crs(const std::string& crs);

// Transforms every vertex (world = frame.origin() + local) from the frame's CRS to `crs`; the
// result has origin (0,0), vertices in `crs` (x = lon/easting) and crs_wkt set to `crs`.
void reproject_mesh(mesh::MeshView& m, const Frame& frame, const std::string& crs);

// WGS 84 longitude/latitude (EPSG:4326) of every vertex, from world coordinates in m.crs_wkt
// (SCHISM hgrid.ll). Throws Error(kCrsError) when the mesh has no CRS or a node cannot be
// transformed.
std::vector<LonLat> mesh_lonlat(const mesh::MeshView& m);

}  // namespace fdr::gis
