// bench_limiter: times sizing::limit_gradient (and distance_to_shore) on rough random input.
// Usage: bench_limiter [alpha=0.2] [sizes...=500 1000 2000]. Prints measurements only.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
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
    double mn = g.v[0], mx = g.v[0];
    for (double v : g.v) { mn = std::min(mn, v); mx = std::max(mx, v); }
    std::printf("  %5zu x %-5zu  %8.3f s   (%.1f ns/cell, result range %.1f .. %.1f)\n", n, n, t,
                1e9 * t / static_cast<double>(n * n), mn, mx);
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
    const auto t0 = Clock::now();
    const fdr::sizing::Grid d = fdr::sizing::distance_to_shore(like, segs);
    std::printf("distance_to_shore: 1000 x 1000 cells, %d segments: %.3f s (max distance %.1f m)\n", m,
                seconds_since(t0), *std::max_element(d.v.begin(), d.v.end()));
  }
  return 0;
}
