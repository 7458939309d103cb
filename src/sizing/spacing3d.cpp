// The constant and the trilinear grid spacing in 3D.
#include "sizing/spacing3d.hpp"

#include <algorithm>
#include <cmath>

#include "base/error.hpp"
#include "sizing/fields.hpp"

namespace fdr::sizing {

ConstantField3::ConstantField3(double h) : h_(h) {
  if (!(h > 0) || !std::isfinite(h))
    throw Error(ExitCode::kInvalidSpacing, "spacing must be a positive finite number, got " + format_number(h));
}

std::string ConstantField3::describe() const { return "constant " + format_number(h_); }

namespace {

void validate(const Grid3& g, const std::string& label) {
  if (g.nx == 0 || g.ny == 0 || g.nz == 0 || g.v.size() != g.nx * g.ny * g.nz)
    throw Error(ExitCode::kInvalidSpacing, "spacing " + label + ": empty grid or value count " +
                                               std::to_string(g.v.size()) + " != " + std::to_string(g.nx) + " x " +
                                               std::to_string(g.ny) + " x " + std::to_string(g.nz));
  for (double d : {g.dx, g.dy, g.dz})
    if (!(d > 0) || !std::isfinite(d))
      throw Error(ExitCode::kInvalidSpacing, "spacing " + label + ": cell size must be positive, got dx = " +
                                                 format_number(g.dx) + ", dy = " + format_number(g.dy) +
                                                 ", dz = " + format_number(g.dz));
  for (std::size_t k = 0; k < g.nz; ++k)
    for (std::size_t j = 0; j < g.ny; ++j)
      for (std::size_t i = 0; i < g.nx; ++i) {
        const double v = g.at(i, j, k);
        if (v > 0 && std::isfinite(v)) continue;
        const Point3 c = g.center(i, j, k);
        throw Error(ExitCode::kInvalidSpacing,
                    "spacing " + label + ": cell (" + std::to_string(i) + ", " + std::to_string(j) + ", " +
                        std::to_string(k) + ") at (" + format_number(c.x) + ", " + format_number(c.y) + ", " +
                        format_number(c.z) + ") is " +
                        (std::isnan(v) ? std::string("NaN (no data)") : format_number(v)) +
                        ", not a positive finite number");
      }
}

// Largest |difference| over the four edges of cell (i, j, k) along axis 0 (x), 1 (y) or 2 (z).
double max_edge_difference(const Grid3& g, std::size_t i, std::size_t j, std::size_t k, int axis) {
  const std::size_t i1 = std::min(i + 1, g.nx - 1), j1 = std::min(j + 1, g.ny - 1), k1 = std::min(k + 1, g.nz - 1);
  double m = 0;
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) {
      double lo, hi;
      if (axis == 0) {
        lo = g.at(i, a ? j1 : j, b ? k1 : k), hi = g.at(i1, a ? j1 : j, b ? k1 : k);
      } else if (axis == 1) {
        lo = g.at(a ? i1 : i, j, b ? k1 : k), hi = g.at(a ? i1 : i, j1, b ? k1 : k);
      } else {
        lo = g.at(a ? i1 : i, b ? j1 : j, k), hi = g.at(a ? i1 : i, b ? j1 : j, k1);
      }
      m = std::max(m, std::abs(hi - lo));
    }
  return m;
}

// Continuous cell-centre index along one axis, clamped to the centres; returns the lower node and
// sets the weight of the upper one.
std::size_t locate(double p, double origin, double d, std::size_t n, double& t) {
  const double u = std::clamp((p - origin) / d - 0.5, 0.0, static_cast<double>(n - 1));
  std::size_t i = static_cast<std::size_t>(u);
  if (i + 1 >= n) i = n >= 2 ? n - 2 : 0;
  t = u - static_cast<double>(i);
  return i;
}

}  // namespace

GridField3::GridField3(Grid3 g, std::string label) : g_(std::move(g)), label_(std::move(label)) {
  validate(g_, label_);
  double l2 = 0;
  for (std::size_t k = 0; k < g_.nz; ++k)
    for (std::size_t j = 0; j < g_.ny; ++j)
      for (std::size_t i = 0; i < g_.nx; ++i) {
        const double ax = max_edge_difference(g_, i, j, k, 0) / g_.dx;
        const double ay = max_edge_difference(g_, i, j, k, 1) / g_.dy;
        const double az = max_edge_difference(g_, i, j, k, 2) / g_.dz;
        l2 = std::max(l2, ax * ax + ay * ay + az * az);
      }
  lipschitz_ = std::sqrt(l2);
  max_ = *std::max_element(g_.v.begin(), g_.v.end());
}

double GridField3::operator()(Point3 p) const {
  if (std::isnan(p.x) || std::isnan(p.y) || std::isnan(p.z)) return std::numeric_limits<double>::quiet_NaN();
  double s, t, u;
  const std::size_t i = locate(p.x, g_.x0, g_.dx, g_.nx, s);
  const std::size_t j = locate(p.y, g_.y0, g_.dy, g_.ny, t);
  const std::size_t k = locate(p.z, g_.z0, g_.dz, g_.nz, u);
  const std::size_t i1 = std::min(i + 1, g_.nx - 1), j1 = std::min(j + 1, g_.ny - 1), k1 = std::min(k + 1, g_.nz - 1);
  auto lerp = [](double a, double b, double w) { return a + w * (b - a); };
  const double c00 = lerp(g_.at(i, j, k), g_.at(i1, j, k), s);
  const double c10 = lerp(g_.at(i, j1, k), g_.at(i1, j1, k), s);
  const double c01 = lerp(g_.at(i, j, k1), g_.at(i1, j, k1), s);
  const double c11 = lerp(g_.at(i, j1, k1), g_.at(i1, j1, k1), s);
  return lerp(lerp(c00, c10, t), lerp(c01, c11, t), u);
}

std::string GridField3::describe() const {
  return label_ + " " + std::to_string(g_.nx) + "x" + std::to_string(g_.ny) + "x" + std::to_string(g_.nz) +
         " cells of " + format_number(g_.dx) + " x " + format_number(g_.dy) + " x " + format_number(g_.dz);
}

}  // namespace fdr::sizing
