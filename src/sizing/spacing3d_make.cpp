// make_spacing3: constant, native lifted paper functions, or an expression in x, y, z.
#include "sizing/spacing3d_make.hpp"

#include <charconv>
#include <cmath>
#include <optional>

#include "base/error.hpp"
#include "sizing/spec_text.hpp"
#include "sizing/fields.hpp"
#include "sizing/spacing3d_expression.hpp"

namespace fdr::sizing {

double PaperF1Field3::operator()(Point3 p) const {
  return k_ * ((std::abs(p.x - 5) + std::abs(p.y - 5) + std::abs(p.z - 5)) * 0.1 + 0.1);
}
double PaperF1Field3::lipschitz() const { return k_ * 0.1 * std::sqrt(3.0); }
std::string PaperF1Field3::describe() const {
  return (k_ == 1 ? std::string() : format_number(k_) + "*") + "paper-f1 (3D)";
}

double PaperF2Field3::operator()(Point3 p) const {
  const double s = p.x + p.y + p.z;
  return k_ * (std::abs(std::sin(s)) + std::abs(std::cos(s))) * 0.1;
}
double PaperF2Field3::lipschitz() const { return k_ * 0.1 * std::sqrt(3.0); }
double PaperF2Field3::upper_bound() const { return k_ * 0.1 * std::sqrt(2.0); }
std::string PaperF2Field3::describe() const {
  return (k_ == 1 ? std::string() : format_number(k_) + "*") + "paper-f2 (3D)";
}

namespace {

using spec_text::parse_number;
using spec_text::require_positive;
using spec_text::trim;

SizingPtr3 make_preset(const std::string& name, double k) {
  if (name == "paper-f1") return std::make_shared<PaperF1Field3>(k);
  if (name == "paper-f2") return std::make_shared<PaperF2Field3>(k);
  return nullptr;
}

}  // namespace

SizingPtr3 make_spacing3(const std::string& spec_in) {
  const std::string spec = trim(spec_in);
  if (spec.empty()) throw Error(ExitCode::kUsage, "spacing: empty specification");
  if (auto v = parse_number(spec)) {
    require_positive(*v, spec);
    return std::make_shared<ConstantField3>(*v);
  }
  if (auto f = make_preset(spec, 1.0)) return f;
  if (const auto star = spec.find('*'); star != std::string::npos && spec.find('*', star + 1) == std::string::npos) {
    const std::string a = trim(spec.substr(0, star)), b = trim(spec.substr(star + 1));
    for (const auto& [name, number] : {std::pair{b, a}, std::pair{a, b}}) {
      const auto k = parse_number(number);
      if (!k || !make_preset(name, 1.0)) continue;
      require_positive(*k, spec);
      return make_preset(name, *k);
    }
  }
  return std::make_shared<ExpressionField3>(spec);
}

}  // namespace fdr::sizing
