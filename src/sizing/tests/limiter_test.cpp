// Tests of the gradient limiter: never increases, alpha-Lipschitz between 8-neighbours,
// idempotent, exact for a single source, NaN barriers, +inf cells.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "base/error.hpp"
#include "sizing/gradient_limiter.hpp"

namespace fdr::sizing {
namespace {

Grid random_grid(std::size_t nx, std::size_t ny, double dx, double dy, unsigned seed, double lo = 1, double hi = 10) {
  Grid g;
  g.nx = nx; g.ny = ny; g.x0 = -7; g.y0 = 3; g.dx = dx; g.dy = dy;
  g.v.resize(nx * ny);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(lo, hi);
  for (double& v : g.v) v = u(rng);
  return g;
}

// Largest violation of g(q) <= g(p) + alpha |p - q| over 8-neighbours, relative to g(q).
double worst_violation(const Grid& g, double alpha) {
  double worst = 0;
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i)
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          const long ii = static_cast<long>(i) + di, jj = static_cast<long>(j) + dj;
          if ((di == 0 && dj == 0) || ii < 0 || jj < 0 || ii >= static_cast<long>(g.nx) || jj >= static_cast<long>(g.ny))
            continue;
          const double p = g.at(ii, jj), q = g.at(i, j);
          if (std::isnan(p) || std::isnan(q)) continue;
          const double d = std::hypot(di * g.dx, dj * g.dy);
          worst = std::max(worst, (q - (p + alpha * d)) / std::abs(q));
        }
  return worst;
}

TEST(Limiter, RandomGridProperties) {
  for (unsigned seed : {1u, 2u, 3u}) {
    const Grid in = random_grid(61, 47, 1.0, seed == 2 ? 1.7 : 1.0, seed);
    for (double alpha : {0.0, 0.05, 0.3, 2.0}) {
      Grid g = in;
      limit_gradient(g, alpha);
      for (std::size_t k = 0; k < g.v.size(); ++k) ASSERT_LE(g.v[k], in.v[k]);
      EXPECT_LE(worst_violation(g, alpha), 1e-11) << "seed " << seed << " alpha " << alpha;
      Grid again = g;
      limit_gradient(again, alpha);
      EXPECT_EQ(again.v, g.v) << "not idempotent, alpha " << alpha;
      // Against the defining formula h(x) = min_y h(y) + alpha |x - y| (brute force).
      double worst_excess = 0;
      for (std::size_t j = 0; j < g.ny; ++j)
        for (std::size_t i = 0; i < g.nx; ++i) {
          double best = in.at(i, j);
          const Point2 c = in.center(i, j);
          for (std::size_t b = 0; b < g.ny; ++b)
            for (std::size_t a = 0; a < g.nx; ++a) best = std::min(best, in.at(a, b) + alpha * dist(c, in.center(a, b)));
          ASSERT_GE(g.at(i, j), best * (1 - 1e-12));
          worst_excess = std::max(worst_excess, g.at(i, j) / best - 1);
        }
      EXPECT_LE(worst_excess, 0.02) << "seed " << seed << " alpha " << alpha;
    }
  }
}

TEST(Limiter, AlreadyLimitedGridUnchanged) {
  Grid g = random_grid(50, 40, 2.0, 1.0, 9);
  const Point2 s{13.3, 20.1};
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i) {
      const Point2 c = g.center(i, j);
      g.at(i, j) = 1 + 0.1 * dist(c, s) + 0.05 * c.x;  // Lipschitz <= 0.15
    }
  for (double alpha : {0.15, 0.2, 1.0}) {
    Grid h = g;
    limit_gradient(h, alpha);
    EXPECT_EQ(h.v, g.v) << alpha;
  }
  // A ramp with exactly the limiting slope.
  Grid r = g;
  for (std::size_t j = 0; j < r.ny; ++j)
    for (std::size_t i = 0; i < r.nx; ++i) r.at(i, j) = 5 + 0.25 * r.center(i, j).x;
  Grid r2 = r;
  limit_gradient(r2, 0.25);
  EXPECT_EQ(r2.v, r.v);
}

TEST(Limiter, SingleSourceIsExactCone) {
  Grid g = random_grid(101, 77, 1.5, 0.75, 4, 100, 100);
  const std::size_t si = 30, sj = 60;
  g.at(si, sj) = 1;
  const double alpha = 0.2;
  limit_gradient(g, alpha);
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i)
      EXPECT_DOUBLE_EQ(g.at(i, j), std::min(100.0, 1 + alpha * dist(g.center(i, j), g.center(si, sj))));
}

TEST(Limiter, NanCellsAreBarriersAndInfCellsGetValues) {
  Grid g = random_grid(30, 20, 1, 1, 5, 50, 50);
  const double inf = std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j < g.ny; ++j) g.at(15, j) = std::nan("");  // a wall at column 15
  g.at(3, 3) = 1;    // low value left of the wall
  g.at(25, 10) = inf;  // no constraint, right of the wall
  g.at(27, 2) = 40;
  limit_gradient(g, 0.5);
  for (std::size_t j = 0; j < g.ny; ++j) EXPECT_TRUE(std::isnan(g.at(15, j)));
  EXPECT_EQ(g.at(3, 3), 1.0);
  EXPECT_LT(g.at(14, 3), 50.0);         // reached on the left side
  // Right of the wall only the source at (27, 2) acts, not the lower one at (3, 3).
  EXPECT_DOUBLE_EQ(g.at(16, 3), 40 + 0.5 * std::hypot(11.0, 1.0));
  EXPECT_EQ(g.at(16, 19), 50.0);
  EXPECT_DOUBLE_EQ(g.at(25, 10), std::min(50.0, 40 + 0.5 * std::hypot(2.0, 8.0)));
  EXPECT_LE(worst_violation(g, 0.5), 1e-11);
  Grid all_inf = random_grid(5, 5, 1, 1, 6, 1, 1);
  for (double& v : all_inf.v) v = inf;
  limit_gradient(all_inf, 0.1);
  for (double v : all_inf.v) EXPECT_EQ(v, inf);
}

TEST(Limiter, BadAlphaAndEmptyGrid) {
  Grid g = random_grid(3, 3, 1, 1, 1);
  EXPECT_THROW(limit_gradient(g, -0.1), Error);
  EXPECT_THROW(limit_gradient(g, std::nan("")), Error);
  Grid e;
  EXPECT_NO_THROW(limit_gradient(e, 0.1));
}

}  // namespace
}  // namespace fdr::sizing
