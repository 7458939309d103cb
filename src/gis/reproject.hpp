// Reprojection of a finished mesh's nodes into another CRS (--output-crs); the mesh itself is
// pipeline's (pipeline/reproject_mesh.hpp): gis only transforms points.
#pragma once
#include <string>
#include "gis/crs.hpp"
#include <vector>
#include "base/types.hpp"

namespace fdr::gis {

// Throws Error(kCrsError) if `crs` (EPSG:n, PROJ string, WKT) is not a usable CRS.
void check_crs(const std::string& crs);

// Transforms every point (world = origin + pts[i], in the frame's CRS) to `crs` in place
// (x = lon/easting) and returns the WKT of `crs`. Throws Error(kCrsError) naming the node.
std::string reproject_points(std::vector<Point2>& pts, Point2 origin, const Frame& frame, const std::string& crs);

}  // namespace fdr::gis
