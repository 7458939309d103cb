// Sphere formulas of global runs (global_sphere.hpp).
#include "gis/global_sphere.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace fdr::gis {
namespace {
constexpr double kDeg = std::numbers::pi / 180.0;

double wrap_lon(double lon) {
  while (lon > 180.0) lon -= 360.0;
  while (lon < -180.0) lon += 360.0;
  return lon;
}
}  // namespace

SphereStereo::SphereStereo(LonLat pole, double radius) : pole_(pole), r_(radius), inv_4r2_(0.25 / (radius * radius)) {
  centre_ = {wrap_lon(pole.lon_deg + 180.0), -pole.lat_deg};
  sin_c_ = std::sin(centre_.lat_deg * kDeg);
  cos_c_ = std::cos(centre_.lat_deg * kDeg);
  if (centre_.lat_deg == 90.0) { sin_c_ = 1; cos_c_ = 0; }
  if (centre_.lat_deg == -90.0) { sin_c_ = -1; cos_c_ = 0; }
  lon0_rad_ = centre_.lon_deg * kDeg;
}

std::string SphereStereo::proj_string() const {
  char buf[256];
  std::snprintf(buf, sizeof buf, "+proj=stere +lat_0=%.17g +lon_0=%.17g +k=1 +x_0=0 +y_0=0 +R=%.17g +units=m +no_defs",
                centre_.lat_deg, centre_.lon_deg, r_);
  return buf;
}

Point2 SphereStereo::forward(LonLat ll) const {
  const double phi = ll.lat_deg * kDeg, dl = ll.lon_deg * kDeg - lon0_rad_;
  const double sp = std::sin(phi), cp = std::cos(phi), cd = std::cos(dl), sd = std::sin(dl);
  const double k = 2.0 / (1.0 + sin_c_ * sp + cos_c_ * cp * cd);
  return {r_ * k * cp * sd, r_ * k * (cos_c_ * sp - sin_c_ * cp * cd)};
}

LonLat SphereStereo::inverse(Point2 p) const {
  const double rho = std::hypot(p.x, p.y);
  if (rho == 0) return centre_;
  const double c = 2.0 * std::atan(rho / (2.0 * r_));
  const double sc = std::sin(c), cc = std::cos(c);
  const double phi = std::asin(std::clamp(cc * sin_c_ + p.y * sc * cos_c_ / rho, -1.0, 1.0));
  const double lam = lon0_rad_ + std::atan2(p.x * sc, rho * cos_c_ * cc - p.y * sin_c_ * sc);
  return {wrap_lon(lam / kDeg), phi / kDeg};
}

Point3 unit_vector(LonLat ll) {
  const double phi = ll.lat_deg * kDeg, lam = ll.lon_deg * kDeg;
  const double cp = std::cos(phi);
  return {cp * std::cos(lam), cp * std::sin(lam), std::sin(phi)};
}

LonLat to_lonlat(Point3 u) {
  return {std::atan2(u.y, u.x) / kDeg, std::atan2(u.z, std::hypot(u.x, u.y)) / kDeg};
}

double great_circle(Point3 a, Point3 b, double r) { return r * std::atan2(std::sqrt(norm2(cross(a, b))), dot(a, b)); }

double great_circle(LonLat a, LonLat b, double r) { return great_circle(unit_vector(a), unit_vector(b), r); }

double spherical_triangle_area(Point3 a, Point3 b, Point3 c, double r) {
  const double num = dot(a, cross(b, c));
  const double den = 1.0 + dot(a, b) + dot(b, c) + dot(c, a);
  return 2.0 * std::atan2(num, den) * r * r;
}

Point3 spherical_circumcentre(Point3 a, Point3 b, Point3 c) {
  const Point3 n = cross(b - a, c - a);
  const double l = std::sqrt(norm2(n));
  return l > 0 ? (1.0 / l) * n : a;
}

double spherical_circumradius(Point3 a, Point3 b, Point3 c, double r) {
  return great_circle(spherical_circumcentre(a, b, c), a, r);
}

}  // namespace fdr::gis
