// Tests of analytic fields, presets, combinators, GridField and the sampled field checks.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "base/error.hpp"
#include "sizing/field_checks.hpp"
#include "sizing/fields.hpp"
#include "sizing/grid_field.hpp"
#include "sizing/make_spacing.hpp"

namespace fdr::sizing {
namespace {

Box2 box(double x0, double y0, double x1, double y1) {
  Box2 b;
  b.add({x0, y0});
  b.add({x1, y1});
  return b;
}

TEST(Presets, EqualTheirFormulas) {
  PaperF1Field f1;
  PaperF2Field f2;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-3, 13);
  for (int k = 0; k < 1000; ++k) {
    const double x = u(rng), y = u(rng);
    EXPECT_DOUBLE_EQ(f1({x, y}), (std::abs(x - 5) + std::abs(y - 5)) * 0.1 + 0.1);
    EXPECT_DOUBLE_EQ(f2({x, y}), (std::abs(std::sin(x + y)) + std::abs(std::cos(x + y))) * 0.1);
  }
  EXPECT_DOUBLE_EQ(PaperF1Field(0.025)({0, 0}), 0.025 * 1.1);
  EXPECT_DOUBLE_EQ(f1.lipschitz(), 0.1 * std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(f2.lipschitz(), 0.1 * std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(PaperF2Field(3).lipschitz(), 0.3 * std::sqrt(2.0));
}

TEST(Presets, LipschitzEstimateMatchesKnownConstant) {
  const Box2 b = box(0, 0, 10, 10);
  const SizingPtr presets[] = {std::make_shared<PaperF1Field>(), std::make_shared<PaperF2Field>()};
  for (const auto& f : presets) {
    const double est = estimate_lipschitz(*f, b, 513);
    EXPECT_LE(est, f->lipschitz() * (1 + 1e-9)) << f->describe();
    // The steepest slope of paper-f2 sits at its kinks, which finite differences round off.
    EXPECT_GE(est, 0.96 * f->lipschitz()) << f->describe();
  }
  EXPECT_EQ(estimate_lipschitz(ConstantField(2), b), 0.0);
}

TEST(Combinators, MinMaxClamp) {
  auto a = std::make_shared<ConstantField>(0.3);
  auto f1 = std::make_shared<PaperF1Field>();
  MinField mn({a, f1});
  MaxField mx({a, f1});
  ClampField cl(f1, 0.2, 0.5);
  for (double x : {0.0, 3.0, 5.0, 7.5, 10.0}) {
    const Point2 p{x, 5.0};
    EXPECT_EQ(mn(p), std::min(0.3, (*f1)(p)));
    EXPECT_EQ(mx(p), std::max(0.3, (*f1)(p)));
    EXPECT_EQ(cl(p), std::clamp((*f1)(p), 0.2, 0.5));
  }
  EXPECT_DOUBLE_EQ(mn.lipschitz(), f1->lipschitz());
  EXPECT_DOUBLE_EQ(cl.lipschitz(), f1->lipschitz());
  EXPECT_THROW(ClampField(f1, 0.5, 0.2), Error);
  EXPECT_THROW(MinField({}), Error);
  ScaledField s(2, f1);
  EXPECT_DOUBLE_EQ(s({0, 0}), 2.2);
  EXPECT_DOUBLE_EQ(s.lipschitz(), 0.2 * std::sqrt(2.0));
}

TEST(GridField, BilinearExactOnLinearAndClampedOutside) {
  Grid g;
  g.nx = 7; g.ny = 5; g.x0 = -3; g.y0 = 2; g.dx = 0.5; g.dy = 2;
  g.v.resize(g.nx * g.ny);
  auto lin = [](Point2 p) { return 10 + 0.3 * p.x - 0.2 * p.y; };
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i) g.at(i, j) = lin(g.center(i, j));
  GridField f(g);
  const Point2 c0 = g.center(0, 0), c1 = g.center(g.nx - 1, g.ny - 1);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> ux(c0.x, c1.x), uy(c0.y, c1.y);
  for (int k = 0; k < 500; ++k) {
    const Point2 p{ux(rng), uy(rng)};
    EXPECT_NEAR(f(p), lin(p), 1e-12);
  }
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i) EXPECT_NEAR(f(g.center(i, j)), g.at(i, j), 1e-12);
  // Outside: clamped to the edge cells.
  EXPECT_NEAR(f({c0.x - 100, c0.y - 100}), g.at(0, 0), 1e-12);
  EXPECT_NEAR(f({c1.x + 100, c0.y}), g.at(g.nx - 1, 0), 1e-12);
  EXPECT_NEAR(f({0.1, c1.y + 7}), lin({0.1, c1.y}), 1e-12);
  EXPECT_NEAR(f.lipschitz(), std::hypot(0.3, 0.2), 1e-12);
  EXPECT_LE(estimate_lipschitz(f, g.extent(), 101), f.lipschitz() * (1 + 1e-9));
}

TEST(GridField, SingleCellAndInvalidCells) {
  Grid g;
  g.nx = 1; g.ny = 1; g.v = {2.5};
  GridField one(g);
  EXPECT_EQ(one({-5, 9}), 2.5);
  EXPECT_EQ(one.lipschitz(), 0.0);

  Grid h;
  h.nx = 3; h.ny = 2; h.x0 = 100; h.y0 = 200; h.dx = 10; h.dy = 10;
  h.v = {1, 1, 1, 1, std::nan(""), 1};
  try {
    GridField bad(h);
    FAIL() << "NaN cell accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidSpacing);
    EXPECT_NE(std::string(e.what()).find("cell (1, 1) at (115, 215)"), std::string::npos) << e.what();
  }
  h.v[4] = 0;
  EXPECT_THROW(GridField{h}, Error);
  h.v[4] = std::numeric_limits<double>::infinity();
  EXPECT_THROW(GridField{h}, Error);
}

TEST(Checks, CheckPositiveNamesTheFirstBadSample) {
  const Box2 b = box(0, 0, 10, 10);
  auto all = [](Point2) { return true; };
  EXPECT_NO_THROW(check_positive(PaperF1Field(), b, 33, all));
  auto f = make_spacing("x - 5");  // <= 0 for x <= 5
  try {
    check_positive(*f, b, 11, all);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidSpacing);
    EXPECT_EQ(std::string(e.what()), "spacing f(x,y) = -5 at (0, 0) is not a positive finite number");
  }
  // Outside samples are ignored: restricting to x > 5 makes the field valid.
  EXPECT_NO_THROW(check_positive(*f, b, 11, [](Point2 p) { return p.x > 5.5; }));
  auto g = make_spacing("sqrt(x - 7)");  // NaN for x < 7
  try {
    check_positive(*g, b, 11, [](Point2 p) { return p.y >= 3; });
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "spacing f(x,y) = nan at (0, 3) is not a positive finite number");
  }
  auto z = make_spacing("1/(x-3)");  // +inf at x = 3, negative left of it
  EXPECT_THROW(check_positive(*z, box(3, 0, 4, 1), 3, all), Error);
}

TEST(Checks, ExpectedTriangles) {
  const Box2 b = box(0, 0, 10, 10);
  // Constant h: area / (3 sqrt(3)/4 h^2).
  const double n = expected_triangles(ConstantField(0.5), b, nullptr, 64);
  EXPECT_NEAR(n, 100.0 / (3 * std::sqrt(3.0) / 4 * 0.25), 1e-9);
  EXPECT_NEAR(kTrianglesPerCircumradiusSquared, 4.0 / (3 * std::sqrt(3.0)), 1e-15);
  // Half the domain.
  const double half = expected_triangles(ConstantField(0.5), b, [](Point2 p) { return p.x < 5; }, 64);
  EXPECT_NEAR(half, n / 2, 1e-9);
  // paper-f1 on [0,10]^2 against a fine reference.
  const double coarse = expected_triangles(PaperF1Field(), b, nullptr, 128);
  const double fine = expected_triangles(PaperF1Field(), b, nullptr, 1024);
  EXPECT_NEAR(coarse / fine, 1.0, 1e-3);
  EXPECT_THROW(expected_triangles(*make_spacing("x-5"), b, nullptr, 8), Error);
}

}  // namespace
}  // namespace fdr::sizing
