// Exact separable Euclidean distance transform (feature transform); see distance_transform.hpp.
#include "sizing/distance_transform.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "base/error.hpp"
#include "base/parallel.hpp"

namespace fdr::sizing {

void nearest_seed(std::size_t nx, std::size_t ny, double dx, double dy, const std::vector<char>& seed,
                  std::vector<std::uint32_t>& feature, std::vector<double>* d2) {
  const std::size_t n = nx * ny;
  if (seed.size() != n || !(dx > 0) || !(dy > 0))
    throw Error(ExitCode::kInternal, "nearest_seed: mask of " + std::to_string(seed.size()) + " cells for a " +
                                         std::to_string(nx) + " x " + std::to_string(ny) + " grid");
  if (n >= kNoFeature) throw Error(ExitCode::kInternal, "nearest_seed: grid too large");
  feature.assign(n, kNoFeature);
  if (d2) d2->assign(n, std::numeric_limits<double>::infinity());
  if (n == 0) return;
  // Pass 1: row of the nearest seed in the same column (-1: none), as int32.
  std::vector<std::int32_t> col(n);
  parallel_bands(nx, [&](std::size_t i0, std::size_t i1) {
    // Upward scan: the last seed at or below.
    for (std::size_t j = 0; j < ny; ++j) {
      const std::size_t r = j * nx;
      for (std::size_t i = i0; i < i1; ++i)
        col[r + i] = seed[r + i] ? static_cast<std::int32_t>(j) : (j > 0 ? col[r - nx + i] : -1);
    }
    // Downward scan: the first seed at or above, when nearer (ties keep the lower one).
    std::vector<std::int32_t> above(i1 - i0, -1);
    for (std::size_t jj = ny; jj-- > 0;) {
      const std::size_t r = jj * nx;
      const auto j = static_cast<std::int32_t>(jj);
      for (std::size_t i = i0; i < i1; ++i) {
        std::int32_t& a = above[i - i0];
        if (seed[r + i]) a = j;
        const std::int32_t b = col[r + i];
        if (a >= 0 && (b < 0 || a - j < j - b)) col[r + i] = a;
      }
    }
  });
  // Pass 2: per row, lower envelope of f_i(x) = (x - i)^2 + w * g_i^2 with w = (dy/dx)^2
  // (squared distance in units of dx^2). For square cells every value is an integer below 2^53.
  const double w = (dy / dx) * (dy / dx);
  parallel_bands(ny, [&](std::size_t j0, std::size_t j1) {
    std::vector<std::int64_t> site(nx);  // columns on the envelope
    std::vector<double> fsite(nx);       // their f value at their own column
    std::vector<double> start(nx + 1);   // the envelope's piece k starts at start[k]
    for (std::size_t j = j0; j < j1; ++j) {
      const std::size_t r = j * nx;
      std::size_t k = 0;  // pieces - 1; none yet when `have` is false
      bool have = false;
      for (std::size_t i = 0; i < nx; ++i) {
        const std::int32_t g = col[r + i];
        if (g < 0) continue;
        const double gi = static_cast<double>(static_cast<std::int64_t>(j) - g);
        const double fi = w * gi * gi;
        const auto q = static_cast<std::int64_t>(i);
        if (!have) {
          site[0] = q; fsite[0] = fi; start[0] = -std::numeric_limits<double>::infinity();
          have = true;
          continue;
        }
        // Intersection of parabola q with the envelope's last piece v (q > v).
        for (;;) {
          const std::int64_t v = site[k];
          const double s = ((fi + static_cast<double>(q * q)) - (fsite[k] + static_cast<double>(v * v))) /
                           static_cast<double>(2 * (q - v));
          if (k > 0 && s <= start[k]) { --k; continue; }
          if (k == 0 && s <= start[0]) { site[0] = q; fsite[0] = fi; break; }  // q hides v everywhere
          ++k;
          site[k] = q; fsite[k] = fi; start[k] = s;
          break;
        }
      }
      if (!have) continue;
      std::size_t p = 0;
      for (std::size_t i = 0; i < nx; ++i) {
        const double x = static_cast<double>(i);
        while (p < k && start[p + 1] <= x) ++p;  // ties: the later (right) column
        const std::int64_t c = site[p];
        const std::size_t src = static_cast<std::size_t>(col[r + static_cast<std::size_t>(c)]);
        feature[r + i] = static_cast<std::uint32_t>(src * nx + static_cast<std::size_t>(c));
        if (d2) {
          const double ex = static_cast<double>(static_cast<std::int64_t>(i) - c) * dx;
          const double ey = static_cast<double>(static_cast<std::int64_t>(j) - static_cast<std::int64_t>(src)) * dy;
          (*d2)[r + i] = ex * ex + ey * ey;
        }
      }
    }
  });
}

}  // namespace fdr::sizing
