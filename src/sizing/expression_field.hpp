// ExpressionField: a spacing function given as a muparser expression in x and y.
#pragma once
#include <memory>
#include "sizing/sizing_field.hpp"

namespace fdr::sizing {

// Variables: x, y (local frame, metres). Operators + - * / ^ and comparisons, the ternary
// "c ? a : b", functions abs sin cos tan asin acos atan sinh cosh tanh sqrt exp log (natural)
// ln log10 log2 sign rint, min/max/sum/avg with one or more arguments, constants _pi and _e.
// The preset names paper-f1 and paper-f2 may appear as operands (see make_spacing.hpp);
// they are evaluated natively.
// Parse errors throw Error(kUsage, "spacing expression '<expr>': <message> at position N"),
// N counting characters from 1 (one past the end for a premature end).
// Not thread-safe (one muparser instance, mutable variables); deterministic.
class ExpressionField final : public SizingField {
 public:
  explicit ExpressionField(const std::string& expr);
  ~ExpressionField() override;
  ExpressionField(const ExpressionField&) = delete;
  ExpressionField& operator=(const ExpressionField&) = delete;

  double operator()(Point2 p) const override;
  std::string describe() const override { return "expr: " + expr_; }
  const std::string& expression() const { return expr_; }

 private:
  struct Impl;
  std::string expr_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fdr::sizing
