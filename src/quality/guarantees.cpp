// The FDR paper's Section 4 bounds for given (alpha, B), the theorem table against the measured
// figures, and the report's fixed-width histograms.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include "base/triangle_geometry.hpp"
#include "quality/report.hpp"

namespace fdr::quality {

void Histogram::add(double v) {
  if (counts.empty()) return;
  // The floor of b without a libm call: truncation equals it for b >= 0, and below 0 (or NaN) the
  // first bin takes the value either way.
  const double b = (v - lo) / width;
  const std::size_t i = !(b >= 0) ? 0 : b >= static_cast<double>(counts.size()) ? counts.size() - 1 : static_cast<std::size_t>(b);
  ++counts[i];
}

Guarantees compute_guarantees(double alpha, double bound_B, std::optional<double> D) {
  Guarantees g;
  if (!std::isfinite(alpha) || alpha < 0) {
    g.note = "no guarantee: the Lipschitz constant alpha of f is unknown";
    return g;
  }
  if (!std::isfinite(bound_B) || bound_B <= 0) {
    g.note = "no guarantee: the bound B must be positive";
    return g;
  }
  const double ab = alpha * bound_B;
  if (ab >= 1) {
    char buf[160];
    std::snprintf(buf, sizeof buf,
                  "no guarantee: alpha*B = %.6g >= 1 (Section 4 requires B < 1/alpha)", ab);
    g.note = buf;
    return g;
  }
  const double s = 2.0 * std::sqrt(2.0) + 3.0 * ab;
  g.valid = true;
  g.beta_B = bound_B / s;
  g.beta = g.beta_B;
  // Section 4: beta = min(B/(2 sqrt(2) + 3 alpha B), D/(2 + alpha D)), D from nn_Mc >= D f. An
  // input with features finer than f (two coast vertices closer than f, a thin spit between two
  // waters) has a small D, and the bounds below are then the weaker ones the paper proves for it.
  if (D && *D >= 0 && std::isfinite(*D)) {
    g.beta_D = *D / (2.0 + alpha * *D);
    g.beta = std::min(g.beta_B, *g.beta_D);
  }
  // Theorem 4.3: R/l <= B / (2 beta (1 - alpha B)); the smallest angle theta has sin(theta) = l/(2R)
  // at the shortest edge.
  g.R_over_l_max = g.beta > 0 ? bound_B / (2.0 * g.beta * (1.0 - ab)) : std::numeric_limits<double>::infinity();
  g.min_angle_deg = g.beta > 0 ? std::asin(std::min(1.0, 0.5 / g.R_over_l_max)) * geom::kDegPerRad : 0.0;
  g.nn_over_f_min = 2.0 * g.beta / (1.0 + alpha * g.beta);
  g.el_over_f_max = 2.0 * bound_B / (1.0 + ab);
  g.el_over_f_max_corrected = 2.0 * bound_B / (1.0 - ab);
  if (!g.beta_D)
    g.note = "2D, beta = B/(2*sqrt(2)+3*alpha*B), assuming beta <= D/(2+alpha*D) (Section 4; D unknown)";
  else if (g.beta < g.beta_B)
    g.note = "2D, beta = D/(2+alpha*D) < B/(2*sqrt(2)+3*alpha*B): the conforming mesh has vertices nearer than f "
             "(input features finer than the spacing; D below)";
  else
    g.note = "2D, beta = B/(2*sqrt(2)+3*alpha*B) <= D/(2+alpha*D) (Section 4; D of the conforming mesh below)";
  return g;
}

std::vector<TheoremCheck> theorem_checks(const QualityReport& r) {
  std::vector<TheoremCheck> rows;
  auto add = [&](const char* key, const char* label, bool upper, double bound, std::optional<double> meas,
                 bool counts = true) {
    std::optional<bool> holds;
    if (meas) holds = upper ? *meas <= bound : *meas >= bound;  // NaN measured: false
    rows.push_back({key, label, upper, bound, meas, holds, counts});
  };
  // The refiner's invariant, the hypothesis of every theorem below (needs f).
  if (r.max_R_over_f) add("fdr_R_over_f_max", "R/f(c) max (FDR, B)", true, r.bound_B, r.max_R_over_f);
  const Guarantees& g = r.guarantees;
  if (!g.valid) return rows;
  add("theorem_4_3_R_over_l_max", "R/l max (Thm 4.3)", true, g.R_over_l_max, r.max_radius_edge);
  add("theorem_4_3_min_angle_deg", "min angle deg", false, g.min_angle_deg, r.min_angle_deg);
  add("theorem_4_4_nn_over_f_min", "nn/f min (Thm 4.4)", false, g.nn_over_f_min, r.nn_over_f_min);
  add("theorem_4_5_el_over_f_max", "el/f max (Thm 4.5)", true, g.el_over_f_max, r.el_over_f_max, false);
  add("theorem_4_5_corrected_el_over_f_max", "el/f max (4.5 fixed)", true, g.el_over_f_max_corrected, r.el_over_f_max);
  return rows;
}

bool guarantees_hold(const QualityReport& r) {
  if (!r.guarantees.valid) return false;
  for (const auto& c : theorem_checks(r))
    if (c.counts && c.holds && !*c.holds) return false;
  return true;
}

}  // namespace fdr::quality
