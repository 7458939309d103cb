// 3D gradient limiter by source propagation with exact Euclidean distances (26-neighbour
// octant sweeps).
#include "sizing/spacing3d_limiter.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <string>

#include "base/error.hpp"
#include "sizing/fields.hpp"

namespace fdr::sizing {

namespace {

// Where a cell's current value comes from: value = base + alpha * |cell - (si, sj, sk)|.
struct Source {
  double base;
  std::int32_t si, sj, sk;  // si < 0 marks a NaN cell
};

constexpr double kRelTol = 1e-12;

struct Limiter3 {
  Grid3& g;
  double alpha;
  std::vector<Source> src;
  std::int64_t nx, ny, nz;
  bool changed = false;

  // Offers the source of cell n to cell (i, j, k) at index c.
  void offer(std::int64_t i, std::int64_t j, std::int64_t k, std::size_t c, std::size_t n) {
    const Source s = src[n];
    double& h = g.v[c];
    if (s.si < 0 || !(s.base < h)) return;  // the candidate is at least base; also rejects NaN cells
    const double ex = g.dx * static_cast<double>(i - s.si), ey = g.dy * static_cast<double>(j - s.sj),
                 ez = g.dz * static_cast<double>(k - s.sk);
    const double cand = s.base + alpha * std::sqrt(ex * ex + ey * ey + ez * ez);
    if (cand < h && (std::isinf(h) || h - cand > kRelTol * std::abs(h))) {
      h = cand;
      src[c] = s;
      changed = true;
    }
  }

  // One raster sweep, each axis in the direction of its sign (+1 increasing, -1 decreasing); every
  // cell takes offers from all 26 neighbours.
  void sweep(int sx, int sy, int sz) {
    for (std::int64_t kk = 0; kk < nz; ++kk) {
      const std::int64_t k = sz > 0 ? kk : nz - 1 - kk;
      for (std::int64_t jj = 0; jj < ny; ++jj) {
        const std::int64_t j = sy > 0 ? jj : ny - 1 - jj;
        for (std::int64_t ii = 0; ii < nx; ++ii) {
          const std::int64_t i = sx > 0 ? ii : nx - 1 - ii;
          const std::size_t c = static_cast<std::size_t>((k * ny + j) * nx + i);
          if (std::isnan(g.v[c])) continue;
          for (std::int64_t dk = -1; dk <= 1; ++dk) {
            if (k + dk < 0 || k + dk >= nz) continue;
            for (std::int64_t dj = -1; dj <= 1; ++dj) {
              if (j + dj < 0 || j + dj >= ny) continue;
              for (std::int64_t di = -1; di <= 1; ++di) {
                if (i + di < 0 || i + di >= nx || (di == 0 && dj == 0 && dk == 0)) continue;
                offer(i, j, k, c, static_cast<std::size_t>(((k + dk) * ny + j + dj) * nx + i + di));
              }
            }
          }
        }
      }
    }
  }
};

}  // namespace

void limit_gradient3(Grid3& g, double alpha) {
  if (!std::isfinite(alpha) || !(alpha >= 0))
    throw Error(ExitCode::kUsage, "gradient limit: alpha must be a finite number >= 0, got " + format_number(alpha));
  if (g.v.size() != g.nx * g.ny * g.nz || !(g.dx > 0) || !(g.dy > 0) || !(g.dz > 0))
    throw Error(ExitCode::kInternal, "limit_gradient3: malformed grid (" + std::to_string(g.nx) + " x " +
                                         std::to_string(g.ny) + " x " + std::to_string(g.nz) + ", " +
                                         std::to_string(g.v.size()) + " values)");
  constexpr auto kMax = static_cast<std::size_t>(INT32_MAX);
  if (g.nx > kMax || g.ny > kMax || g.nz > kMax) throw Error(ExitCode::kInternal, "limit_gradient3: grid too large");
  if (g.v.empty()) return;
  Limiter3 L{g, alpha, std::vector<Source>(g.v.size()), static_cast<std::int64_t>(g.nx),
             static_cast<std::int64_t>(g.ny), static_cast<std::int64_t>(g.nz)};
  for (std::size_t k = 0; k < g.nz; ++k)
    for (std::size_t j = 0; j < g.ny; ++j)
      for (std::size_t i = 0; i < g.nx; ++i) {
        const double v = g.at(i, j, k);
        L.src[g.index(i, j, k)] = std::isnan(v) ? Source{v, -1, -1, -1}
                                                : Source{v, static_cast<std::int32_t>(i), static_cast<std::int32_t>(j),
                                                         static_cast<std::int32_t>(k)};
      }
  // Why rounds: a source can reach a cell only through neighbours holding other sources, or around
  // NaN holes, which one sweep per octant may not finish. Cap (documented): a shortest path around
  // NaN holes bends at most once per round, so nx + ny + nz + 64 rounds cover any grid.
  const std::size_t max_rounds = g.nx + g.ny + g.nz + 64;
  static constexpr std::array<std::array<int, 3>, 8> kOrders = {
      {{1, 1, 1}, {-1, -1, -1}, {-1, 1, 1}, {1, -1, -1}, {1, -1, 1}, {-1, 1, -1}, {1, 1, -1}, {-1, -1, 1}}};
  for (std::size_t round = 0;; ++round) {
    if (round >= max_rounds)
      throw Error(ExitCode::kWorkLimit, "3D gradient limiting did not settle after " + std::to_string(max_rounds) +
                                            " rounds (nodata pattern too convoluted); fill nodata or coarsen the grid");
    L.changed = false;
    for (const auto& o : kOrders) L.sweep(o[0], o[1], o[2]);
    if (!L.changed) return;
  }
}

}  // namespace fdr::sizing
