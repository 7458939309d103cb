// Sampled checks on spacing fields: Lipschitz estimate, positivity, expected triangle count.
#include "sizing/field_checks.hpp"

#include <cmath>
#include <vector>

#include "base/error.hpp"
#include "sizing/fields.hpp"

namespace fdr::sizing {

namespace {

struct Lattice {
  int n;
  double x0, y0, sx, sy;
  Point2 at(int i, int j) const { return {x0 + sx * i, y0 + sy * j}; }
};

Lattice lattice(Box2 box, int n) {
  n = std::max(n, 2);
  return {n, box.lo.x, box.lo.y, box.width() / (n - 1), box.height() / (n - 1)};
}

[[noreturn]] void throw_bad_value(double v, Point2 p) {
  throw Error(ExitCode::kInvalidSpacing, "spacing f(x,y) = " + format_number(v) + " at (" + format_number(p.x) +
                                             ", " + format_number(p.y) + ") is not a positive finite number");
}

}  // namespace

double estimate_lipschitz(const SizingField& f, Box2 box, int n) {
  if (box.empty()) return 0.0;
  const Lattice L = lattice(box, n);
  std::vector<double> prev(L.n), cur(L.n);
  double best = 0.0;
  auto slope = [&](double a, double b, double d) {
    if (std::isfinite(a) && std::isfinite(b) && d > 0) best = std::max(best, std::abs(a - b) / d);
  };
  const double dxy = std::hypot(L.sx, L.sy);
  // Why two rows only: each sample is compared with its left, lower, and both lower diagonals.
  for (int j = 0; j < L.n; ++j) {
    for (int i = 0; i < L.n; ++i) cur[i] = f(L.at(i, j));
    for (int i = 0; i < L.n; ++i) {
      if (i > 0) slope(cur[i], cur[i - 1], L.sx);
      if (j > 0) {
        slope(cur[i], prev[i], L.sy);
        if (i > 0) slope(cur[i], prev[i - 1], dxy);
        if (i + 1 < L.n) slope(cur[i], prev[i + 1], dxy);
      }
    }
    std::swap(prev, cur);
  }
  return best;
}

void check_positive(const SizingField& f, Box2 box, int n, const std::function<bool(Point2)>& inside) {
  if (box.empty()) return;
  const Lattice L = lattice(box, n);
  for (int j = 0; j < L.n; ++j)
    for (int i = 0; i < L.n; ++i) {
      const Point2 p = L.at(i, j);
      if (inside && !inside(p)) continue;
      const double v = f(p);
      if (!(v > 0) || !std::isfinite(v)) throw_bad_value(v, p);
    }
}

double expected_triangles(const SizingField& f, Box2 box, const std::function<bool(Point2)>& inside, int n) {
  if (box.empty()) return 0.0;
  n = std::max(n, 1);
  const double cx = box.width() / n, cy = box.height() / n;
  double sum = 0.0;
  for (int j = 0; j < n; ++j) {
    double row = 0.0;  // per-row partial sums keep the accumulation error small
    for (int i = 0; i < n; ++i) {
      const Point2 p{box.lo.x + (i + 0.5) * cx, box.lo.y + (j + 0.5) * cy};
      if (inside && !inside(p)) continue;
      const double v = f(p);
      if (!(v > 0) || !std::isfinite(v)) throw_bad_value(v, p);
      row += 1.0 / (v * v);
    }
    sum += row;
  }
  return kTrianglesPerCircumradiusSquared * sum * cx * cy;
}

}  // namespace fdr::sizing
