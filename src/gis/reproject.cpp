// --output-crs: node reprojection through OGRCoordinateTransformation (traditional GIS order).
#include "gis/reproject.hpp"
#include <memory>
#include <ogr_spatialref.h>
#include "base/error.hpp"
#include "gis/gdal_util.hpp"

namespace fdr::gis {
namespace {
OGRSpatialReference parse(const std::string& crs) {
  OGRSpatialReference s;
  GdalQuiet quiet;
  if (s.SetFromUserInput(crs.c_str()) != OGRERR_NONE)
    throw Error(ExitCode::kCrsError, "--output-crs '" + crs + "': unknown CRS");
  s.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  return s;
}
}  // namespace

void check_crs(const std::string& crs) { (void)parse(crs); }

void reproject_mesh(mesh::MeshView& m, const Frame& frame, const std::string& crs) {
  ensure_gdal_registered();
  OGRSpatialReference dst = parse(crs);
  OGRSpatialReference src = frame.srs();
  src.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<OGRCoordinateTransformation, void (*)(OGRCoordinateTransformation*)> ct(
      OGRCreateCoordinateTransformation(&src, &dst), OGRCoordinateTransformation::DestroyCT);
  if (!ct) throw Error(ExitCode::kCrsError, "--output-crs '" + crs + "': no transformation from " + frame.name());
  const std::size_t n = m.vertices.size();
  std::vector<double> x(n), y(n);
  std::vector<int> ok(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const Point2 w = m.world(static_cast<Index>(i));
    x[i] = w.x;
    y[i] = w.y;
  }
  if (n && !ct->Transform(n, x.data(), y.data(), nullptr, ok.data()))
    for (std::size_t i = 0; i < n; ++i)
      if (!ok[i])
        throw Error(ExitCode::kCrsError, "--output-crs '" + crs + "': node " + std::to_string(i) + " at (" +
                                             std::to_string(x[i]) + ", " + std::to_string(y[i]) + ") cannot be transformed");
  for (std::size_t i = 0; i < n; ++i) m.vertices[i] = {x[i], y[i]};
  m.origin = {0, 0};
  char* wkt = nullptr;
  const char* opts[] = {"FORMAT=WKT2_2019", nullptr};
  dst.exportToWkt(&wkt, opts);
  m.crs_wkt = wkt ? wkt : "";
  CPLFree(wkt);
}

}  // namespace fdr::gis
