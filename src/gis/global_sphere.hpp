// The sphere of global runs: its stereographic projection (the working frame of --global), great-
// circle lengths and areas, and Earth-centred coordinates. Pure formulas, no PROJ.
#pragma once
#include <array>
#include <string>
#include "base/point3.hpp"
#include "base/types.hpp"

namespace fdr::gis {

// Mean Earth radius (IUGG R1), metres. Global ocean models treat longitude/latitude as spherical
// coordinates on one sphere; the mesh, its spacing and its report all use this one.
inline constexpr double kEarthRadius = 6371008.8;

// Stereographic projection of the sphere whose point at infinity is `pole` (a point inside the
// land mass that bounds the ocean): its centre of projection is the antipode of `pole`, scale 1
// there. Conformal and circle-preserving, so a Delaunay triangulation in the plane is one on the
// sphere. World coordinates in metres, false easting/northing 0 (the local origin of the frame).
class SphereStereo {
 public:
  explicit SphereStereo(LonLat pole = {0, -90}, double radius = kEarthRadius);
  LonLat pole() const { return pole_; }
  LonLat centre() const { return centre_; }
  double radius() const { return r_; }
  // The same projection as a PROJ string ("+proj=stere ... +R=..."): the working CRS.
  std::string proj_string() const;
  Point2 forward(LonLat ll) const;   // the pole itself maps to +-inf
  LonLat inverse(Point2 p) const;    // longitude in [-180, 180]
  // Point scale factor (grid length / ground length) at world point p: 1 + |p|^2 / (4 R^2).
  double scale(Point2 p) const { return 1.0 + (p.x * p.x + p.y * p.y) * inv_4r2_; }

 private:
  LonLat pole_, centre_;
  double r_, inv_4r2_;
  double sin_c_, cos_c_, lon0_rad_;
};

// Unit vector of a lon/lat point (x towards (0, 0), z towards the north pole).
Point3 unit_vector(LonLat ll);
// Earth-centred Cartesian coordinates on the sphere of radius r.
inline Point3 sphere_xyz(LonLat ll, double r = kEarthRadius) { return r * unit_vector(ll); }
// Great-circle distance between unit vectors (atan2 of |a x b| and a . b: accurate at every angle).
double great_circle(Point3 a, Point3 b, double r = kEarthRadius);
double great_circle(LonLat a, LonLat b, double r = kEarthRadius);
// Area of the spherical triangle abc (unit vectors), signed (positive counter-clockwise seen from
// outside the sphere), by the Van Oosterom-Strackee formula for its solid angle.
double spherical_triangle_area(Point3 a, Point3 b, Point3 c, double r = kEarthRadius);
// Circumradius on the sphere: the great-circle distance from the triangle's circumcentre (the
// normalised (b - a) x (c - a)) to its vertices.
double spherical_circumradius(Point3 a, Point3 b, Point3 c, double r = kEarthRadius);
// The circumcentre of triangle abc (unit vectors, counter-clockwise) on the sphere.
Point3 spherical_circumcentre(Point3 a, Point3 b, Point3 c);
LonLat to_lonlat(Point3 unit);

}  // namespace fdr::gis
