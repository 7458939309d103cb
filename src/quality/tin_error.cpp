// The TIN's vertical error against the DEM.
#include "quality/tin_error.hpp"
#include <algorithm>
#include <cmath>

namespace fdr::quality {

// Vertical error of the linear TIN against the DEM grid: every cell centre inside a triangle is
// compared with the plane through the triangle's three vertex elevations.
std::pair<double, double> tin_vertical_error(const mesh::MeshView& m, const sizing::Grid& dem) {
  double max_err = 0, sum2 = 0;
  std::size_t n = 0;
  for (const auto& t : m.triangles) {
    const Point2 a = m.vertices[t[0]], b = m.vertices[t[1]], c = m.vertices[t[2]];
    const double za = m.z[t[0]], zb = m.z[t[1]], zc = m.z[t[2]];
    const double det = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    if (!(det > 0)) continue;
    const double xmin = std::min({a.x, b.x, c.x}), xmax = std::max({a.x, b.x, c.x});
    const double ymin = std::min({a.y, b.y, c.y}), ymax = std::max({a.y, b.y, c.y});
    const long i0 = std::max(0L, static_cast<long>(std::ceil((xmin - dem.x0) / dem.dx - 0.5)));
    const long i1 = std::min(static_cast<long>(dem.nx) - 1, static_cast<long>(std::floor((xmax - dem.x0) / dem.dx - 0.5)));
    const long j0 = std::max(0L, static_cast<long>(std::ceil((ymin - dem.y0) / dem.dy - 0.5)));
    const long j1 = std::min(static_cast<long>(dem.ny) - 1, static_cast<long>(std::floor((ymax - dem.y0) / dem.dy - 0.5)));
    for (long j = j0; j <= j1; ++j)
      for (long i = i0; i <= i1; ++i) {
        const Point2 p = dem.center(static_cast<std::size_t>(i), static_cast<std::size_t>(j));
        const double l1 = ((b.x - p.x) * (c.y - p.y) - (b.y - p.y) * (c.x - p.x)) / det;
        const double l2 = ((c.x - p.x) * (a.y - p.y) - (c.y - p.y) * (a.x - p.x)) / det;
        const double l3 = 1 - l1 - l2;
        if (l1 < 0 || l2 < 0 || l3 < 0) continue;
        const double zd = dem.at(static_cast<std::size_t>(i), static_cast<std::size_t>(j));
        if (!std::isfinite(zd)) continue;
        const double e = std::fabs(l1 * za + l2 * zb + l3 * zc - zd);
        max_err = std::max(max_err, e);
        sum2 += e * e;
        ++n;
      }
  }
  return {max_err, n ? std::sqrt(sum2 / static_cast<double>(n)) : 0.0};
}

}  // namespace fdr::quality
