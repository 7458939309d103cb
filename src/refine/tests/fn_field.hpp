// A spacing function from a lambda (refine tests; was in cdt/tests, which may not see sizing).
#pragma once
#include <functional>
#include <string>
#include "sizing/sizing_field.hpp"

namespace fdr::testing {

struct FnField : sizing::SizingField {
  std::function<double(Point2)> fn;
  explicit FnField(std::function<double(Point2)> f) : fn(std::move(f)) {}
  double operator()(Point2 p) const override { return fn(p); }
  std::string describe() const override { return "test"; }
};

}  // namespace fdr::testing
