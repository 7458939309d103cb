// --output-crs: a reprojected copy of a finished mesh (same topology).
#include "pipeline/reproject_mesh.hpp"
#include "gis/reproject.hpp"

namespace fdr::pipeline {

void reproject_mesh(mesh::MeshView& m, const gis::Frame& frame, const std::string& crs) {
  m.crs_wkt = gis::reproject_points(m.vertices, m.origin, frame, crs);
  m.origin = {0, 0};
}

}  // namespace fdr::pipeline
