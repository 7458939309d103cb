// Tests of the sizing stage's O(cells) pieces: the exact Euclidean distance transform against
// brute force on random masks, distance_to_shore's fast path against brute force (exact near the
// shore, bounded beyond), the gradient limiter against the brute-force largest alpha-Lipschitz
// minorant, and the same bits for every thread count (FDR_THREADS).
#include "sizing/tests/brute_distance.hpp"
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <random>
#include <string>

#include "sizing/distance_transform.hpp"
#include "sizing/gradient_limiter.hpp"
#include "sizing/raster_rules.hpp"
#include "sizing/spacing_grid.hpp"
#include "sizing/spacing_rules.hpp"
#include "base/tests/scoped_env.hpp"

namespace fdr::sizing {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

using fdr::ThreadsEnv;

double brute_d2(std::size_t nx, std::size_t ny, double dx, double dy, const std::vector<char>& seed, std::size_t i,
                std::size_t j) {
  double best = kInf;
  for (std::size_t b = 0; b < ny; ++b)
    for (std::size_t a = 0; a < nx; ++a)
      if (seed[b * nx + a]) {
        const double ex = (static_cast<double>(i) - static_cast<double>(a)) * dx;
        const double ey = (static_cast<double>(j) - static_cast<double>(b)) * dy;
        best = std::min(best, ex * ex + ey * ey);
      }
  return best;
}

TEST(NearestSeed, EqualsBruteForceOnRandomMasks) {
  std::mt19937 rng(5);
  struct Case {
    std::size_t nx, ny;
    double dx, dy, density;
  };
  const Case cases[] = {{1, 1, 1, 1, 1.0},     {1, 1, 1, 1, 0.0},    {17, 1, 1, 1, 0.2},   {1, 23, 1, 1, 0.2},
                        {37, 29, 1, 1, 0.002}, {37, 29, 1, 1, 0.05}, {64, 40, 1, 1, 0.3},  {50, 50, 1, 1, 0.9},
                        {41, 33, 250, 250, 0.01}, {45, 31, 1.5, 0.7, 0.03}, {30, 60, 0.3, 2.0, 0.1}};
  for (const Case& c : cases)
    for (int rep = 0; rep < 4; ++rep) {
      std::bernoulli_distribution b(c.density);
      std::vector<char> seed(c.nx * c.ny);
      for (auto& s : seed) s = b(rng);
      if (rep == 3 && c.nx * c.ny > 1) {  // a single seed
        std::fill(seed.begin(), seed.end(), 0);
        seed[rng() % seed.size()] = 1;
      }
      std::vector<std::uint32_t> feat;
      std::vector<double> d2;
      nearest_seed(c.nx, c.ny, c.dx, c.dy, seed, feat, &d2);
      ASSERT_EQ(feat.size(), seed.size());
      const bool square = c.dx == c.dy;
      for (std::size_t j = 0; j < c.ny; ++j)
        for (std::size_t i = 0; i < c.nx; ++i) {
          const std::size_t k = j * c.nx + i;
          const double want = brute_d2(c.nx, c.ny, c.dx, c.dy, seed, i, j);
          if (std::isinf(want)) {
            EXPECT_EQ(feat[k], kNoFeature);
            EXPECT_EQ(d2[k], kInf);
            continue;
          }
          ASSERT_NE(feat[k], kNoFeature);
          ASSERT_TRUE(seed[feat[k]]) << "feature is not a seed";
          // d2 is the distance to the returned feature.
          const double ex = (static_cast<double>(i) - static_cast<double>(feat[k] % c.nx)) * c.dx;
          const double ey = (static_cast<double>(j) - static_cast<double>(feat[k] / c.nx)) * c.dy;
          EXPECT_EQ(d2[k], ex * ex + ey * ey);
          if (square) ASSERT_EQ(d2[k], want) << c.nx << "x" << c.ny << " cell " << i << "," << j;
          else ASSERT_LE(d2[k], want * (1 + 1e-12)) << c.nx << "x" << c.ny << " cell " << i << "," << j;
        }
    }
}

using fdr::sizing::testing::brute_dist;

// A wiggly closed coast (chained segments), a few islands and loose segments, all inside the grid.
std::vector<std::pair<Point2, Point2>> random_shore(std::mt19937& rng, Box2 box, int n) {
  std::vector<std::pair<Point2, Point2>> segs;
  std::uniform_real_distribution<double> u(0, 1);
  const Point2 c{0.5 * (box.lo.x + box.hi.x), 0.5 * (box.lo.y + box.hi.y)};
  const double r = 0.35 * std::min(box.width(), box.height());
  auto ring = [&](Point2 o, double rad, int m) {
    std::vector<Point2> pts;
    for (int k = 0; k < m; ++k) {
      const double t = 2 * std::numbers::pi * k / m, rr = rad * (1 + 0.25 * std::sin(5 * t) + 0.1 * (u(rng) - 0.5));
      pts.push_back({o.x + rr * std::cos(t), o.y + rr * std::sin(t)});
    }
    for (int k = 0; k < m; ++k) segs.push_back({pts[k], pts[(k + 1) % m]});
  };
  ring(c, r, n);
  for (int k = 0; k < 3; ++k) ring({c.x + 0.4 * r * (u(rng) - 0.5), c.y + 0.4 * r * (u(rng) - 0.5)}, 0.08 * r, 7);
  for (int k = 0; k < 5; ++k) {
    const Point2 a{box.lo.x + box.width() * (0.05 + 0.9 * u(rng)), box.lo.y + box.height() * (0.05 + 0.9 * u(rng))};
    segs.push_back({a, k == 0 ? a : Point2{a.x + 0.03 * box.width() * u(rng), a.y + 0.03 * box.height() * u(rng)}});
  }
  return segs;
}

TEST(DistanceToShore, FastPathExactNearTheShoreAndBoundedBeyond) {
  std::mt19937 rng(3);
  for (const auto& [dx, dy, n] : {std::tuple{1.0, 1.0, 300}, std::tuple{2.0, 2.0, 40}, std::tuple{1.5, 0.8, 500}}) {
    Grid like;
    like.nx = 90; like.ny = 70; like.x0 = -30; like.y0 = 12; like.dx = dx; like.dy = dy;
    like.v.assign(like.nx * like.ny, 0.0);
    const auto segs = random_shore(rng, like.extent(), n);
    const Grid fast = distance_to_shore(like, segs);
    const Grid exact = distance_to_shore(like, segs, true);
    const double cell = std::max(dx, dy), diag = std::hypot(dx, dy);
    std::size_t differ = 0;
    for (std::size_t j = 0; j < like.ny; ++j)
      for (std::size_t i = 0; i < like.nx; ++i) {
        const double want = brute_dist(like.center(i, j), segs);
        ASSERT_EQ(exact.at(i, j), want) << i << " " << j;
        const double got = fast.at(i, j);
        ASSERT_GE(got, want) << i << " " << j;
        ASSERT_LE(got, want + diag) << i << " " << j;
        // Guaranteed exact within (3.5 - sqrt 2) cells of the shore.
        if (want <= (3.5 - std::sqrt(2.0)) * cell) { ASSERT_EQ(got, want) << "near the shore: " << i << " " << j; }
        differ += got != want;
      }
    EXPECT_LT(differ, like.v.size() / 10) << "dx " << dx;
  }
}

TEST(DistanceToShore, SegmentsOutsideTheGridStillExact) {
  Grid like;
  like.nx = 20; like.ny = 10; like.x0 = 0; like.y0 = 0; like.dx = like.dy = 1;
  like.v.assign(200, 0.0);
  const std::vector<std::pair<Point2, Point2>> segs = {{{-5, 3}, {30, 4}}, {{2, 2}, {3, 3}}};
  const Grid d = distance_to_shore(like, segs);
  for (std::size_t j = 0; j < like.ny; ++j)
    for (std::size_t i = 0; i < like.nx; ++i) EXPECT_EQ(d.at(i, j), brute_dist(like.center(i, j), segs));
}

// h(x) = min over y of h0(y) + alpha |x - y|: the largest alpha-Lipschitz function <= h0.
Grid oracle(const Grid& h0, double alpha) {
  Grid out = h0;
  for (std::size_t j = 0; j < h0.ny; ++j)
    for (std::size_t i = 0; i < h0.nx; ++i) {
      double best = kInf;
      const Point2 c = h0.center(i, j);
      for (std::size_t b = 0; b < h0.ny; ++b)
        for (std::size_t a = 0; a < h0.nx; ++a) best = std::min(best, h0.at(a, b) + alpha * dist(c, h0.center(a, b)));
      out.at(i, j) = best;
    }
  return out;
}

TEST(Limiter, LargestLipschitzMinorantOnSquareCells) {
  std::mt19937 rng(17);
  for (int trial = 0; trial < 6; ++trial) {
    Grid g;
    g.nx = 23 + trial * 3; g.ny = 19 + trial; g.x0 = 1; g.y0 = -4; g.dx = g.dy = trial % 2 ? 1.0 : 40.0;
    g.v.resize(g.nx * g.ny);
    std::uniform_real_distribution<double> u(1, 10 * g.dx);
    std::bernoulli_distribution sparse(0.05);
    for (double& v : g.v) v = trial >= 3 ? (sparse(rng) ? u(rng) : 100 * g.dx) : u(rng);  // rough or few sources
    for (double alpha : {0.0, 0.05, 0.2, 1.0}) {
      Grid h = g;
      limit_gradient(h, alpha);
      const Grid want = oracle(g, alpha);
      for (std::size_t k = 0; k < h.v.size(); ++k)
        ASSERT_NEAR(h.v[k], want.v[k], 1e-12 * want.v[k]) << "trial " << trial << " alpha " << alpha << " cell " << k;
      // alpha-Lipschitz between every pair of cells (not only neighbours).
      for (std::size_t p = 0; p < h.v.size(); ++p)
        for (std::size_t q = 0; q < h.v.size(); ++q) {
          const double d = dist(h.center(p % h.nx, p / h.nx), h.center(q % h.nx, q / h.nx));
          ASSERT_LE(h.v[q], (h.v[p] + alpha * d) * (1 + 1e-12)) << "trial " << trial << " alpha " << alpha;
        }
    }
  }
}

// Same bits for 1, 2, 3 and 5 threads: EDT, distance to shore, rules, limiter.
TEST(SizingThreads, SameResultForEveryThreadCount) {
  std::mt19937 rng(8);
  Grid like;
  like.nx = 157; like.ny = 131; like.x0 = 100; like.y0 = -50; like.dx = like.dy = 3;
  like.v.assign(like.nx * like.ny, 0.0);
  const auto shore = random_shore(rng, like.extent(), 400);
  std::vector<char> seed(like.v.size());
  std::bernoulli_distribution b(0.01);
  for (auto& s : seed) s = b(rng);
  Grid rough = like;
  std::uniform_real_distribution<double> u(5, 500);
  for (double& v : rough.v) v = u(rng);
  Grid dem = like;
  for (std::size_t k = 0; k < dem.v.size(); ++k) dem.v[k] = -20 - 10 * std::sin(0.05 * static_cast<double>(k % 157)) * std::cos(0.07 * static_cast<double>(k / 157));
  SpacingRules r;
  r.hmin = 4; r.hmax = 200; r.dist_grade = 0.1; r.slope = 10; r.channel_elements = 3;

  struct Result {
    std::vector<std::uint32_t> feat;
    std::vector<double> d2, dist, lim, rules;
  };
  auto run = [&] {
    Result res;
    nearest_seed(like.nx, like.ny, like.dx, like.dy, seed, res.feat, &res.d2);
    res.dist = distance_to_shore(like, shore).v;
    Grid h = rough;
    limit_gradient(h, 0.15);
    res.lim = h.v;
    RuleGrid rg = spacing_from_rules(r, {&like, &shore, &dem, nullptr, &shore});
    limit_gradient(rg.h, 0.2);
    res.rules = rg.h.v;
    return res;
  };
  Result one;
  {
    ThreadsEnv t(1);
    one = run();
  }
  for (int n : {2, 3, 5}) {
    ThreadsEnv t(n);
    const Result other = run();
    EXPECT_EQ(other.feat, one.feat) << n;
    EXPECT_EQ(other.d2, one.d2) << n;
    EXPECT_EQ(other.dist, one.dist) << n;
    EXPECT_EQ(other.lim, one.lim) << n;
    EXPECT_EQ(other.rules, one.rules) << n;
  }
}

TEST(SpacingGrid, CellFromHminAndDomain) {
  Box2 b;
  b.add({0, 0});
  b.add({100000, 50000});
  // hmin rules while the grid stays within 4M cells...
  EXPECT_EQ(spacing_grid_cell(b, 100), 100);
  // ...and the 4M-cell budget caps it.
  EXPECT_DOUBLE_EQ(spacing_grid_cell(b, 10), std::sqrt(100000.0 * 50000.0 / 4e6));
  const Grid g = spacing_grid(b, 100);
  EXPECT_EQ(g.nx, 1002u);
  EXPECT_EQ(g.ny, 502u);
  EXPECT_LE(g.x0, b.lo.x);
  EXPECT_GE(g.x0 + static_cast<double>(g.nx) * g.dx, b.hi.x);
}

}  // namespace
}  // namespace fdr::sizing
