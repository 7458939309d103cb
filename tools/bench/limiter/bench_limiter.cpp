// bench_limiter: times sizing::limit_gradient (and distance_to_shore) on rough random input.
// Usage: bench_limiter [alpha=0.2] [sizes...=500 1000 2000]. Prints measurements only.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <algorithm>
#include <vector>

#include "sizing/gradient_limiter.hpp"
#include "sizing/raster_rules.hpp"

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

fdr::sizing::Grid rough_grid(std::size_t n, unsigned seed) {
  fdr::sizing::Grid g;
  g.nx = g.ny = n;
  g.dx = g.dy = 10.0;  // 10 m cells
  g.v.resize(n * n);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(20.0, 2000.0);
  for (double& v : g.v) v = u(rng);
  return g;
}

}  // namespace

int main(int argc, char** argv) {
  const double alpha = argc > 1 ? std::atof(argv[1]) : 0.2;
  std::vector<std::size_t> sizes;
  for (int k = 2; k < argc; ++k) sizes.push_back(static_cast<std::size_t>(std::atol(argv[k])));
  if (sizes.empty()) sizes = {500, 1000, 2000};
  std::printf("limit_gradient, alpha = %g, uniform random values in [20, 2000], 10 m cells\n", alpha);
  for (std::size_t n : sizes) {
    fdr::sizing::Grid g = rough_grid(n, 42);
    const auto t0 = Clock::now();
    fdr::sizing::limit_gradient(g, alpha);
    const double t = seconds_since(t0);
    // An already alpha-Lipschitz grid (the common case: the distance rule grows slower than alpha).
    fdr::sizing::Grid smooth = g;
    const auto t1 = Clock::now();
    fdr::sizing::limit_gradient(smooth, alpha);
    const double ts = seconds_since(t1);
    double mn = g.v[0], mx = g.v[0];
    for (double v : g.v) { mn = std::min(mn, v); mx = std::max(mx, v); }
    std::printf("  %5zu x %-5zu  %8.3f s   (%.1f M cells/s, result range %.1f .. %.1f); its result again (already "
                "limited): %.4f s (%.0f M cells/s)\n", n, n, t, static_cast<double>(n * n) / t / 1e6, mn, mx, ts,
                static_cast<double>(n * n) / ts / 1e6);
  }
  // distance_to_shore on 1000 x 1000 cells against 1e5 segments of a wiggly coastline.
  {
    fdr::sizing::Grid like = rough_grid(1000, 1);
    std::vector<std::pair<fdr::Point2, fdr::Point2>> segs;
    const int m = 100000;
    auto coast = [&](int k) {
      const double t = 10000.0 * k / m;
      return fdr::Point2{t, 3000 + 800 * std::sin(t / 700) + 60 * std::sin(t / 23)};
    };
    for (int k = 0; k < m; ++k) segs.push_back({coast(k), coast(k + 1)});
    auto t0 = Clock::now();
    const fdr::sizing::Grid d = fdr::sizing::distance_to_shore(like, segs);
    const double t_fast = seconds_since(t0);
    t0 = Clock::now();
    const fdr::sizing::Grid e = fdr::sizing::distance_to_shore(like, segs, true);
    const double t_exact = seconds_since(t0);
    std::size_t differ = 0;
    double worst = 0;
    for (std::size_t k = 0; k < d.v.size(); ++k) {
      differ += d.v[k] != e.v[k];
      worst = std::max(worst, d.v[k] - e.v[k]);
    }
    std::printf("distance_to_shore: 1000 x 1000 cells, %d segments: %.3f s = %.1f M cells/s (max distance %.1f m);\n"
                "  exact BVH path %.3f s = %.1f M cells/s; %zu cells differ, by at most %.3g m (cells of 10 m)\n",
                m, t_fast, 1.0 / t_fast, *std::max_element(d.v.begin(), d.v.end()), t_exact, 1.0 / t_exact, differ, worst);
  }
  return 0;
}
