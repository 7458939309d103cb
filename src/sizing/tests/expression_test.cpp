// Tests of ExpressionField (muparser) and the make_spacing spec grammar.
#include <gtest/gtest.h>

#include <cmath>

#include "base/error.hpp"
#include "sizing/expression_field.hpp"
#include "sizing/fields.hpp"
#include "sizing/make_spacing.hpp"

namespace fdr::sizing {
namespace {

TEST(Expression, AllFunctions) {
  const Point2 p{0.7, -1.3};
  const double x = p.x, y = p.y;
  struct Case {
    const char* expr;
    double want;
  } cases[] = {
      {"x + y", x + y},           {"x - y", x - y},
      {"x * y", x * y},           {"x / y", x / y},
      {"x ^ 2 + y^3", x * x + y * y * y},
      {"abs(y)", std::abs(y)},    {"sin(x)", std::sin(x)},
      {"cos(y)", std::cos(y)},    {"tan(x)", std::tan(x)},
      {"sqrt(x)", std::sqrt(x)},  {"exp(y)", std::exp(y)},
      {"log(x)", std::log(x)},    {"min(x, y)", std::min(x, y)},
      {"max(x, y)", std::max(x, y)},
      {"min(max(x, 0.1), 0.5)", 0.5},
      {"-x + 2*(y - 1)", -x + 2 * (y - 1)},
      {"x < 1 ? 3 : 4", 3},
  };
  for (const auto& c : cases) {
    ExpressionField f(c.expr);
    EXPECT_NEAR(f(p), c.want, 1e-14 * std::max(1.0, std::abs(c.want))) << c.expr;
    EXPECT_EQ(f.describe(), std::string("expr: ") + c.expr);
  }
}

TEST(Expression, DeterministicAndVariablesFollowThePoint) {
  ExpressionField f("0.1*abs(x-5)+0.02*y");
  EXPECT_DOUBLE_EQ(f({7, 10}), 0.1 * 2 + 0.2);
  EXPECT_DOUBLE_EQ(f({5, 0}), 0.0);
  const double a = f({1.234, 5.678});
  f({9, 9});
  EXPECT_EQ(f({1.234, 5.678}), a);
  EXPECT_LT(f.lipschitz(), 0);  // unknown
}

std::string error_of(const std::string& expr) {
  try {
    ExpressionField f(expr);
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kUsage);
    return e.what();
  }
  return "no error";
}

TEST(Expression, ErrorsNameThePosition) {
  EXPECT_EQ(error_of("x+z"), "spacing expression 'x+z': Unexpected token \"z\" at position 3");
  EXPECT_EQ(error_of("foo(1)"), "spacing expression 'foo(1)': Unexpected token \"foo\" at position 1");
  const std::string e1 = error_of("sqrt(4)+");
  EXPECT_NE(e1.find("spacing expression 'sqrt(4)+': Unexpected end of expression at position 9"), std::string::npos)
      << e1;
  const std::string e2 = error_of("2*(3");
  EXPECT_NE(e2.find("spacing expression '2*(3': Missing parenthesis at position 5"), std::string::npos) << e2;
  const std::string e3 = error_of("1+x, 2");
  EXPECT_NE(e3.find("several comma-separated results, expected one at position 4"), std::string::npos) << e3;
  EXPECT_NE(error_of("").find("spacing expression '':"), std::string::npos);
}

TEST(Spec, ConstantPresetScaledAndExpression) {
  auto c = make_spacing(" 2.5 ");
  EXPECT_EQ((*c)({3, 4}), 2.5);
  EXPECT_EQ(c->lipschitz(), 0.0);
  EXPECT_NE(dynamic_cast<const ConstantField*>(c.get()), nullptr);
  EXPECT_EQ(make_spacing("1e-3")->operator()({0, 0}), 1e-3);

  auto f1 = make_spacing("paper-f1");
  EXPECT_NE(dynamic_cast<const PaperF1Field*>(f1.get()), nullptr);
  auto f2 = make_spacing("paper-f2");
  EXPECT_NE(dynamic_cast<const PaperF2Field*>(f2.get()), nullptr);

  for (const char* s : {"0.025*paper-f1", "paper-f1*0.025", " 0.025 * paper-f1 "}) {
    auto k = make_spacing(s);
    ASSERT_NE(dynamic_cast<const PaperF1Field*>(k.get()), nullptr) << s;
    EXPECT_DOUBLE_EQ((*k)({1, 2}), 0.025 * ((4 + 3) * 0.1 + 0.1)) << s;
    EXPECT_DOUBLE_EQ(k->lipschitz(), 0.025 * 0.1 * std::sqrt(2.0));
  }
  auto k2 = make_spacing("3*paper-f2");
  ASSERT_NE(dynamic_cast<const PaperF2Field*>(k2.get()), nullptr);
  EXPECT_DOUBLE_EQ((*k2)({0.3, 0.4}), 3 * PaperF2Field()({0.3, 0.4}));

  // Presets inside an expression are evaluated natively and can be combined.
  auto m = make_spacing("min(paper-f1, 0.3)");
  ASSERT_NE(dynamic_cast<const ExpressionField*>(m.get()), nullptr);
  EXPECT_DOUBLE_EQ((*m)({5, 5}), 0.1);
  EXPECT_DOUBLE_EQ((*m)({0, 0}), 0.3);
  auto sum = make_spacing("paper-f1+paper-f2-0.05");
  EXPECT_DOUBLE_EQ((*sum)({1, 2}), PaperF1Field()({1, 2}) + PaperF2Field()({1, 2}) - 0.05);
  // Expression: x-paper-f1 is x minus the preset.
  EXPECT_DOUBLE_EQ((*make_spacing("x-paper-f1"))({8, 5}), 8 - 0.4);
  EXPECT_EQ(make_spacing("0.1*x+1")->operator()({10, 0}), 2.0);
}

TEST(Spec, Errors) {
  auto code = [](const std::string& s) {
    try {
      make_spacing(s);
    } catch (const Error& e) {
      return e.code();
    }
    return ExitCode::kOk;
  };
  EXPECT_EQ(code(""), ExitCode::kUsage);
  EXPECT_EQ(code("0"), ExitCode::kInvalidSpacing);
  EXPECT_EQ(code("-2"), ExitCode::kInvalidSpacing);
  EXPECT_EQ(code("inf"), ExitCode::kInvalidSpacing);
  EXPECT_EQ(code("-1*paper-f1"), ExitCode::kInvalidSpacing);
  EXPECT_EQ(code("paper-f3"), ExitCode::kUsage);
  EXPECT_EQ(code("paper-f1 +"), ExitCode::kUsage);
  try {
    make_spacing("min(paper-f1, q)");
  } catch (const Error& e) {
    // The original text and a position in it are reported, not the substituted one.
    EXPECT_EQ(std::string(e.what()), "spacing expression 'min(paper-f1, q)': Unexpected token \"q\" at position 15");
  }
}

}  // namespace
}  // namespace fdr::sizing
