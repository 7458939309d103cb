// GridField: bilinear spacing over a raster, validated at construction.
#include "sizing/grid_field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "base/error.hpp"
#include "sizing/fields.hpp"

namespace fdr::sizing {

GridField::GridField(Grid g, std::string label) : g_(std::move(g)), label_(std::move(label)) {
  if (g_.nx == 0 || g_.ny == 0 || g_.v.size() != g_.nx * g_.ny)
    throw Error(ExitCode::kInvalidSpacing, "spacing " + label_ + ": empty grid or value count " +
                                               std::to_string(g_.v.size()) + " != " + std::to_string(g_.nx) +
                                               " x " + std::to_string(g_.ny));
  if (!(g_.dx > 0) || !(g_.dy > 0) || !std::isfinite(g_.dx) || !std::isfinite(g_.dy))
    throw Error(ExitCode::kInvalidSpacing, "spacing " + label_ + ": cell size must be positive, got dx = " +
                                               format_number(g_.dx) + ", dy = " + format_number(g_.dy));
  for (std::size_t j = 0; j < g_.ny; ++j)
    for (std::size_t i = 0; i < g_.nx; ++i) {
      const double v = g_.at(i, j);
      if (!(v > 0) || !std::isfinite(v)) {
        const Point2 c = g_.center(i, j);
        throw Error(ExitCode::kInvalidSpacing,
                    "spacing " + label_ + ": cell (" + std::to_string(i) + ", " + std::to_string(j) + ") at (" +
                        format_number(c.x) + ", " + format_number(c.y) + ") is " +
                        (std::isnan(v) ? std::string("NaN (no data)") : format_number(v)) +
                        ", not a positive finite number");
      }
    }
  // Why per cell: the bilinear gradient on a cell is bounded by its edge differences.
  double l2 = 0;
  for (std::size_t j = 0; j < g_.ny; ++j)
    for (std::size_t i = 0; i < g_.nx; ++i) {
      const std::size_t i1 = std::min(i + 1, g_.nx - 1), j1 = std::min(j + 1, g_.ny - 1);
      const double ax = std::max(std::abs(g_.at(i1, j) - g_.at(i, j)), std::abs(g_.at(i1, j1) - g_.at(i, j1))) / g_.dx;
      const double ay = std::max(std::abs(g_.at(i, j1) - g_.at(i, j)), std::abs(g_.at(i1, j1) - g_.at(i1, j))) / g_.dy;
      l2 = std::max(l2, ax * ax + ay * ay);
    }
  lipschitz_ = std::sqrt(l2);
  max_ = *std::max_element(g_.v.begin(), g_.v.end());
}

double GridField::operator()(Point2 p) const {
  // Continuous index with 0 at the first cell centre, clamped to the centres' hull.
  const double u = std::clamp((p.x - g_.x0) / g_.dx - 0.5, 0.0, static_cast<double>(g_.nx - 1));
  const double w = std::clamp((p.y - g_.y0) / g_.dy - 0.5, 0.0, static_cast<double>(g_.ny - 1));
  if (std::isnan(u) || std::isnan(w)) return std::numeric_limits<double>::quiet_NaN();
  std::size_t i = static_cast<std::size_t>(u), j = static_cast<std::size_t>(w);
  if (i + 1 >= g_.nx) i = g_.nx >= 2 ? g_.nx - 2 : 0;
  if (j + 1 >= g_.ny) j = g_.ny >= 2 ? g_.ny - 2 : 0;
  const double s = u - static_cast<double>(i), t = w - static_cast<double>(j);
  const std::size_t i1 = std::min(i + 1, g_.nx - 1), j1 = std::min(j + 1, g_.ny - 1);
  const double a = g_.at(i, j) + s * (g_.at(i1, j) - g_.at(i, j));
  const double b = g_.at(i, j1) + s * (g_.at(i1, j1) - g_.at(i, j1));
  return a + t * (b - a);
}

std::string GridField::describe() const {
  return label_ + " " + std::to_string(g_.nx) + "x" + std::to_string(g_.ny) + " cells of " + format_number(g_.dx) +
         " x " + format_number(g_.dy);
}

}  // namespace fdr::sizing
