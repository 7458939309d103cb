// Wells from an OGR source, and the GIS files a terrain run makes for its 2D run and its user: an
// in-memory point layer (the wells as fixed vertices of the terrain TIN), the wells layer of the
// top-surface GeoPackage, and the domain polygon taken from a DEM's valid data.
#pragma once
#include <array>
#include <string>
#include <vector>
#include "base/point3.hpp"
#include "base/types.hpp"
#include "gis/crs.hpp"
#include "terrain/wells.hpp"

namespace fdr::terrain {

// A GDAL in-memory (/vsimem/) dataset, removed when this goes.
class MemLayer {
 public:
  MemLayer() = default;
  explicit MemLayer(std::string path) : path_(std::move(path)) {}
  ~MemLayer();
  MemLayer(MemLayer&& o) noexcept : path_(std::move(o.path_)) { o.path_.clear(); }
  MemLayer& operator=(MemLayer&& o) noexcept;
  MemLayer(const MemLayer&) = delete;
  MemLayer& operator=(const MemLayer&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// Where the wells are: an OGR source, its layer ("" = the first) and the CRS of a layer without one.
struct WellsSource {
  std::string path, layer, s_srs;
};

// The wells of `src`, one per feature, in the local frame of `frame`:
// - a Point (Z ignored) with its range from attributes, matched case-insensitively: `top` and
//   `bottom` (elevations, metres, positive up) or `depth_from` and `depth_to` (depths below the DEM
//   at the well, metres, positive down);
// - a LineString with Z: a vertical well from its highest to its lowest vertex; its vertices must
//   lie within `max_offset` metres of its first one in xy (deviated wells are not modelled).
// An optional `name` attribute names the well in messages and in the outputs (else "FID n").
// Errors (fdr::Error) name the file, layer, feature id and coordinates: kInputUnreadable (cannot
// open, no such layer), kCrsError (no CRS and no s_srs), kInvalidGeometry (another geometry, no
// range, a deviated line), kUsage (a layer without features).
std::vector<Well> read_wells(const WellsSource& src, const gis::Frame& frame, double max_offset);

// The wells' positions as a point layer in their own CRS (one point per feature, the first vertex
// of a line), for the 2D run to take as fixed vertices. Checks every feature as read_wells does
// except the deviation, before any meshing.
MemLayer wells_point_layer(const WellsSource& src);

// The local frame's nearest point of `xy` to p and its squared distance, or {xy.size(), inf}.
std::pair<std::size_t, double> nearest_vertex(const std::vector<Point2>& xy, Point2 p);

// One well as the GeoPackage shows it: its name, its vertical line in world coordinates.
struct WellLine {
  std::string name;
  std::array<Point3, 2> line;
};

// Adds (or replaces) the layer `wells` (LineString Z, fields name, top, bottom) in the GeoPackage
// at `path`, in the CRS `crs_wkt`. Throws Error(kOutputError) naming the file.
void write_wells_layer(const std::string& path, const std::string& crs_wkt, const std::vector<WellLine>& wells);

// The domain polygon of a DEM: the box of its cells with valid data (not nodata), from the centre
// of the first such cell to the centre of the last in each direction, as a polygon layer in the
// DEM's CRS. Errors name `option` and the file: kInputUnreadable, kCrsError (no CRS), kInvalidSpacing
// (no valid cell).
MemLayer dem_extent_layer(const std::string& dem, const std::string& option = "--dem");

}  // namespace fdr::terrain
