// 3D gradient limiter by source propagation with exact Euclidean distances (26-neighbour
// octant sweeps).
#include "sizing/spacing3d_limiter.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>

#include "base/error.hpp"
#include "base/parallel.hpp"
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
  // cell takes offers from the 13 neighbours the sweep has already visited (the previous slab,
  // the previous row of its slab, the previous cell of its row). Each of the 26 directions is
  // upstream in some of the eight sweep orders, so a round that changes nothing has tried them all.
  void sweep(int sx, int sy, int sz) {
    for (std::int64_t kk = 0; kk < nz; ++kk) {
      const std::int64_t k = sz > 0 ? kk : nz - 1 - kk;
      for (std::int64_t jj = 0; jj < ny; ++jj) {
        const std::int64_t j = sy > 0 ? jj : ny - 1 - jj;
        for (std::int64_t ii = 0; ii < nx; ++ii) {
          const std::int64_t i = sx > 0 ? ii : nx - 1 - ii;
          const std::size_t c = static_cast<std::size_t>((k * ny + j) * nx + i);
          if (std::isnan(g.v[c])) continue;
          auto take = [&](std::int64_t di, std::int64_t dj, std::int64_t dk) {
            const std::int64_t a = i + di, b = j + dj, d = k + dk;
            if (a < 0 || b < 0 || d < 0 || a >= nx || b >= ny || d >= nz) return;
            offer(i, j, k, c, static_cast<std::size_t>((d * ny + b) * nx + a));
          };
          for (std::int64_t dj = -1; dj <= 1; ++dj)
            for (std::int64_t di = -1; di <= 1; ++di) take(di, dj, -sz);
          for (std::int64_t di = -1; di <= 1; ++di) take(di, -sy, 0);
          take(-sx, 0, 0);
        }
      }
    }
  }
};

// Whether an offer from a neighbour of cell (i, j, k), with every source still the cell itself,
// would lower it: the candidates and tests of Limiter3::offer, read-only.
bool first_offer_lowers(const Grid3& g, double alpha, std::int64_t i, std::int64_t j, std::int64_t k) {
  const auto nx = static_cast<std::int64_t>(g.nx), ny = static_cast<std::int64_t>(g.ny),
             nz = static_cast<std::int64_t>(g.nz);
  const double h = g.v[static_cast<std::size_t>((k * ny + j) * nx + i)];
  if (std::isnan(h)) return false;
  for (std::int64_t dk = -1; dk <= 1; ++dk)
    for (std::int64_t dj = -1; dj <= 1; ++dj)
      for (std::int64_t di = -1; di <= 1; ++di) {
        const std::int64_t a = i + di, b = j + dj, c = k + dk;
        if (a < 0 || b < 0 || c < 0 || a >= nx || b >= ny || c >= nz) continue;
        const double base = g.v[static_cast<std::size_t>((c * ny + b) * nx + a)];
        if (!(base < h)) continue;  // also NaN neighbours and the cell itself
        const double ex = g.dx * static_cast<double>(-di), ey = g.dy * static_cast<double>(-dj),
                     ez = g.dz * static_cast<double>(-dk);
        const double cand = base + alpha * std::sqrt(ex * ex + ey * ey + ez * ez);
        if (cand < h && (std::isinf(h) || h - cand > kRelTol * std::abs(h))) return true;
      }
  return false;
}

// Whether any cell would be lowered in the first round, checked in slabs of z on every thread;
// when none would, the sweeps would return the grid unchanged.
bool any_offer_lowers(const Grid3& g, double alpha) {
  std::vector<char> slab_hit(g.nz, 0);
  parallel_bands(g.nz, [&](std::size_t k0, std::size_t k1) {
    for (std::size_t k = k0; k < k1; ++k)
      for (std::size_t j = 0; j < g.ny && !slab_hit[k]; ++j)
        for (std::size_t i = 0; i < g.nx && !slab_hit[k]; ++i)
          if (first_offer_lowers(g, alpha, static_cast<std::int64_t>(i), static_cast<std::int64_t>(j),
                                 static_cast<std::int64_t>(k)))
            slab_hit[k] = 1;
  }, 4);
  return std::find(slab_hit.begin(), slab_hit.end(), 1) != slab_hit.end();
}

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
  if (g.v.empty() || !any_offer_lowers(g, alpha)) return;
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
