// make_spacing: parses a spacing spec into a constant, native preset or expression field.
#include "sizing/make_spacing.hpp"

#include <charconv>
#include <cmath>
#include <optional>

#include "base/error.hpp"
#include "sizing/spec_text.hpp"
#include "sizing/expression_field.hpp"
#include "sizing/fields.hpp"

namespace fdr::sizing {

namespace {

using spec_text::parse_number;
using spec_text::require_positive;
using spec_text::trim;

// 1 for paper-f1, 2 for paper-f2, 0 otherwise.
int preset_id(const std::string& s) {
  if (s == "paper-f1") return 1;
  if (s == "paper-f2") return 2;
  return 0;
}

SizingPtr make_preset(int id, double k) {
  if (id == 1) return std::make_shared<PaperF1Field>(k);
  return std::make_shared<PaperF2Field>(k);
}

}  // namespace

SizingPtr make_spacing(const std::string& spec_in) {
  const std::string spec = trim(spec_in);
  if (spec.empty()) throw Error(ExitCode::kUsage, "spacing: empty specification");
  if (auto v = parse_number(spec)) {
    require_positive(*v, spec);
    return std::make_shared<ConstantField>(*v);
  }
  if (int id = preset_id(spec)) return make_preset(id, 1.0);
  // "K*preset" or "preset*K": exactly one '*' with a number on one side, a preset on the other.
  if (const auto star = spec.find('*'); star != std::string::npos && spec.find('*', star + 1) == std::string::npos) {
    const std::string a = trim(spec.substr(0, star)), b = trim(spec.substr(star + 1));
    std::optional<double> k;
    int id = 0;
    if ((id = preset_id(b)) != 0) k = parse_number(a);
    else if ((id = preset_id(a)) != 0) k = parse_number(b);
    if (id != 0 && k) {
      require_positive(*k, spec);
      return make_preset(id, *k);
    }
  }
  return std::make_shared<ExpressionField>(spec);
}

}  // namespace fdr::sizing
