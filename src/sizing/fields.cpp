// Analytic spacing fields and min/max/clamp combinators.
#include "sizing/fields.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

#include "base/error.hpp"

namespace fdr::sizing {

std::string format_number(double v) {
  if (std::isnan(v)) return "nan";  // to_chars would print the sign bit ("-nan")
  char buf[64];
  auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::string ConstantField::describe() const { return "constant " + format_number(h_); }

double PaperF1Field::lipschitz() const { return std::abs(k_) * 0.1 * std::sqrt(2.0); }
std::string PaperF1Field::describe() const {
  return k_ == 1.0 ? "paper-f1" : format_number(k_) + "*paper-f1";
}

double PaperF2Field::lipschitz() const { return std::abs(k_) * 0.1 * std::sqrt(2.0); }
std::string PaperF2Field::describe() const {
  return k_ == 1.0 ? "paper-f2" : format_number(k_) + "*paper-f2";
}

ScaledField::ScaledField(double k, SizingPtr f) : k_(k), f_(std::move(f)) {
  if (!f_) throw Error(ExitCode::kInternal, "ScaledField: null field");
}
double ScaledField::lipschitz() const {
  const double l = f_->lipschitz();
  return l < 0 ? -1.0 : std::abs(k_) * l;
}
std::string ScaledField::describe() const { return format_number(k_) + "*(" + f_->describe() + ")"; }

namespace {
void require_nonempty(const std::vector<SizingPtr>& f, const char* what) {
  if (f.empty()) throw Error(ExitCode::kInternal, std::string(what) + ": no fields given");
  for (const auto& p : f)
    if (!p) throw Error(ExitCode::kInternal, std::string(what) + ": null field");
}
double max_lipschitz(const std::vector<SizingPtr>& f) {
  double l = 0;
  for (const auto& p : f) {
    const double li = p->lipschitz();
    if (li < 0) return -1.0;
    l = std::max(l, li);
  }
  return l;
}
std::string join(const char* name, const std::vector<SizingPtr>& f) {
  std::string s = std::string(name) + "(";
  for (std::size_t i = 0; i < f.size(); ++i) s += (i ? ", " : "") + f[i]->describe();
  return s + ")";
}
}  // namespace

MinField::MinField(std::vector<SizingPtr> fields) : f_(std::move(fields)) { require_nonempty(f_, "MinField"); }
double MinField::operator()(Point2 p) const {
  double m = std::numeric_limits<double>::infinity();
  for (const auto& f : f_) {
    const double v = (*f)(p);
    if (std::isnan(v)) return v;  // an invalid value must reach the positivity check
    m = std::min(m, v);
  }
  return m;
}
double MinField::lipschitz() const { return max_lipschitz(f_); }
double MinField::upper_bound() const {
  double u = std::numeric_limits<double>::infinity();
  for (const auto& g : f_) u = std::min(u, g->upper_bound());
  return u;
}
bool MinField::thread_safe() const {
  return std::all_of(f_.begin(), f_.end(), [](const SizingPtr& g) { return g->thread_safe(); });
}
std::string MinField::describe() const { return join("min", f_); }

MaxField::MaxField(std::vector<SizingPtr> fields) : f_(std::move(fields)) { require_nonempty(f_, "MaxField"); }
double MaxField::operator()(Point2 p) const {
  double m = -std::numeric_limits<double>::infinity();
  for (const auto& f : f_) {
    const double v = (*f)(p);
    if (std::isnan(v)) return v;
    m = std::max(m, v);
  }
  return m;
}
double MaxField::lipschitz() const { return max_lipschitz(f_); }
double MaxField::upper_bound() const {
  double u = 0;
  for (const auto& g : f_) u = std::max(u, g->upper_bound());
  return u;
}
bool MaxField::thread_safe() const {
  return std::all_of(f_.begin(), f_.end(), [](const SizingPtr& g) { return g->thread_safe(); });
}
std::string MaxField::describe() const { return join("max", f_); }

ClampField::ClampField(SizingPtr f, double hmin, double hmax) : f_(std::move(f)), hmin_(hmin), hmax_(hmax) {
  if (!f_) throw Error(ExitCode::kInternal, "ClampField: null field");
  if (!(hmin > 0) || !std::isfinite(hmin) || !(hmin <= hmax))
    throw Error(ExitCode::kUsage, "spacing clamp: need 0 < hmin <= hmax, got hmin = " + format_number(hmin) +
                                      ", hmax = " + format_number(hmax));
}
double ClampField::upper_bound() const { return std::min(hmax_, std::max(f_->upper_bound(), hmin_)); }
double ClampField::operator()(Point2 p) const {
  const double v = (*f_)(p);
  if (std::isnan(v)) return v;
  return std::min(std::max(v, hmin_), hmax_);
}
std::string ClampField::describe() const {
  return "clamp(" + f_->describe() + ", " + format_number(hmin_) + ", " + format_number(hmax_) + ")";
}

}  // namespace fdr::sizing
