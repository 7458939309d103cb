// A spacing function from a lambda (refine tests; was in cdt/tests, which may not see sizing).
#pragma once
#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include "mesh/triangulation.hpp"
#include "base/triangle_geometry.hpp"
#include "predicates/predicates.hpp"
#include "sizing/sizing_field.hpp"

namespace fdr::testing {

struct FnField : sizing::SizingField {
  std::function<double(Point2)> fn;
  double lip = -1;  // a Lipschitz constant the test knows, or negative
  explicit FnField(std::function<double(Point2)> f, double lipschitz = -1) : fn(std::move(f)), lip(lipschitz) {}
  double operator()(Point2 p) const override { return fn(p); }
  double lipschitz() const override { return lip; }
  bool thread_safe() const override { return true; }  // the tests' lambdas are pure
  std::string describe() const override { return "test"; }
};

// Largest R / f(c) over the live triangles (the FDR bound every refined mesh must keep).
inline double max_r_over_f(const mesh::Triangulation& T, const sizing::SizingField& f) {
  double worst = 0;
  for (TriangleId t = 0; t < T.num_slots(); ++t) {
    if (T.dead(t)) continue;
    double r2;
    const Point2 c = geom::circumcentre(T.point(T.corner(t, 0)), T.point(T.corner(t, 1)), T.point(T.corner(t, 2)), &r2);
    worst = std::max(worst, std::sqrt(r2) / f(c));
  }
  return worst;
}

}  // namespace fdr::testing
