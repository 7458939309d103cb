// Frame: the working projected CRS plus a local origin, chosen once per run (UTM or a centred TM).
#pragma once
#include <memory>
#include <string>
#include <vector>
#include "base/types.hpp"
#include "sizing/sizing_field.hpp"

class OGRSpatialReference;  // GDAL's class (global namespace); only crs.cpp and friends include GDAL.

namespace fdr::gis {

class Frame {
 public:
  Frame();  // an empty frame (valid() == false); use choose_frame()
  ~Frame();
  Frame(const Frame&);
  Frame& operator=(const Frame&);
  Frame(Frame&&) noexcept;
  Frame& operator=(Frame&&) noexcept;

  bool valid() const;
  const std::string& name() const;  // short name for printing, e.g. "WGS 84 / UTM zone 18N (EPSG:32618)"
  std::string wkt() const;          // WKT2_2019 of the projected CRS
  std::string projjson() const;
  int epsg() const;                 // EPSG code of the projected CRS, 0 if it has none
  const OGRSpatialReference& srs() const;  // traditional GIS axis order (x = easting)

  // Local origin in projected (world) coordinates: world = origin + local.
  Point2 origin() const;
  // Bounding box of the sample the frame was chosen from, in local coordinates.
  Box2 domain_box() const;
  void set_domain_box(const Box2& b);

  Point2 to_world(Point2 local) const { return origin() + local; }
  Point2 to_local_world(Point2 world) const { return world - origin(); }
  // (x, y) in `src` (traditional GIS order: x = lon/easting) -> local frame. Builds a
  // transformation per call: use to_local_batch() for many points.
  Point2 to_local(double x, double y, const OGRSpatialReference& src) const;
  // Transforms xy (in src) to local coordinates in place; throws kCrsError naming `what` when a
  // point cannot be transformed.
  void to_local_batch(std::vector<Point2>& xy, const OGRSpatialReference& src,
                      const std::string& what) const;
  Point2 lonlat_to_local(LonLat ll) const;
  LonLat to_lonlat(Point2 local) const;  // WGS 84 (EPSG:4326) longitude/latitude
  // Point scale factor of the projection at a local point: ground distance * k = grid distance.
  // Conformal projections (UTM, TM): the scale k. Others: sqrt(areal scale), the geometric mean
  // of the meridional and parallel scales (PROJ proj_factors()).
  double scale_factor(Point2 local) const;

  // Builds a frame from an explicit CRS (PROJ string, EPSG:n, WKT, anything SetFromUserInput
  // accepts) and origin; throws kCrsError if the CRS is unknown or not projected.
  static Frame from_crs(const std::string& crs, Point2 origin);

  struct Impl;  // opaque (OGR/PROJ objects)

 private:
  std::shared_ptr<Impl> impl_;  // immutable after construction, shared by copies
  Box2 domain_box_;
  friend Frame choose_frame(const std::vector<LonLat>&, const std::string&);
};

// Working frame for a domain given by lon/lat points (a sample of its vertices or its bbox
// corners). If t_srs is non-empty it is used (any PROJ string / EPSG:n / WKT; must be projected).
// Otherwise: the UTM zone of the domain centre (north/south) if the domain is at most 6 degrees
// wide in longitude and within |lat| < 84; else a transverse Mercator centred on the domain
// (k0 = 1). TM rather than Lambert azimuthal equal-area because TM is conformal: the scale is the
// same in every direction, so an isotropic ground spacing maps to an isotropic grid spacing by a
// single factor k (ground_to_grid below) and angles, hence triangle quality, are preserved.
// Domains wider than 120 degrees of longitude are refused (kCrsError: give --t_srs).
// The origin is the domain centre rounded to a round number of metres.
Frame choose_frame(const std::vector<LonLat>& sample_or_bbox, const std::string& t_srs);

// f_grid(p) = f_ground(p) * k(p) when max |k - 1| over the frame's domain box (5 % margin) exceeds
// 1e-3; k is precomputed on a coarse grid (<= 65 x 65) and interpolated bilinearly. Otherwise
// returns f_ground unchanged. *max_abs_k_minus_1 receives max |k - 1| over that grid.
sizing::SizingPtr ground_to_grid(sizing::SizingPtr f_ground, const Frame& frame,
                                 double* max_abs_k_minus_1 = nullptr);
// The same over an explicit local box.
sizing::SizingPtr ground_to_grid(sizing::SizingPtr f_ground, const Frame& frame, const Box2& local_box,
                                 double* max_abs_k_minus_1 = nullptr);

}  // namespace fdr::gis
