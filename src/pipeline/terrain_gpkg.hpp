// The GIS user's view of a terrain volume: its top surface as a GeoPackage (the terrain TIN with
// the DEM's elevation at every node, the domain outline the side walls stand on, the layers'
// names and figures).
#pragma once
#include <string>
#include <vector>
#include "pipeline/pipeline.hpp"
#include "pipeline/run3d.hpp"

namespace fdr::pipeline {

// The metadata rows that name the volume's parts: `terrain_surfaces` (from the top down,
// comma-separated), `terrain_marker_<m>` (the facet marker m's name: top, base, side, horizons),
// `terrain_layer_<i>` (material i's name) and `terrain_layers` (the report's layers as JSON).
std::vector<std::pair<std::string, std::string>> terrain_metadata(const Result3& r, const std::vector<std::string>& surfaces);

// Writes the 2D run's terrain TIN (nodes with z = the DEM's elevation, triangles, boundaries =
// the outline of the side walls, repairs) and terrain_metadata() to `path`, atomically.
void write_top_gpkg(const std::string& path, const Result& tin_run, const Result3& r,
                    const std::vector<std::string>& surfaces, const std::string& source);

}  // namespace fdr::pipeline
