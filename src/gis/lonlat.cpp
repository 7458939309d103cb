// World coordinates to WGS 84 lon/lat through OGRCoordinateTransformation (traditional GIS order).
#include "gis/lonlat.hpp"
#include <memory>
#include <ogr_spatialref.h>
#include "base/error.hpp"
#include "gis/gdal_util.hpp"

namespace fdr::gis {

std::vector<LonLat> points_to_lonlat(const std::vector<Point2>& pts, Point2 origin, const std::string& crs_wkt) {
  if (crs_wkt.empty())
    throw Error(ExitCode::kCrsError, "the mesh has no CRS, so its nodes cannot be given in lon/lat (EPSG:4326)");
  ensure_gdal_registered();
  OGRSpatialReference src;
  {
    GdalQuiet quiet;
    if (src.SetFromUserInput(crs_wkt.c_str()) != OGRERR_NONE)
      throw Error(ExitCode::kCrsError, "the mesh CRS cannot be parsed");
  }
  src.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  OGRSpatialReference dst;
  dst.importFromEPSG(4326);
  dst.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<OGRCoordinateTransformation, void (*)(OGRCoordinateTransformation*)> ct(
      OGRCreateCoordinateTransformation(&src, &dst), OGRCoordinateTransformation::DestroyCT);
  if (!ct) throw Error(ExitCode::kCrsError, "no transformation from the mesh CRS to EPSG:4326");
  const std::size_t n = pts.size();
  std::vector<double> x(n), y(n);
  std::vector<int> ok(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = origin.x + pts[i].x;
    y[i] = origin.y + pts[i].y;
  }
  if (n && !ct->Transform(n, x.data(), y.data(), nullptr, ok.data()))
    for (std::size_t i = 0; i < n; ++i)
      if (!ok[i])
        throw Error(ExitCode::kCrsError, "node " + std::to_string(i + 1) + " at (" + std::to_string(origin.x + pts[i].x) +
                                             ", " + std::to_string(origin.y + pts[i].y) +
                                             ") cannot be transformed to EPSG:4326");
  std::vector<LonLat> out(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = {x[i], y[i]};
  return out;
}

}  // namespace fdr::gis
