// Lon/lat geometries of a global mesh across the antimeridian (GeoPackage output of --global runs).
#pragma once
#include <cmath>
#include <cstddef>
#include "base/types.hpp"

namespace fdr::io {

// Continues the longitudes of p[0..n) across +-180 so that consecutive points differ by at most
// 180 degrees (a triangle from 179.9 to -179.9 gets 180.1): the geometry then draws as the short
// piece it is instead of a band around the globe. A closed line whose longitudes would not come
// back to their start (a coast ring around a pole) is left as it is. Returns true when changed.
inline bool continue_longitudes(Point2* p, std::size_t n, bool closed) {
  if (n < 2) return false;
  auto step = [](double prev, double x) {
    if (x - prev > 180.0) return -360.0;
    if (x - prev < -180.0) return 360.0;
    return 0.0;
  };
  double shift = 0, prev = p[0].x;
  bool any = false;
  for (std::size_t i = 1; i < n; ++i) {
    shift += step(prev, p[i].x + shift);
    any |= shift != 0;
    prev = p[i].x + shift;
  }
  if (!any || (closed && std::fabs(prev - p[0].x) > 180.0)) return false;
  shift = 0;
  prev = p[0].x;
  for (std::size_t i = 1; i < n; ++i) {
    shift += step(prev, p[i].x + shift);
    p[i].x += shift;
    prev = p[i].x;
  }
  return true;
}

}  // namespace fdr::io
