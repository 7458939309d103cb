// World coordinates in a given CRS to WGS 84 longitude/latitude (SCHISM hgrid.ll).
#pragma once
#include <string>
#include <vector>
#include "base/types.hpp"

namespace fdr::gis {

// Longitude/latitude (EPSG:4326) of origin + pts[i], given in the CRS `crs_wkt` (any string
// OGRSpatialReference::SetFromUserInput accepts). Throws Error(kCrsError) when crs_wkt is empty
// or unusable, or a point cannot be transformed (naming the 1-based node and its coordinates).
std::vector<LonLat> points_to_lonlat(const std::vector<Point2>& pts, Point2 origin, const std::string& crs_wkt);

}  // namespace fdr::gis
