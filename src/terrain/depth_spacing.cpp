// Depth-graded terrain spacing on a 3D grid (depth_spacing.hpp).
#include "terrain/depth_spacing.hpp"
#include <algorithm>
#include <cmath>
#include "base/error.hpp"
#include "sizing/spacing3d_limiter.hpp"
#include "terrain/wells.hpp"

namespace fdr::terrain {

sizing::Grid3 spacing_grid_geometry(const Box3& box, double max_cells, double min_cell) {
  const double wx = box.hi.x - box.lo.x, wy = box.hi.y - box.lo.y, wz = box.hi.z - box.lo.z;
  if (!(wx > 0 && wy > 0 && wz > 0 && max_cells >= 64))
    throw Error(ExitCode::kInternal, "terrain spacing grid: empty box or too few cells");
  // Columns of 8 cells at least: the xy cell takes the rest of the budget.
  double cell = std::sqrt(wx * wy * 8.0 / max_cells);
  cell = std::max({cell, std::cbrt(wx * wy * wz / max_cells), min_cell});
  sizing::Grid3 g;
  g.dx = g.dy = cell;
  g.dz = std::min(cell, wz / 8.0);
  g.nx = static_cast<std::size_t>(std::ceil(wx / g.dx)) + 1;
  g.ny = static_cast<std::size_t>(std::ceil(wy / g.dy)) + 1;
  g.nz = static_cast<std::size_t>(std::ceil(wz / g.dz)) + 1;
  // Half a cell of margin on every side, so cell centres straddle the box.
  g.x0 = box.lo.x - 0.5 * g.dx;
  g.y0 = box.lo.y - 0.5 * g.dy;
  g.z0 = box.lo.z - 0.5 * g.dz;
  return g;
}

std::vector<Point2> column_centres(const sizing::Grid3& g) {
  std::vector<Point2> c;
  c.reserve(g.nx * g.ny);
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i) {
      const Point3 p = g.center(i, j, 0);
      c.push_back({p.x, p.y});
    }
  return c;
}

void fill_depth_spacing(sizing::Grid3& g, const std::vector<double>& h2, const std::vector<double>& top,
                        const DepthSpacing& opt) {
  if (!(opt.hmin > 0) || !(opt.hmax >= opt.hmin) || !std::isfinite(opt.hmax))
    throw Error(ExitCode::kUsage, "terrain spacing: need 0 < hmin <= hmax");
  if (!(opt.grade >= 0) || !std::isfinite(opt.grade)) throw Error(ExitCode::kUsage, "terrain spacing: the depth grade must be >= 0");
  const std::size_t cols = g.nx * g.ny;
  if (h2.size() != cols || top.size() != cols) throw Error(ExitCode::kInternal, "terrain spacing: one value per column expected");
  g.v.assign(cols * g.nz, 0.0);
  for (std::size_t k = 0; k < g.nz; ++k)
    for (std::size_t c = 0; c < cols; ++c) {
      const double z = g.z0 + (static_cast<double>(k) + 0.5) * g.dz;
      const double depth = std::max(0.0, top[c] - z);
      double h = h2[c] + opt.grade * depth;
      if (!std::isfinite(h)) h = opt.hmax;  // a column off the DEM and the 2D spacing: no constraint
      g.v[k * cols + c] = std::clamp(h, opt.hmin, opt.hmax);
    }
  if (!opt.near_segments.empty()) cap_near_segments(g, opt.near_segments, opt.near_h);
  // The limiter bounds differences between neighbouring cells; the trilinear interpolant's gradient
  // has one such bound per axis, so limiting by alpha / sqrt(3) makes the field alpha-Lipschitz.
  sizing::limit_gradient3(g, opt.alpha / std::sqrt(3.0));
}

}  // namespace fdr::terrain
