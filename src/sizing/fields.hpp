// Analytic spacing fields (constant, the FDR paper's Figure 2 presets) and combinators.
#pragma once
#include <cmath>
#include <vector>
#include "sizing/sizing_field.hpp"

namespace fdr::sizing {

// f(p) = h everywhere; Lipschitz constant 0.
class ConstantField final : public SizingField {
 public:
  explicit ConstantField(double h) : h_(h) {}
  double operator()(Point2) const override { return h_; }
  double lipschitz() const override { return 0.0; }
  bool thread_safe() const override { return true; }
  double upper_bound() const override { return h_; }
  std::string describe() const override;
  double value() const { return h_; }

 private:
  double h_;
};

// paper-f1 scaled by k: f(x,y) = k * ((|x-5| + |y-5|) * 0.1 + 0.1)  (FDR paper, Figure 2 top).
// Lipschitz: |grad| = k*0.1*|(+-1, +-1)| = k*0.1*sqrt(2) wherever differentiable.
class PaperF1Field final : public SizingField {
 public:
  explicit PaperF1Field(double scale = 1.0) : k_(scale) {}
  double operator()(Point2 p) const override {
    return k_ * ((std::abs(p.x - 5.0) + std::abs(p.y - 5.0)) * 0.1 + 0.1);
  }
  double lipschitz() const override;
  bool thread_safe() const override { return true; }
  std::string describe() const override;

 private:
  double k_;
};

// paper-f2 scaled by k: f(x,y) = k * (|sin(x+y)| + |cos(x+y)|) * 0.1  (FDR paper, Figure 2 bottom).
// Lipschitz: with u = x+y, g(u) = |sin u| + |cos u| has |g'(u)| = |cos u -+ sin u| <= 1 inside
// each quadrant (the extremes 1 are reached at the kinks), and |grad u| = sqrt(2), so the
// constant is k*0.1*sqrt(2) (not 2*sqrt(2)*0.1). Range: k*[0.1, 0.1*sqrt(2)].
class PaperF2Field final : public SizingField {
 public:
  explicit PaperF2Field(double scale = 1.0) : k_(scale) {}
  double operator()(Point2 p) const override {
    const double u = p.x + p.y;
    return k_ * ((std::abs(std::sin(u)) + std::abs(std::cos(u))) * 0.1);
  }
  double lipschitz() const override;
  bool thread_safe() const override { return true; }
  std::string describe() const override;

 private:
  double k_;
};

// k * f(p); Lipschitz k * L(f).
class ScaledField final : public SizingField {
 public:
  ScaledField(double k, SizingPtr f);
  double operator()(Point2 p) const override { return k_ * (*f_)(p); }
  double lipschitz() const override;
  bool thread_safe() const override { return f_->thread_safe(); }
  double upper_bound() const override { return std::abs(k_) * f_->upper_bound(); }
  std::string describe() const override;

 private:
  double k_;
  SizingPtr f_;
};

// min_i f_i(p). The minimum of L_i-Lipschitz functions is max_i L_i-Lipschitz.
class MinField final : public SizingField {
 public:
  explicit MinField(std::vector<SizingPtr> fields);  // throws kInternal when empty
  double operator()(Point2 p) const override;
  double lipschitz() const override;
  bool thread_safe() const override;
  double upper_bound() const override;
  std::string describe() const override;

 private:
  std::vector<SizingPtr> f_;
};

// max_i f_i(p); Lipschitz max_i L_i.
class MaxField final : public SizingField {
 public:
  explicit MaxField(std::vector<SizingPtr> fields);  // throws kInternal when empty
  double operator()(Point2 p) const override;
  double lipschitz() const override;
  bool thread_safe() const override;
  double upper_bound() const override;
  std::string describe() const override;

 private:
  std::vector<SizingPtr> f_;
};

// min(max(f(p), hmin), hmax); clamping does not increase the Lipschitz constant.
// Throws kUsage unless 0 < hmin <= hmax (hmax may be +inf).
class ClampField final : public SizingField {
 public:
  ClampField(SizingPtr f, double hmin, double hmax);
  double operator()(Point2 p) const override;
  double lipschitz() const override { return f_->lipschitz(); }
  bool thread_safe() const override { return f_->thread_safe(); }
  double upper_bound() const override;
  std::string describe() const override;

 private:
  SizingPtr f_;
  double hmin_, hmax_;
};

// f given in world coordinates, evaluated in a local frame: g(p) = f(p + origin).
class ShiftedField final : public SizingField {
 public:
  ShiftedField(SizingPtr f, Point2 origin) : f_(std::move(f)), o_(origin) {}
  // Scalar additions: a vectorized pair spilled through the stack made a store-forwarding stall
  // on every evaluation (same values).
  __attribute__((optimize("no-tree-slp-vectorize"))) double operator()(Point2 p) const override {
    return (*f_)({p.x + o_.x, p.y + o_.y});
  }
  double lipschitz() const override { return f_->lipschitz(); }
  bool thread_safe() const override { return f_->thread_safe(); }
  double upper_bound() const override { return f_->upper_bound(); }
  std::string describe() const override { return f_->describe(); }

 private:
  SizingPtr f_;
  Point2 o_;
};

// Formats a double for messages and descriptions (shortest round-trip form).
std::string format_number(double v);

}  // namespace fdr::sizing
