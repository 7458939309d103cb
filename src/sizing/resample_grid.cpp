// Grids resampled onto the spacing grid's cells for the spacing rules (see resample_grid.hpp).
#include "sizing/resample_grid.hpp"
#include <algorithm>
#include <cmath>
#include <limits>
#include "sizing/raster_rules.hpp"
#include "base/parallel.hpp"

namespace fdr::sizing {

// `g` resampled onto the cells of `like` (bilinear between cell centres, clamped to their hull as
// GridField does). A non-finite corner with a non-zero weight is passed through (NaN before +inf),
// so nodata and "no constraint" areas are not smeared into finite values.
Grid resample_like(const Grid& g, const Grid& like) {
  if (g.nx == like.nx && g.ny == like.ny && g.x0 == like.x0 && g.y0 == like.y0 && g.dx == like.dx && g.dy == like.dy)
    return g;
  Grid r = like;
  parallel_bands(r.ny, [&](std::size_t j0, std::size_t j1) {
  for (std::size_t j = j0; j < j1; ++j)
    for (std::size_t i = 0; i < r.nx; ++i) {
      const Point2 p = r.center(i, j);
      const double u = std::clamp((p.x - g.x0) / g.dx - 0.5, 0.0, static_cast<double>(g.nx - 1));
      const double w = std::clamp((p.y - g.y0) / g.dy - 0.5, 0.0, static_cast<double>(g.ny - 1));
      std::size_t i0 = static_cast<std::size_t>(u), j0 = static_cast<std::size_t>(w);
      if (i0 + 1 >= g.nx) i0 = g.nx >= 2 ? g.nx - 2 : 0;
      if (j0 + 1 >= g.ny) j0 = g.ny >= 2 ? g.ny - 2 : 0;
      const double s = u - static_cast<double>(i0), t = w - static_cast<double>(j0);
      const std::size_t i1 = std::min(i0 + 1, g.nx - 1), j1 = std::min(j0 + 1, g.ny - 1);
      const double c[4] = {g.at(i0, j0), g.at(i1, j0), g.at(i0, j1), g.at(i1, j1)};
      const double wt[4] = {(1 - s) * (1 - t), s * (1 - t), (1 - s) * t, s * t};
      double v = 0;
      bool nan = false, inf = false;
      for (int k = 0; k < 4; ++k) {
        if (wt[k] == 0) continue;
        if (std::isnan(c[k])) nan = true;
        else if (std::isinf(c[k])) inf = true;
        else v += wt[k] * c[k];
      }
      r.at(i, j) = nan ? std::numeric_limits<double>::quiet_NaN() : inf ? std::numeric_limits<double>::infinity() : v;
    }
  });
  return r;
}

Grid size_raster_rule(Grid s, const Grid& like) {
  if (s.nx != like.nx || s.ny != like.ny) {
    // Resample onto `like` through a field (both grids cover the same box).
    Grid r = like;
    Grid filled = fill_nan(s, std::numeric_limits<double>::infinity());
    for (auto& v : filled.v) if (!(v > 0)) v = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < r.ny; ++j)
      for (std::size_t i = 0; i < r.nx; ++i) {
        const Point2 p = r.center(i, j);
        const long ii = std::clamp(static_cast<long>((p.x - s.x0) / s.dx), 0L, static_cast<long>(s.nx) - 1);
        const long jj = std::clamp(static_cast<long>((p.y - s.y0) / s.dy), 0L, static_cast<long>(s.ny) - 1);
        r.at(i, j) = filled.at(static_cast<std::size_t>(ii), static_cast<std::size_t>(jj));
      }
    s = std::move(r);
  }
  for (auto& v : s.v) if (!(v > 0) || !std::isfinite(v)) v = std::numeric_limits<double>::infinity();
  return s;
}

}  // namespace fdr::sizing
