// Gradient limiter by source propagation with exact Euclidean distances (8-neighbour
// raster sweeps, in the spirit of Danielsson's vector distance transform).
#include "sizing/gradient_limiter.hpp"

#include <cmath>
#include <cstdint>
#include <string>

#include "base/error.hpp"
#include "sizing/fields.hpp"

namespace fdr::sizing {

namespace {

// Where a cell's current value comes from: value = base + alpha * |cell - (si, sj)|.
struct Source {
  double base;
  std::int32_t si, sj;  // si < 0 marks a NaN cell
};

constexpr double kRelTol = 1e-12;

struct Limiter {
  Grid& g;
  double alpha;
  std::vector<Source> src;
  std::int64_t nx, ny;
  bool changed = false;

  // Offers neighbour k's source to cell (i, j) at index c.
  inline void offer(std::int64_t i, std::int64_t j, std::size_t c, std::size_t k) {
    const Source s = src[k];
    double& h = g.v[c];
    // Cheap rejection first: the candidate is at least the source's base value.
    if (s.si < 0 || !(s.base < h)) return;  // also rejects NaN cells (h NaN)
    const double ex = g.dx * static_cast<double>(i - s.si), ey = g.dy * static_cast<double>(j - s.sj);
    const double cand = s.base + alpha * std::sqrt(ex * ex + ey * ey);
    if (cand < h && (std::isinf(h) || h - cand > kRelTol * std::abs(h))) {
      h = cand;
      src[c] = s;
      changed = true;
    }
  }

  // Knight move from k to c: the straight line crosses cells m1 and m2, so both must hold
  // data, otherwise a one-cell NaN wall would be jumped.
  inline void offer_knight(std::int64_t i, std::int64_t j, std::size_t c, std::size_t k, std::size_t m1,
                           std::size_t m2) {
    if (!(src[k].base < g.v[c]) || std::isnan(g.v[m1]) || std::isnan(g.v[m2])) return;
    offer(i, j, c, k);
  }

  // Rows from bottom to top; in each row a left-to-right pass takes W, SW, S, SE, then a
  // right-to-left pass takes E, so values flow upward along any direction.
  void forward() {
    for (std::int64_t j = 0; j < ny; ++j) {
      const std::size_t row = static_cast<std::size_t>(j * nx);
      for (std::int64_t i = 0; i < nx; ++i) {
        const std::size_t c = row + static_cast<std::size_t>(i);
        if (i > 0) offer(i, j, c, c - 1);
        if (j > 0) {
          const std::size_t b = c - static_cast<std::size_t>(nx);
          if (i > 0) offer(i, j, c, b - 1);
          offer(i, j, c, b);
          if (i + 1 < nx) offer(i, j, c, b + 1);
          // Knight moves: relay sources whose line to this cell passes between two
          // 8-neighbours that hold other sources (matters for anisotropic cells).
          if (i > 1) offer_knight(i, j, c, b - 2, b - 1, c - 1);
          if (i + 2 < nx) offer_knight(i, j, c, b + 2, b + 1, c + 1);
          if (j > 1) {
            const std::size_t bb = b - static_cast<std::size_t>(nx);
            if (i > 0) offer_knight(i, j, c, bb - 1, bb, b - 1);
            if (i + 1 < nx) offer_knight(i, j, c, bb + 1, bb, b + 1);
          }
        }
      }
      for (std::int64_t i = nx - 2; i >= 0; --i) {
        const std::size_t c = row + static_cast<std::size_t>(i);
        offer(i, j, c, c + 1);
      }
    }
  }

  // Mirror image: rows from top to bottom, E, NE, N, NW right-to-left, then W left-to-right.
  void backward() {
    for (std::int64_t j = ny - 1; j >= 0; --j) {
      const std::size_t row = static_cast<std::size_t>(j * nx);
      for (std::int64_t i = nx - 1; i >= 0; --i) {
        const std::size_t c = row + static_cast<std::size_t>(i);
        if (i + 1 < nx) offer(i, j, c, c + 1);
        if (j + 1 < ny) {
          const std::size_t a = c + static_cast<std::size_t>(nx);
          if (i + 1 < nx) offer(i, j, c, a + 1);
          offer(i, j, c, a);
          if (i > 0) offer(i, j, c, a - 1);
          if (i + 2 < nx) offer_knight(i, j, c, a + 2, a + 1, c + 1);
          if (i > 1) offer_knight(i, j, c, a - 2, a - 1, c - 1);
          if (j + 2 < ny) {
            const std::size_t aa = a + static_cast<std::size_t>(nx);
            if (i + 1 < nx) offer_knight(i, j, c, aa + 1, aa, a + 1);
            if (i > 0) offer_knight(i, j, c, aa - 1, aa, a - 1);
          }
        }
      }
      for (std::int64_t i = 1; i < nx; ++i) {
        const std::size_t c = row + static_cast<std::size_t>(i);
        offer(i, j, c, c - 1);
      }
    }
  }
};

}  // namespace

void limit_gradient(Grid& g, double alpha) {
  if (!std::isfinite(alpha) || !(alpha >= 0))
    throw Error(ExitCode::kUsage, "gradient limit: alpha must be a finite number >= 0, got " + format_number(alpha));
  if (g.v.size() != g.nx * g.ny || !(g.dx > 0) || !(g.dy > 0))
    throw Error(ExitCode::kInternal, "limit_gradient: malformed grid (" + std::to_string(g.nx) + " x " +
                                         std::to_string(g.ny) + ", " + std::to_string(g.v.size()) + " values)");
  if (g.nx > static_cast<std::size_t>(INT32_MAX) || g.ny > static_cast<std::size_t>(INT32_MAX))
    throw Error(ExitCode::kInternal, "limit_gradient: grid too large");
  if (g.v.empty()) return;
  Limiter L{g, alpha, std::vector<Source>(g.v.size()), static_cast<std::int64_t>(g.nx), static_cast<std::int64_t>(g.ny)};
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i) {
      const double v = g.at(i, j);
      L.src[j * g.nx + i] = std::isnan(v) ? Source{v, -1, -1}
                                          : Source{v, static_cast<std::int32_t>(i), static_cast<std::int32_t>(j)};
    }
  // Why repeat: source propagation can need another sweep pair where the nearest source
  // reaches a cell only through neighbours that hold a different source, or around NaN holes.
  // Cap (documented): a shortest path around NaN holes can bend at most once per sweep pair, so
  // nx + ny + 64 sweep pairs cover any grid; reaching it means a bug or a pathological nodata maze.
  const std::size_t max_sweeps = g.nx + g.ny + 64;
  std::size_t sweeps = 0;
  do {
    if (++sweeps > max_sweeps)
      throw Error(ExitCode::kWorkLimit, "gradient limiting did not settle after " + std::to_string(max_sweeps) +
                                            " sweeps (nodata pattern too convoluted); fill nodata or coarsen the grid");
    L.changed = false;
    L.forward();
    L.backward();
  } while (L.changed);
}

}  // namespace fdr::sizing
