// Gradient limiter by source propagation with exact Euclidean distances (8-neighbour
// raster sweeps, in the spirit of Danielsson's vector distance transform).
#include "sizing/gradient_limiter.hpp"

#include <cmath>
#include <algorithm>
#include <cstdint>
#include <string>

#include "base/error.hpp"
#include "sizing/fields.hpp"
#include "base/parallel.hpp"

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
  std::vector<Source>& src;
  std::int64_t nx, ny;
  bool changed = false;
  // Row skipping: a row's offers read only its own row and the two rows before it in the sweep's
  // direction, so when none of those changed since the row was last swept in that direction,
  // sweeping it again cannot change it (skipping it gives the same bits as sweeping it).
  // Ticks count processed rows (0 = never).
  std::vector<std::uint64_t> last_change = std::vector<std::uint64_t>(static_cast<std::size_t>(ny), 0);
  std::vector<std::uint64_t> last_fwd = std::vector<std::uint64_t>(static_cast<std::size_t>(ny), 0);
  std::vector<std::uint64_t> last_bwd = std::vector<std::uint64_t>(static_cast<std::size_t>(ny), 0);
  std::uint64_t tick = 0;
  bool row_dirty = false;

  // Whether row j must be swept (rows j, j - step, j - 2 step are its inputs); if so starts it.
  bool begin_row(std::int64_t j, int step, std::vector<std::uint64_t>& last) {
    const auto r = static_cast<std::size_t>(j);
    const std::uint64_t since = last[r];
    bool need = since == 0 || last_change[r] >= since;
    for (int k = 1; k <= 2 && !need; ++k) {
      const std::int64_t jj = j - k * step;
      if (jj >= 0 && jj < ny) need = last_change[static_cast<std::size_t>(jj)] >= since;
    }
    if (!need) return false;
    last[r] = ++tick;
    row_dirty = false;
    return true;
  }
  void end_row(std::int64_t j) {
    if (row_dirty) {
      last_change[static_cast<std::size_t>(j)] = tick;
      changed = true;
    }
  }

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
      row_dirty = true;
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
  void forward(std::int64_t j0, std::int64_t j1) {
    for (std::int64_t j = j0; j < j1; ++j) {
      if (!begin_row(j, 1, last_fwd)) continue;
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
      end_row(j);
    }
  }

  // Mirror image: rows from top to bottom, E, NE, N, NW right-to-left, then W left-to-right.
  void backward(std::int64_t j0, std::int64_t j1) {
    for (std::int64_t j = j1 - 1; j >= j0; --j) {
      if (!begin_row(j, -1, last_bwd)) continue;
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
      end_row(j);
    }
  }
};

// Per row: whether any offer of the first sweep pair (sources = the cells themselves) would change
// a cell of the row: the same candidates and tests as Limiter::offer / offer_knight, over all 8
// neighbours and the 8 knight moves (with the two cells the code requires to hold data), without
// writing anything. Returns whether any row has one.
bool rows_with_changes(const Grid& g, double alpha, std::vector<char>& row_flag) {
  struct Dir {
    int di, dj;       // the neighbour k relative to c
    bool knight;
    int m1i, m1j, m2i, m2j;  // cells that must hold data for a knight move
  };
  static constexpr Dir dirs[16] = {
      {-1, 0, false, 0, 0, 0, 0},  {1, 0, false, 0, 0, 0, 0},   {-1, -1, false, 0, 0, 0, 0}, {0, -1, false, 0, 0, 0, 0},
      {1, -1, false, 0, 0, 0, 0},  {-1, 1, false, 0, 0, 0, 0},  {0, 1, false, 0, 0, 0, 0},   {1, 1, false, 0, 0, 0, 0},
      {-2, -1, true, -1, -1, -1, 0}, {2, -1, true, 1, -1, 1, 0}, {-1, -2, true, 0, -2, -1, -1}, {1, -2, true, 0, -2, 1, -1},
      {2, 1, true, 1, 1, 1, 0},    {-2, 1, true, -1, 1, -1, 0}, {1, 2, true, 0, 2, 1, 1},     {-1, 2, true, 0, 2, -1, 1}};
  double w[16];
  for (int d = 0; d < 16; ++d) {
    // As Limiter::offer computes it: ex = dx * (i - si), ey = dy * (j - sj).
    const double ex = g.dx * static_cast<double>(-dirs[d].di), ey = g.dy * static_cast<double>(-dirs[d].dj);
    w[d] = alpha * std::sqrt(ex * ex + ey * ey);
  }
  const auto nx = static_cast<std::int64_t>(g.nx), ny = static_cast<std::int64_t>(g.ny);
  row_flag.assign(g.ny, 0);
  parallel_bands(g.ny, [&](std::size_t j0, std::size_t j1) {
    // Quick pass: when every pair of cells one offer apart differs by at most 0.999 of the rise
    // alpha |c - k| (a margin far above rounding), no offer can change anything either way.
    // NaN fails the comparison and sends the band to the exact pass.
    bool margin = alpha > 0;
    for (std::int64_t j = static_cast<std::int64_t>(j0); j < static_cast<std::int64_t>(j1) && margin; ++j)
      for (int d = 0; d < 16 && margin; ++d) {
        const Dir& o = dirs[d];
        if (o.dj < 0 || (o.dj == 0 && o.di < 0) || j + o.dj >= ny) continue;  // each pair once
        const std::int64_t lo = std::max<std::int64_t>(0, -o.di), hi = std::min<std::int64_t>(nx, nx - o.di);
        const double* a = &g.v[static_cast<std::size_t>(j * nx)];
        const double* b = &g.v[static_cast<std::size_t>((j + o.dj) * nx + o.di)];
        const double lim = 0.999 * w[d];
        bool ok = true;
        for (std::int64_t i = lo; i < hi; ++i) ok &= std::abs(a[i] - b[i]) <= lim;
        margin = ok;
      }
    if (margin) return;
    for (std::int64_t j = static_cast<std::int64_t>(j0); j < static_cast<std::int64_t>(j1); ++j)
      for (const Dir& d : dirs) {
        const std::int64_t jk = j + d.dj;
        if (jk < 0 || jk >= ny || (d.knight && (j + d.m1j < 0 || j + d.m1j >= ny || j + d.m2j < 0 || j + d.m2j >= ny)))
          continue;
        const std::int64_t lo = std::max<std::int64_t>({0, -d.di, d.knight ? -d.m1i : 0, d.knight ? -d.m2i : 0});
        const std::int64_t hi = std::min<std::int64_t>({nx, nx - d.di, d.knight ? nx - d.m1i : nx, d.knight ? nx - d.m2i : nx});
        const double* hrow = &g.v[static_cast<std::size_t>(j * nx)];
        const double* krow = &g.v[static_cast<std::size_t>(jk * nx + d.di)];
        const double* m1 = d.knight ? &g.v[static_cast<std::size_t>((j + d.m1j) * nx + d.m1i)] : hrow;
        const double* m2 = d.knight ? &g.v[static_cast<std::size_t>((j + d.m2j) * nx + d.m2i)] : hrow;
        const double wd = w[&d - dirs];
        bool hit = false;
        for (std::int64_t i = lo; i < hi; ++i) {
          const double h = hrow[i], cand = krow[i] + wd;  // NaN source: cand NaN, never < h
          hit |= (cand < h) & (std::isinf(h) | (h - cand > kRelTol * std::abs(h))) & !std::isnan(m1[i]) & !std::isnan(m2[i]);
        }
        if (hit) {
          row_flag[static_cast<std::size_t>(j)] = 1;
          break;
        }
      }
  }, 16);
  return std::find(row_flag.begin(), row_flag.end(), 1) != row_flag.end();
}

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
  // Most spacing grids are already alpha-Lipschitz (the distance rule grows slower than alpha):
  // when no offer of the first sweep pair would change a cell, the sweeps return the grid
  // unchanged. In that first pair every source is still the neighbour itself, so each offer is
  // g(k) + alpha |c - k| with |c - k| one of 16 constants: check that first, read-only, in row
  // bands on every thread, with the offers' own arithmetic and tests. Rows without such an offer
  // count as already swept both ways (row skipping below), so the first pair sweeps only the
  // rows that change and those downstream of a change.
  std::vector<char> row_flag;
  if (!rows_with_changes(g, alpha, row_flag)) return;
  std::vector<Source> src(g.v.size());
  Limiter L{g, alpha, src, static_cast<std::int64_t>(g.nx), static_cast<std::int64_t>(g.ny)};
  L.tick = 1;
  for (std::size_t j = 0; j < g.ny; ++j) L.last_fwd[j] = L.last_bwd[j] = row_flag[j] ? 0 : 1;
  parallel_bands(g.ny, [&](std::size_t j0, std::size_t j1) {
    for (std::size_t j = j0; j < j1; ++j)
      for (std::size_t i = 0; i < g.nx; ++i) {
        const double v = g.at(i, j);
        src[j * g.nx + i] = std::isnan(v) ? Source{v, -1, -1}
                                          : Source{v, static_cast<std::int32_t>(i), static_cast<std::int32_t>(j)};
      }
  }, 16);
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
    L.forward(0, L.ny);
    L.backward(0, L.ny);
  } while (L.changed);
}

}  // namespace fdr::sizing
