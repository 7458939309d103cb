// The spacing of global runs on the sphere (global_spacing.hpp).
#include "gis/global_spacing.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <numbers>

#include "base/error.hpp"
#include "base/num_format.hpp"
#include "base/step_laps.hpp"
#include "gis/raster_input.hpp"

namespace fdr::gis {

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kInf = std::numeric_limits<double>::infinity();

// Unit vectors of the cell centres, row-major as the grid.
std::vector<Point3> cell_vectors(const LonLatGrid& g) {
  std::vector<double> co(g.nx), so(g.nx);
  for (std::size_t i = 0; i < g.nx; ++i) {
    const double lam = g.centre(i, 0).lon_deg * kDeg;
    co[i] = std::cos(lam);
    so[i] = std::sin(lam);
  }
  std::vector<Point3> u(g.nx * g.ny);
  for (std::size_t j = 0; j < g.ny; ++j) {
    const double phi = g.centre(0, j).lat_deg * kDeg, cl = std::cos(phi), sl = std::sin(phi);
    for (std::size_t i = 0; i < g.nx; ++i) u[j * g.nx + i] = {cl * co[i], cl * so[i], sl};
  }
  return u;
}

// Alternating raster sweeps over the grid's 8-neighbourhood (longitude wrapping) until a pair of
// sweeps changes nothing; offer(c, nb) returns true when cell c took something from cell nb.
template <class Offer>
void sweep_until_stable(const LonLatGrid& g, Offer&& offer) {
  const auto nx = static_cast<std::int64_t>(g.nx), ny = static_cast<std::int64_t>(g.ny);
  auto id = [nx](std::int64_t i, std::int64_t j) {
    return static_cast<std::size_t>(j * nx + ((i % nx) + nx) % nx);
  };
  for (int pass = 0; pass < 1000; ++pass) {
    bool changed = false;
    // Each row also runs back the other way (Danielsson's scheme): a value travels along its row
    // in both directions within one sweep.
    for (std::int64_t j = 0; j < ny; ++j) {
      for (std::int64_t i = 0; i < nx; ++i) {
        const std::size_t c = id(i, j);
        changed |= offer(c, id(i - 1, j));
        if (j > 0) {
          changed |= offer(c, id(i - 1, j - 1));
          changed |= offer(c, id(i, j - 1));
          changed |= offer(c, id(i + 1, j - 1));
        }
      }
      for (std::int64_t i = nx - 1; i >= 0; --i) changed |= offer(id(i, j), id(i + 1, j));
    }
    for (std::int64_t j = ny - 1; j >= 0; --j) {
      for (std::int64_t i = nx - 1; i >= 0; --i) {
        const std::size_t c = id(i, j);
        changed |= offer(c, id(i + 1, j));
        if (j + 1 < ny) {
          changed |= offer(c, id(i + 1, j + 1));
          changed |= offer(c, id(i, j + 1));
          changed |= offer(c, id(i - 1, j + 1));
        }
      }
      for (std::int64_t i = 0; i < nx; ++i) changed |= offer(id(i, j), id(i - 1, j));
    }
    if (!changed) { if (debug::on(debug::Aid::kSizing)) std::fprintf(stderr, "sphere sweeps: %d pass pairs\n", pass + 1); return; }
  }
}

double first_diff(const LonLatGrid& g, const std::vector<double>& d, std::size_t i, std::size_t j, bool along_lon) {
  if (along_lon) {
    const std::size_t a = (i + g.nx - 1) % g.nx, b = (i + 1) % g.nx;
    return (d[j * g.nx + b] - d[j * g.nx + a]) / 2.0;
  }
  const std::size_t j0 = j > 0 ? j - 1 : j, j1 = j + 1 < g.ny ? j + 1 : j;
  return j1 > j0 ? (d[j1 * g.nx + i] - d[j0 * g.nx + i]) / static_cast<double>(j1 - j0) : 0.0;
}

}  // namespace

double LonLatGrid::sample(LonLat p) const {
  const double fx = (p.lon_deg + 180.0) / dlon - 0.5;
  const double fi = std::floor(fx);
  const double t = fx - fi;
  const auto n = static_cast<std::int64_t>(nx);
  const std::size_t i0 = static_cast<std::size_t>(((static_cast<std::int64_t>(fi) % n) + n) % n);
  const std::size_t i1 = (i0 + 1) % nx;
  const double fy = std::clamp((p.lat_deg - lat0) / dlat - 0.5, 0.0, static_cast<double>(ny - 1));
  const std::size_t j0 = std::min(static_cast<std::size_t>(fy), ny > 1 ? ny - 2 : 0);
  const std::size_t j1 = std::min(j0 + 1, ny - 1);
  const double u = fy - static_cast<double>(j0);
  const double a = v[j0 * nx + i0] + t * (v[j0 * nx + i1] - v[j0 * nx + i0]);
  const double b = v[j1 * nx + i0] + t * (v[j1 * nx + i1] - v[j1 * nx + i0]);
  return a + u * (b - a);
}

LonLatGrid lonlat_grid(double cell_deg, double lat_min, double lat_max, double fill) {
  if (!(cell_deg > 0) || !(lat_min < lat_max))
    throw Error(ExitCode::kInternal, "lonlat_grid: need cell > 0 and lat_min < lat_max");
  LonLatGrid g;
  g.nx = static_cast<std::size_t>(std::max(4.0, std::round(360.0 / cell_deg)));
  g.dlon = 360.0 / static_cast<double>(g.nx);
  g.lat0 = std::max(-90.0, lat_min);
  const double top = std::min(90.0, lat_max);
  g.ny = static_cast<std::size_t>(std::max(2.0, std::ceil((top - g.lat0) / cell_deg)));
  g.dlat = (top - g.lat0) / static_cast<double>(g.ny);
  g.v.assign(g.nx * g.ny, fill);
  return g;
}

double LonLatRaster::sample(LonLat p) const {
  const bool wraps = std::fabs(static_cast<double>(nx) * dx - 360.0) < 1e-6 * 360.0;
  double fx = (p.lon_deg - x0) / dx - 0.5;
  if (wraps) fx -= static_cast<double>(nx) * std::floor(fx / static_cast<double>(nx));
  else fx = std::clamp(fx, 0.0, static_cast<double>(nx - 1));
  const double fy = std::clamp((p.lat_deg - y0) / dy - 0.5, 0.0, static_cast<double>(ny - 1));
  const std::size_t i0 = std::min(static_cast<std::size_t>(fx), nx - 1);
  const std::size_t i1 = wraps ? (i0 + 1) % nx : std::min(i0 + 1, nx - 1);
  const std::size_t j0 = std::min(static_cast<std::size_t>(fy), ny - 1), j1 = std::min(j0 + 1, ny - 1);
  const double t = fx - static_cast<double>(i0), u = fy - static_cast<double>(j0);
  const double a = v[j0 * nx + i0] + t * (v[j0 * nx + i1] - v[j0 * nx + i0]);
  const double b = v[j1 * nx + i0] + t * (v[j1 * nx + i1] - v[j1 * nx + i0]);
  return a + u * (b - a);
}

LonLatRaster read_lonlat_raster(const std::string& path) {
  sizing::Grid g = read_raster_native(path, {0, 0});
  const double x1 = g.x0 + static_cast<double>(g.nx) * g.dx, y1 = g.y0 + static_cast<double>(g.ny) * g.dy;
  if (!(g.x0 >= -360.5 && x1 <= 360.5 && g.y0 >= -90.5 && y1 <= 90.5))
    throw Error(ExitCode::kCrsError, path + ": a global run needs a longitude/latitude raster (extent " + num6(g.x0) +
                                         ", " + num6(g.y0) + " - " + num6(x1) + ", " + num6(y1) + " is not in degrees)");
  LonLatRaster r;
  r.nx = g.nx;
  r.ny = g.ny;
  r.x0 = g.x0;
  r.y0 = g.y0;
  r.dx = g.dx;
  r.dy = g.dy;
  r.v = std::move(g.v);
  return r;
}

void distance_to_shore_sphere(LonLatGrid& g, const std::vector<Point3>& shore, double radius, double max_distance) {
  const std::vector<Point3> cv = cell_vectors(g);
  // Dot products below this are farther than max_distance: not offered on.
  const double min_dot = max_distance / radius < std::numbers::pi ? std::cos(max_distance / radius) : -2.0;
  std::vector<std::int64_t> src(g.v.size(), -1);
  std::vector<double> best(g.v.size(), -2.0);  // dot product with the source: larger is nearer
  for (std::size_t k = 0; k < shore.size(); ++k) {
    const LonLat ll = to_lonlat(shore[k]);
    const double fi = std::floor((ll.lon_deg + 180.0) / g.dlon), fj = std::floor((ll.lat_deg - g.lat0) / g.dlat);
    const auto i = static_cast<std::size_t>(std::clamp(fi, 0.0, static_cast<double>(g.nx - 1)));
    const auto j = static_cast<std::size_t>(std::clamp(fj, 0.0, static_cast<double>(g.ny - 1)));
    const std::size_t c = j * g.nx + i;
    const double d = dot(cv[c], shore[k]);
    if (d > best[c]) { best[c] = d; src[c] = static_cast<std::int64_t>(k); }
  }
  sweep_until_stable(g, [&](std::size_t c, std::size_t nb) {
    if (src[nb] < 0 || src[nb] == src[c]) return false;
    const double d = dot(cv[c], shore[static_cast<std::size_t>(src[nb])]);
    if (!(d > best[c]) || d < min_dot) return false;
    best[c] = d;
    src[c] = src[nb];
    return true;
  });
  for (std::size_t c = 0; c < g.v.size(); ++c) {
    if (src[c] < 0) { g.v[c] = kInf; continue; }
    g.v[c] = great_circle(cv[c], shore[static_cast<std::size_t>(src[c])], radius);
  }
}

bool lipschitz_on_grid(const LonLatGrid& g, const std::vector<Point3>& cv, double alpha, double radius) {
  const double ar = alpha * radius;
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i) {
      const std::size_t c = j * g.nx + i;
      const std::size_t right = j * g.nx + (i + 1) % g.nx;
      if (std::fabs(g.v[c] - g.v[right]) > ar * dist(cv[c], cv[right])) return false;
      if (j + 1 == g.ny) continue;
      for (const std::size_t up : {c + g.nx, (j + 1) * g.nx + (i + 1) % g.nx, (j + 1) * g.nx + (i + g.nx - 1) % g.nx})
        if (std::fabs(g.v[c] - g.v[up]) > ar * dist(cv[c], cv[up])) return false;
    }
  return true;
}

void limit_gradient_sphere(LonLatGrid& g, double alpha, double radius) {
  if (!(alpha >= 0) || !std::isfinite(alpha)) throw Error(ExitCode::kUsage, "gradation must be a finite number >= 0");
  const std::vector<Point3> cv = cell_vectors(g);
  // An alpha-Lipschitz grid (the distance rule alone, whose grade is below alpha) stays as it is.
  if (lipschitz_on_grid(g, cv, alpha, radius)) return;
  const std::vector<double> base = g.v;
  std::vector<std::size_t> src(g.v.size());
  for (std::size_t c = 0; c < src.size(); ++c) src[c] = c;
  const double ar = alpha * radius;
  sweep_until_stable(g, [&](std::size_t c, std::size_t nb) {
    const std::size_t s = src[nb];
    if (s == src[c] || !std::isfinite(base[s])) return false;
    const double cand = base[s] + ar * dist(cv[c], cv[s]);
    if (!(cand < g.v[c] * (1 - 1e-12))) return false;
    g.v[c] = cand;
    src[c] = s;
    return true;
  });
}

double default_cell_deg(double hmin) { return std::clamp(2 * hmin / (kEarthRadius * kDeg), 0.02, 0.5); }

LonLatGrid sphere_spacing(const SphereRules& r, double lat_min, const std::vector<Point3>& shore,
                          const LonLatRaster* elevation, std::string* describe) {
  if (!(r.hmin > 0) || !(r.hmax >= r.hmin))
    throw Error(ExitCode::kInvalidSpacing, "need 0 < --hmin <= --hmax (got hmin " + num6(r.hmin) + ", hmax " +
                                               num6(r.hmax) + ")");
  const double cell = r.cell_deg > 0 ? r.cell_deg : default_cell_deg(r.hmin);
  const bool any = r.dist_grade || r.slope || r.wavelength;
  const double grade = r.dist_grade.value_or(any ? -1.0 : 0.1);
  StepLaps lap(debug::Aid::kSizing, "sphere spacing");
  LonLatGrid g = lonlat_grid(cell, std::max(-90.0, lat_min - 2 * cell), 90.0, kInf);
  std::vector<std::string> names;
  if (grade >= 0) {
    // Beyond (hmax - hmin) / grade the rule gives hmax: the distance is not needed there.
    distance_to_shore_sphere(g, shore, kEarthRadius, grade > 0 ? (r.hmax - r.hmin) / grade + 2 * cell * 111195.0 : kInf);
    lap("distance");
    for (double& v : g.v) v = r.hmin + grade * v;
    names.push_back("hmin + " + num6(grade) + " * great-circle distance to shore");
  }
  if (elevation && (r.slope || r.wavelength)) {
    std::vector<double> depth(g.v.size());
    for (std::size_t j = 0; j < g.ny; ++j)
      for (std::size_t i = 0; i < g.nx; ++i) depth[j * g.nx + i] = -elevation->sample(g.centre(i, j));
    const double dphi = g.dlat * kDeg * kEarthRadius, dlam = g.dlon * kDeg * kEarthRadius;
    for (std::size_t j = 0; j < g.ny; ++j) {
      const double cphi = std::cos(g.centre(0, j).lat_deg * kDeg);
      for (std::size_t i = 0; i < g.nx; ++i) {
        const std::size_t c = j * g.nx + i;
        const double d = depth[c];
        if (!(d > 0)) continue;
        if (r.wavelength) g.v[c] = std::min(g.v[c], r.wave_period_s * std::sqrt(9.81 * d) / *r.wavelength);
        if (r.slope) {
          const double gx = first_diff(g, depth, i, j, true) / (dlam * cphi), gy = first_diff(g, depth, i, j, false) / dphi;
          const double gm = std::hypot(gx, gy);
          if (gm > 0) g.v[c] = std::min(g.v[c], 2.0 * std::numbers::pi / *r.slope * d / gm);
        }
      }
    }
    if (r.wavelength) names.push_back("wavelength " + num6(*r.wavelength));
    if (r.slope) names.push_back("slope " + num6(*r.slope));
  }
  for (double& v : g.v) v = std::isnan(v) ? r.hmax : std::clamp(v, r.hmin, r.hmax);
  lap("rules");
  limit_gradient_sphere(g, r.gradation);
  lap("limit");
  if (describe) {
    std::string s = "sphere grid " + std::to_string(g.nx) + "x" + std::to_string(g.ny) + " of " + num6(g.dlon) +
                    " deg: min(";
    for (std::size_t k = 0; k < names.size(); ++k) s += (k ? ", " : "") + names[k];
    *describe = s + ") clamped to [" + num6(r.hmin) + ", " + num6(r.hmax) + "] m, gradient-limited to " +
                num6(r.gradation) + " on the sphere, times the stereographic scale factor";
  }
  return g;
}

StereoSpacing::StereoSpacing(std::shared_ptr<const LonLatGrid> g, SphereStereo proj, double alpha, double rho_max,
                             double bound, std::string label)
    : g_(std::move(g)), proj_(proj), bound_(bound), alpha_(1.05 * alpha), label_(std::move(label)) {
  if (!(bound > 0)) throw Error(ExitCode::kUsage, "--bound must be positive");
  double hmax = 0;
  for (double v : g_->v) hmax = std::max(hmax, v);
  // d(k g)/dp = g grad k + k grad_p g; |grad k| = |p| / (2 R^2) and k |grad_p g| = |grad_sphere g|.
  lipschitz_ = 1.1 * (alpha + hmax * rho_max / (2.0 * proj_.radius() * proj_.radius()));
}

double StereoSpacing::operator()(Point2 p) const {
  const double r = proj_.radius();
  const double k = proj_.scale(p);
  auto plane = [&](double g) {
    const double t = std::tan(bound_ * g / r);
    return r / bound_ * 2.0 * t * k / (1.0 + std::sqrt(1.0 + t * t * k));
  };
  const double g = g_->sample(proj_.inverse(p));
  // The sphere circle's centre is not the image of c: it lies on the meridian through c, at
  // polar angle (theta(a + rho) + theta(a - rho)) / 2, farther out the larger the circle. g is
  // lowered by alpha times that offset for the largest circle accepted, so that B g bounds the
  // radius against the spacing at the true centre of every accepted circle.
  const double a = std::hypot(p.x, p.y), rho = bound_ * plane(g);
  const double mid = std::atan((a + rho) / (2 * r)) + std::atan((a - rho) / (2 * r));
  const double offset = r * std::fabs(mid - 2.0 * std::atan(a / (2 * r)));
  return plane(std::max(0.5 * g, g - alpha_ * offset));
}

}  // namespace fdr::gis
