// ExpressionField3: a 3D spacing function given as a muparser expression in x, y and z.
#pragma once
#include <memory>
#include <mutex>
#include <string>
#include <vector>
#include "sizing/spacing3d.hpp"

namespace fdr::sizing {

// Variables x, y, z (mesh coordinates); the operators, functions and constants of the 2D
// ExpressionField (expression_field.hpp), e.g. the paper's test functions lifted to 3D:
//   (abs(x-5)+abs(y-5)+abs(z-5))*0.1+0.1   and   (abs(sin(x+y+z))+abs(cos(x+y+z)))*0.1
// Parse errors throw Error(kUsage, "spacing expression '<expr>': <message> at position N"), N
// counting characters from 1. Evaluation errors throw Error(kInvalidSpacing) naming the point.
// Thread-safe: each call takes a parsed evaluator from a pool (a new one when all are busy), so
// threads never share muparser's variables; every evaluator gives the same bits.
class ExpressionField3 final : public SizingField3 {
 public:
  explicit ExpressionField3(const std::string& expr);
  ~ExpressionField3() override;
  ExpressionField3(const ExpressionField3&) = delete;
  ExpressionField3& operator=(const ExpressionField3&) = delete;

  double operator()(Point3 p) const override;
  std::string describe() const override { return "expr: " + expr_; }
  const std::string& expression() const { return expr_; }

  struct Evaluator;

 private:
  std::string expr_;
  mutable std::mutex pool_mutex_;
  mutable std::vector<std::unique_ptr<Evaluator>> idle_;
};

}  // namespace fdr::sizing
