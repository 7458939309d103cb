// The spacing of a global run, computed on the sphere: the rules on a longitude/latitude grid in
// ground metres, gradient-limited in distances on the sphere, and the field the mesher reads in
// the stereographic plane (ground spacing times the projection's exact scale factor).
#pragma once
#include <cstddef>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>
#include "base/point3.hpp"
#include "base/types.hpp"
#include "gis/global_sphere.hpp"
#include "sizing/sizing_field.hpp"

namespace fdr::gis {

// A grid over the whole circle of longitude (cell centres at -180 + (i + 0.5) dlon, wrapping
// around) and latitudes lat0 + (j + 0.5) dlat. Values row-major, row 0 southmost.
struct LonLatGrid {
  std::size_t nx = 0, ny = 0;
  double lat0 = -90, dlon = 1, dlat = 1;
  std::vector<double> v;
  LonLat centre(std::size_t i, std::size_t j) const {
    return {-180.0 + (static_cast<double>(i) + 0.5) * dlon, lat0 + (static_cast<double>(j) + 0.5) * dlat};
  }
  // Bilinear between cell centres, wrapping in longitude and clamped in latitude.
  double sample(LonLat p) const;
};

// A lon/lat grid of cells of about `cell_deg` degrees (a whole number of cells around the
// circle) covering latitudes [lat_min, lat_max], values `fill`.
LonLatGrid lonlat_grid(double cell_deg, double lat_min, double lat_max, double fill);

// A geographic raster (band 1; EPSG:4326-style lon/lat, e.g. ETOPO) sampled bilinearly at the
// grid's cell centres, longitude wrapping; NaN where it has no data. Throws kInputUnreadable when
// unreadable and kCrsError when its extent is not in degrees.
struct LonLatRaster {
  std::size_t nx = 0, ny = 0;
  double x0 = 0, y0 = 0, dx = 1, dy = 1;  // lower-left corner and cell size, degrees
  std::vector<double> v;
  double sample(LonLat p) const;          // bilinear, longitude wrapping when the raster spans 360
};
LonLatRaster read_lonlat_raster(const std::string& path);

struct SphereRules {
  double hmin = 0, hmax = 0;                // metres
  std::optional<double> dist_grade;         // h = hmin + grade * great-circle distance to shore
  std::optional<double> slope;              // h = (2 pi / slp) depth / |grad depth|
  std::optional<double> wavelength;         // h = T sqrt(g depth) / wl
  double wave_period_s = 44712.0;
  double gradation = 0.15;                  // alpha on the sphere
  double cell_deg = 0;                      // 0: default_cell_deg(hmin)
};

// The grid cell of the spacing (degrees): about 2 hmin on the ground, within [0.02, 0.5]. Why
// not finer: the rules' spacing grows from hmin at the coast, and a cone of slope 0.1 is
// interpolated from cells of 2 hmin within 0.1 hmin.
double default_cell_deg(double hmin);

// Great-circle distance (metres) from every cell centre to the nearest of `shore` (unit
// vectors), by nearest-source propagation over the grid (8 neighbours, longitude wrapping):
// each cell keeps the shore point its distance is measured to. Exact at the points' cells; a
// cell may keep a shore point slightly farther than the nearest one elsewhere. No points, or
// farther than max_distance (not propagated beyond it): +inf.
void distance_to_shore_sphere(LonLatGrid& g, const std::vector<Point3>& shore, double radius = kEarthRadius,
                              double max_distance = std::numeric_limits<double>::infinity());

// Lowers g so that |g(x) - g(y)| <= alpha |x - y|_chord between neighbouring cells (chord of the
// sphere, never longer than the great circle): each cell keeps the cell its value comes from and
// offers value(source) + alpha chord(x, source) to its neighbours, in alternating sweeps until
// nothing changes. Hence alpha-Lipschitz in great-circle distance along the grid. A grid that is
// alpha-Lipschitz between neighbours already is returned unchanged after one read-only pass.
void limit_gradient_sphere(LonLatGrid& g, double alpha, double radius = kEarthRadius);

// The rules combined by minimum, clamped to [hmin, hmax], gradient-limited; the depth rules read
// `elevation` (positive up) when given. Without any rule, h = hmin + 0.1 d.
LonLatGrid sphere_spacing(const SphereRules& rules, double lat_min, const std::vector<Point3>& shore,
                          const LonLatRaster* elevation, std::string* describe = nullptr);

// f in the stereographic plane, chosen so that the refinement's test in the plane is the test on
// the sphere: a plane circle of centre c and radius r is the image of a sphere circle of radius
// R (theta(|c| + r) - theta(|c| - r)) / 2, theta(rho) = 2 atan(rho / 2R), so r <= B f(c) exactly
// when that radius is <= B g(inverse(c)), g the ground spacing:
//   f(c) = (R / B) 2 t k / (1 + sqrt(1 + t^2 k)),  t = tan(B g / R),  k = 1 + |c|^2 / 4R^2,
// which is k g (the scale factor times g) for g << R; g is lowered by alpha times the distance
// between inverse(c) and the sphere circle's centre (operator()). Thread-safe. Its Lipschitz constant in the
// plane is bounded by that of k g: alpha_sphere + max g |grad k| over the points within rho_max
// of the centre, with a margin for the terms of higher order in g / R and for the bilinear
// interpolation between cell centres.
class StereoSpacing final : public sizing::SizingField {
 public:
  StereoSpacing(std::shared_ptr<const LonLatGrid> g, SphereStereo proj, double alpha, double rho_max, double bound,
                std::string label);
  double operator()(Point2 p) const override;
  double lipschitz() const override { return lipschitz_; }
  bool thread_safe() const override { return true; }
  std::string describe() const override { return label_; }
  const LonLatGrid& ground() const { return *g_; }
  const SphereStereo& projection() const { return proj_; }

 private:
  std::shared_ptr<const LonLatGrid> g_;
  SphereStereo proj_;
  double bound_;
  double alpha_;  // of the ground spacing on the sphere, with a margin for the interpolation
  double lipschitz_;
  std::string label_;
};

}  // namespace fdr::gis
