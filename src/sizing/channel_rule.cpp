// Channel (feature-size) rule on the distance-to-shore grid; see channel_rule.hpp.
#include "sizing/channel_rule.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "base/error.hpp"
#include "base/parallel.hpp"

namespace fdr::sizing {

std::vector<char> inside_mask(const Grid& like, const std::vector<std::pair<Point2, Point2>>& boundary) {
  std::vector<char> in(like.nx * like.ny, 0);
  if (like.nx == 0 || like.ny == 0) return in;
  // Crossings of every boundary segment with the row centre lines, bucketed by row.
  std::vector<std::vector<double>> xs(like.ny);
  for (const auto& [a, b] : boundary) {
    if (a.y == b.y) continue;
    const double ylo = std::min(a.y, b.y), yhi = std::max(a.y, b.y);
    // Rows whose centre y lies in [ylo, yhi) (half-open: a vertex on a row is counted once).
    const double j0 = std::ceil((ylo - like.y0) / like.dy - 0.5), j1 = std::ceil((yhi - like.y0) / like.dy - 0.5) - 1;
    for (double jd = std::max(j0, 0.0); jd <= std::min(j1, static_cast<double>(like.ny) - 1); jd += 1) {
      const std::size_t j = static_cast<std::size_t>(jd);
      const double y = like.y0 + (jd + 0.5) * like.dy;
      xs[j].push_back(a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y));
    }
  }
  for (std::size_t j = 0; j < like.ny; ++j) {
    auto& r = xs[j];
    std::sort(r.begin(), r.end());
    for (std::size_t k = 0; k + 1 < r.size(); k += 2) {
      const double i0 = std::ceil((r[k] - like.x0) / like.dx - 0.5), i1 = std::ceil((r[k + 1] - like.x0) / like.dx - 0.5) - 1;
      for (double id = std::max(i0, 0.0); id <= std::min(i1, static_cast<double>(like.nx) - 1); id += 1)
        in[j * like.nx + static_cast<std::size_t>(id)] = 1;
    }
  }
  return in;
}

Grid rule_channel(const Grid& dist, const std::vector<char>& water, double n_elements) {
  if (!(n_elements >= 1) || !std::isfinite(n_elements))
    throw Error(ExitCode::kUsage, "--channel-elements must be a number >= 1");
  if (water.size() != dist.nx * dist.ny) throw Error(ExitCode::kInternal, "rule_channel: mask of the wrong size");
  constexpr double kInf = std::numeric_limits<double>::infinity();
  Grid out;
  out.nx = dist.nx, out.ny = dist.ny, out.x0 = dist.x0, out.y0 = dist.y0, out.dx = dist.dx, out.dy = dist.dy;
  out.v.assign(dist.v.size(), kInf);
  const long nx = static_cast<long>(dist.nx), ny = static_cast<long>(dist.ny);
  auto d = [&](long i, long j) {
    if (i < 0 || j < 0 || i >= nx || j >= ny) return -kInf;  // outside the grid: no ridge test
    return dist.v[static_cast<std::size_t>(j * nx + i)];
  };
  static const int dirs[4][2] = {{1, 0}, {0, 1}, {1, 1}, {1, -1}};
  // Row bands on every thread (every cell is decided from `dist` alone).
  parallel_bands(dist.ny, [&](std::size_t j0, std::size_t j1) {
    for (long j = static_cast<long>(j0); j < static_cast<long>(j1); ++j)
      for (long i = 0; i < nx; ++i) {
        const std::size_t k = static_cast<std::size_t>(j * nx + i);
        if (!water[k]) continue;
        const double c = dist.v[k];
        if (!(c > 0) || !std::isfinite(c)) continue;
        bool ridge = false;
        for (const auto& dd : dirs) {
          const double p = d(i - dd[0], j - dd[1]), q = d(i + dd[0], j + dd[1]);
          if (p == -kInf || q == -kInf) continue;
          if (c >= p && c >= q && (c > p || c > q)) { ridge = true; break; }  // not along a plateau
        }
        if (ridge) out.v[k] = 2.0 * c / n_elements;
      }
  });
  return out;
}

}  // namespace fdr::sizing
