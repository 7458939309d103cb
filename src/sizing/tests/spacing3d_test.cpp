// Tests of the 3D spacing functions: constant, expression in x, y, z (the paper's f1 and f2 lifted
// to 3D, thread safety), trilinear grid, and the 3D gradient limiter (only lowers, alpha-Lipschitz
// between grid nodes, idempotent, exact for one source, NaN barriers, +inf cells).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>

#include "base/error.hpp"
#include "base/parallel.hpp"
#include "sizing/spacing3d.hpp"
#include "sizing/spacing3d_expression.hpp"
#include "sizing/spacing3d_limiter.hpp"
#include "sizing/spacing3d_make.hpp"

namespace fdr::sizing {
namespace {

ExitCode code_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.code();
  }
  return ExitCode::kOk;
}

TEST(Spacing3d, Constant) {
  const ConstantField3 f(0.25);
  EXPECT_EQ(f({1, 2, 3}), 0.25);
  EXPECT_EQ(f.lipschitz(), 0.0);
  EXPECT_EQ(code_of([] { ConstantField3 g(0); }), ExitCode::kInvalidSpacing);
  EXPECT_EQ(code_of([] { ConstantField3 g(NAN); }), ExitCode::kInvalidSpacing);
}

TEST(Spacing3d, PaperFunctionsAsExpressions) {
  const ExpressionField3 f1("(abs(x-5)+abs(y-5)+abs(z-5))*0.1+0.1");
  const ExpressionField3 f2("(abs(sin(x+y+z))+abs(cos(x+y+z)))*0.1");
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(0, 10);
  for (int n = 0; n < 200; ++n) {
    const Point3 p{u(rng), u(rng), u(rng)};
    const double s = p.x + p.y + p.z;
    EXPECT_DOUBLE_EQ(f1(p), (std::abs(p.x - 5) + std::abs(p.y - 5) + std::abs(p.z - 5)) * 0.1 + 0.1);
    EXPECT_DOUBLE_EQ(f2(p), (std::abs(std::sin(s)) + std::abs(std::cos(s))) * 0.1);
  }
  EXPECT_EQ(f1({5, 5, 5}), 0.1);
}

TEST(Spacing3d, ExpressionErrors) {
  try {
    ExpressionField3 f("x + * z");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kUsage);
    EXPECT_NE(std::string(e.what()).find("spacing expression 'x + * z'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("at position"), std::string::npos) << e.what();
  }
  EXPECT_EQ(code_of([] { ExpressionField3 f("w + 1"); }), ExitCode::kUsage);   // unknown variable
  EXPECT_EQ(code_of([] { ExpressionField3 f("x, y"); }), ExitCode::kUsage);    // two results
}

// Several threads evaluating one field at once get the bits one thread gets.
TEST(Spacing3d, ExpressionThreadSafe) {
  const ExpressionField3 f("0.1 + 0.01*sqrt(x*x + y*y + z*z) + 0.05*sin(3*z)");
  const std::size_t n = 20000;
  std::vector<double> one(n), many(n);
  auto at = [](std::size_t i) { return Point3{0.001 * static_cast<double>(i), 0.5, -0.002 * static_cast<double>(i)}; };
  for (std::size_t i = 0; i < n; ++i) one[i] = f(at(i));
  parallel_bands(n, [&](std::size_t lo, std::size_t hi) {
    for (std::size_t i = lo; i < hi; ++i) many[i] = f(at(i));
  }, 64, 2);
  EXPECT_EQ(one, many);
}

TEST(Spacing3d, MakeSpacing3) {
  EXPECT_EQ(make_spacing3(" 0.5 ")->describe(), "constant 0.5");
  const auto f1 = make_spacing3("paper-f1"), f2 = make_spacing3("2 * paper-f2"), e = make_spacing3("x + 2*z + 1");
  const ExpressionField3 g1("(abs(x-5)+abs(y-5)+abs(z-5))*0.1+0.1");
  const ExpressionField3 g2("(abs(sin(x+y+z))+abs(cos(x+y+z)))*0.1");
  for (Point3 p : {Point3{0, 0, 0}, Point3{1.5, 7.25, 3}, Point3{10, 2, 9.5}}) {
    EXPECT_DOUBLE_EQ((*f1)(p), g1(p));
    EXPECT_DOUBLE_EQ((*f2)(p), 2 * g2(p));
    EXPECT_DOUBLE_EQ((*e)(p), p.x + 2 * p.z + 1);
  }
  EXPECT_NEAR(f1->lipschitz(), 0.1 * std::sqrt(3.0), 1e-15);
  EXPECT_EQ(code_of([] { make_spacing3(""); }), ExitCode::kUsage);
  EXPECT_EQ(code_of([] { make_spacing3("-1"); }), ExitCode::kInvalidSpacing);
  EXPECT_EQ(code_of([] { make_spacing3("0 * paper-f1"); }), ExitCode::kInvalidSpacing);
  EXPECT_EQ(code_of([] { make_spacing3("x +"); }), ExitCode::kUsage);
}

Grid3 random_grid(std::size_t nx, std::size_t ny, std::size_t nz, double dx, double dy, double dz, unsigned seed) {
  Grid3 g;
  g.nx = nx, g.ny = ny, g.nz = nz;
  g.x0 = -3, g.y0 = 2, g.z0 = 7;
  g.dx = dx, g.dy = dy, g.dz = dz;
  g.v.resize(nx * ny * nz);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(1, 10);
  for (double& v : g.v) v = u(rng);
  return g;
}

TEST(Spacing3d, GridTrilinear) {
  // A linear function is reproduced exactly inside the centres' hull, clamped outside.
  Grid3 g;
  g.nx = 4, g.ny = 3, g.nz = 5;
  g.dx = 2, g.dy = 1, g.dz = 0.5;
  g.v.resize(g.nx * g.ny * g.nz);
  auto lin = [](Point3 p) { return 1 + 0.5 * p.x + 0.25 * p.y + 2 * p.z; };
  for (std::size_t k = 0; k < g.nz; ++k)
    for (std::size_t j = 0; j < g.ny; ++j)
      for (std::size_t i = 0; i < g.nx; ++i) g.at(i, j, k) = lin(g.center(i, j, k));
  const GridField3 f(g);
  EXPECT_NEAR(f({3.3, 1.7, 1.1}), lin({3.3, 1.7, 1.1}), 1e-12);
  EXPECT_NEAR(f({-5, 1.5, 1.25}), lin({1, 1.5, 1.25}), 1e-12);
  EXPECT_DOUBLE_EQ(f(g.center(2, 1, 3)), g.at(2, 1, 3));
  EXPECT_NEAR(f.lipschitz(), std::sqrt(0.25 + 0.0625 + 4), 1e-12);
  EXPECT_EQ(f.upper_bound(), g.v.back());
  // A one-cell-thick grid is constant along that axis.
  Grid3 flat = random_grid(3, 3, 1, 1, 1, 1, 5);
  const GridField3 h(flat);
  EXPECT_EQ(h({1.5, 1.5, -10}), h({1.5, 1.5, 10}));
}

TEST(Spacing3d, GridRejectsBadCells) {
  Grid3 g = random_grid(3, 3, 3, 1, 1, 1, 1);
  g.at(1, 2, 0) = NAN;
  try {
    GridField3 f(g, "wells");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidSpacing);
    EXPECT_NE(std::string(e.what()).find("cell (1, 2, 0)"), std::string::npos) << e.what();
  }
  g.at(1, 2, 0) = -1;
  EXPECT_EQ(code_of([&] { GridField3 f(g); }), ExitCode::kInvalidSpacing);
  g.at(1, 2, 0) = 1;
  g.v.pop_back();
  EXPECT_EQ(code_of([&] { GridField3 f(g); }), ExitCode::kInvalidSpacing);
}

// Largest violation of g(q) <= g(p) + alpha |p - q| over every pair of non-NaN cells, relative to
// g(q); `neighbours_only` restricts it to 26-neighbours.
double worst_violation(const Grid3& g, double alpha, bool neighbours_only) {
  double worst = 0;
  const std::size_t n = g.v.size();
  for (std::size_t a = 0; a < n; ++a) {
    const std::size_t ai = a % g.nx, aj = a / g.nx % g.ny, ak = a / (g.nx * g.ny);
    for (std::size_t b = 0; b < n; ++b) {
      const std::size_t bi = b % g.nx, bj = b / g.nx % g.ny, bk = b / (g.nx * g.ny);
      if (a == b || std::isnan(g.v[a]) || std::isnan(g.v[b])) continue;
      auto far = [](std::size_t u, std::size_t w) { return u > w + 1 || w > u + 1; };
      if (neighbours_only && (far(ai, bi) || far(aj, bj) || far(ak, bk))) continue;
      const double d = dist(g.center(ai, aj, ak), g.center(bi, bj, bk));
      worst = std::max(worst, (g.v[b] - (g.v[a] + alpha * d)) / std::abs(g.v[b]));
    }
  }
  return worst;
}

TEST(Spacing3dLimiter, RandomGridProperties) {
  for (unsigned seed : {1u, 2u}) {
    const Grid3 in = random_grid(9, 8, 7, 1.0, seed == 2 ? 1.6 : 1.0, seed == 2 ? 0.7 : 1.0, seed);
    for (double alpha : {0.0, 0.1, 0.5, 3.0}) {
      Grid3 g = in;
      limit_gradient3(g, alpha);
      for (std::size_t c = 0; c < g.v.size(); ++c) ASSERT_LE(g.v[c], in.v[c]);
      EXPECT_LE(worst_violation(g, alpha, true), 1e-11) << "seed " << seed << " alpha " << alpha;
      Grid3 again = g;
      limit_gradient3(again, alpha);
      EXPECT_EQ(again.v, g.v) << "not idempotent, alpha " << alpha;
      // Against the defining formula h(x) = min_y h(y) + alpha |x - y| (brute force): never below it.
      double worst_excess = 0;
      for (std::size_t c = 0; c < g.v.size(); ++c) {
        const Point3 pc = in.center(c % in.nx, c / in.nx % in.ny, c / (in.nx * in.ny));
        double best = in.v[c];
        for (std::size_t y = 0; y < in.v.size(); ++y)
          best = std::min(best, in.v[y] + alpha * dist(pc, in.center(y % in.nx, y / in.nx % in.ny, y / (in.nx * in.ny))));
        ASSERT_GE(g.v[c], best * (1 - 1e-12));
        worst_excess = std::max(worst_excess, g.v[c] / best - 1);
      }
      EXPECT_LE(worst_excess, 0.02) << "seed " << seed << " alpha " << alpha;
    }
  }
}

// Between every pair of grid nodes, not only neighbours, on cubic cells.
TEST(Spacing3dLimiter, LipschitzBetweenAllNodes) {
  Grid3 g = random_grid(8, 7, 6, 0.5, 0.5, 0.5, 11);
  limit_gradient3(g, 0.3);
  EXPECT_LE(worst_violation(g, 0.3, false), 1e-11);
}

TEST(Spacing3dLimiter, SingleSourceIsACone) {
  Grid3 g;
  g.nx = 12, g.ny = 10, g.nz = 9;
  g.dx = 1, g.dy = 2, g.dz = 0.5;
  g.v.assign(g.nx * g.ny * g.nz, 100.0);
  g.at(3, 4, 5) = 1.0;
  limit_gradient3(g, 0.2);
  const Point3 s = g.center(3, 4, 5);
  for (std::size_t k = 0; k < g.nz; ++k)
    for (std::size_t j = 0; j < g.ny; ++j)
      for (std::size_t i = 0; i < g.nx; ++i)
        EXPECT_NEAR(g.at(i, j, k), 1.0 + 0.2 * dist(g.center(i, j, k), s), 1e-12) << i << " " << j << " " << k;
}

TEST(Spacing3dLimiter, AlreadyLimitedGridUnchanged) {
  Grid3 g = random_grid(10, 9, 8, 1.0, 1.5, 0.8, 3);
  const Point3 s{2.1, 5.3, 9.9};
  for (std::size_t k = 0; k < g.nz; ++k)
    for (std::size_t j = 0; j < g.ny; ++j)
      for (std::size_t i = 0; i < g.nx; ++i) {
        const Point3 c = g.center(i, j, k);
        g.at(i, j, k) = 1 + 0.1 * dist(c, s) + 0.05 * c.z;  // Lipschitz <= 0.15
      }
  for (double alpha : {0.15, 0.3}) {
    Grid3 h = g;
    limit_gradient3(h, alpha);
    EXPECT_EQ(h.v, g.v) << alpha;
  }
}

TEST(Spacing3dLimiter, NanWallAndInfCells) {
  // A NaN wall at i == 4: a closed wall keeps the low source from the +inf cells beyond it; with
  // one open cell, values reach them through it (each the source's value plus alpha times the
  // straight distance, as in 2D).
  for (bool gap : {false, true}) {
    Grid3 g;
    g.nx = 9, g.ny = 6, g.nz = 5;
    g.v.assign(g.nx * g.ny * g.nz, std::numeric_limits<double>::infinity());
    for (std::size_t k = 0; k < g.nz; ++k)
      for (std::size_t j = 0; j < g.ny; ++j) g.at(4, j, k) = NAN;
    if (gap) g.at(4, 0, 0) = std::numeric_limits<double>::infinity();
    g.at(1, 5, 4) = 1.0;
    limit_gradient3(g, 1.0);
    for (std::size_t k = 0; k < g.nz; ++k)
      for (std::size_t j = 0; j < g.ny; ++j) {
        EXPECT_EQ(std::isnan(g.at(4, j, k)), !(gap && j == 0 && k == 0));
        for (std::size_t i = 0; i < g.nx; ++i) {
          if (i == 4) continue;
          const double v = g.at(i, j, k);
          if (i > 4 && !gap) {
            EXPECT_EQ(v, std::numeric_limits<double>::infinity()) << i << " " << j << " " << k;
            continue;
          }
          ASSERT_TRUE(std::isfinite(v)) << i << " " << j << " " << k;
          EXPECT_NEAR(v, 1.0 + dist(g.center(i, j, k), g.center(1, 5, 4)), 1e-12);
        }
      }
    if (gap) EXPECT_LE(worst_violation(g, 1.0, true), 1e-11);
  }
  Grid3 g = random_grid(3, 3, 3, 1, 1, 1, 2);
  EXPECT_EQ(code_of([&] { limit_gradient3(g, -1); }), ExitCode::kUsage);
  EXPECT_EQ(code_of([&] { limit_gradient3(g, INFINITY); }), ExitCode::kUsage);
  Grid3 empty;
  EXPECT_NO_THROW(limit_gradient3(empty, 0.5));
}

}  // namespace
}  // namespace fdr::sizing
