// The report as a compact human summary: figures, an ASCII angle histogram, the theory table.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>
#include "quality/report.hpp"
#include "quality/text_format.hpp"

namespace fdr::quality {
namespace {


}  // namespace

void write_text(const QualityReport& r, std::ostream& out) {
  out << "Mesh quality\n";
  if (!r.run.input_file.empty()) line(out, "input", r.run.input_file);
  line(out, "spacing f", r.spacing);
  line(out, "vertices / triangles", std::to_string(r.vertices) + " / " + std::to_string(r.triangles));
  line(out, "area", fmt(r.area, "%.10g"));
  if (r.degenerate_triangles || r.inverted_triangles) {
    line(out, "degenerate / inverted", std::to_string(r.degenerate_triangles) + " / " +
                                           std::to_string(r.inverted_triangles));
  }
  line(out, "angle min / max (deg)", fmt(r.min_angle_deg, "%.4f") + " / " + fmt(r.max_angle_deg, "%.4f"));
  line(out, "max radius-edge R/l", fmt(r.max_radius_edge, "%.4f"));
  line(out, "orthogonality max / p99", fmt(r.orthogonality.orthogonality_max, "%.3g") + " / " +
                                           fmt(r.orthogonality.orthogonality_p99, "%.3g"));
  line(out, "smoothness max / p99", fmt(r.orthogonality.smoothness_max, "%.4f") + " / " +
                                        fmt(r.orthogonality.smoothness_p99, "%.4f"));
  if (r.max_R_over_f) {
    line(out, "R/f(c) max / mean", fmt(r.max_R_over_f, "%.4f") + " / " + fmt(r.mean_R_over_f, "%.4f"));
    line(out, "bad triangles (R/f(c) > B)", std::to_string(*r.bad_triangles) + "  (B = " + fmt(r.bound_B) + ")");
  }
  if (r.conformity_min) {
    line(out, "conformity min / mean / p05", fmt(r.conformity_min, "%.4f") + " / " +
                                                 fmt(r.conformity_mean, "%.4f") + " / " +
                                                 fmt(r.conformity_p05, "%.4f"));
    line(out, "nn/f min, el/f max", fmt(r.nn_over_f_min, "%.4f") + ", " + fmt(r.el_over_f_max, "%.4f"));
    if (r.vertical_error_max_m)
      line(out, "TIN vs DEM error max / RMS (m)",
           fmt(r.vertical_error_max_m, "%.3f") + " / " + fmt(r.vertical_error_rms_m, "%.3f"));
  }
  if (r.spacing_invalid) line(out, "f <= 0 or not finite (skipped)", std::to_string(r.spacing_invalid));
  line(out, "exempt small-angle triangles", std::to_string(r.run.exempt_small_angle_triangles));
  line(out, "Steiner points seg/interior", std::to_string(r.run.steiner_segment) + " / " +
                                                 std::to_string(r.run.steiner_interior));
  line(out, "time s cdt/refine/write/total",
       fmt(r.run.cdt_s, "%.3f") + " / " + fmt(r.run.refine_s, "%.3f") + " / " + fmt(r.run.write_s, "%.3f") +
           " / " + fmt(r.run.total_s, "%.3f"));
  line(out, "peak RSS (MB)", fmt(r.run.peak_rss_mb, "%.1f"));
  line(out, "predicates filtered / exact",
       std::to_string(r.run.predicate_filtered) + " / " + std::to_string(r.run.predicate_exact));

  // Triangle-style histogram: min angles with a bar, max angles as a compact second column.
  out << "\n  Min-angle histogram" << std::string(32, ' ') << "| Max-angle histogram\n";
  std::uint64_t peak = 1;
  for (auto c : r.min_angle_histogram.counts) peak = std::max(peak, c);
  const auto& hmin = r.min_angle_histogram;
  const auto& hmax = r.max_angle_histogram;
  const std::size_t rows = std::max(hmin.counts.size(), (hmax.counts.size() + 1) / 2);
  for (std::size_t i = 0; i < rows; ++i) {
    char left[80] = "";
    if (i < hmin.counts.size()) {
      const double lo = hmin.lo + static_cast<double>(i) * hmin.width;
      const int bar = static_cast<int>(std::lround(24.0 * static_cast<double>(hmin.counts[i]) /
                                                   static_cast<double>(peak)));
      std::snprintf(left, sizeof left, "  %3.0f - %3.0f deg: %10llu %-24s", lo, lo + hmin.width,
                    static_cast<unsigned long long>(hmin.counts[i]), std::string(bar, '#').c_str());
    }
    out << left;
    // Two max-angle bins per row keep the table as tall as the min-angle one.
    for (std::size_t k = 2 * i; k < 2 * i + 2 && k < hmax.counts.size(); ++k) {
      const double lo = hmax.lo + static_cast<double>(k) * hmax.width;
      char right[64];
      std::snprintf(right, sizeof right, " | %3.0f-%3.0f: %9llu", lo, lo + hmax.width,
                    static_cast<unsigned long long>(hmax.counts[k]));
      out << right;
    }
    out << '\n';
  }

  if (r.model_ready) write_model_ready_text(*r.model_ready, out);

  const Guarantees& g = r.guarantees;
  out << "\n  Theory vs measured (alpha = " << (r.alpha >= 0 ? fmt(r.alpha) : std::string("unknown"))
      << ", B = " << fmt(r.bound_B) << ")\n";
  if (!g.valid) out << "    " << g.note << '\n';
  else out << "    beta = " << fmt(g.beta, "%.6f") << "; " << g.note << '\n';
  if (g.valid && r.run.conforming_D) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "    D = min nn/f of the conforming mesh = %.4g at (%.1f, %.1f); beta_B = %.6f, beta_D = %.6f\n",
                  *r.run.conforming_D, r.run.conforming_D_at.x, r.run.conforming_D_at.y, g.beta_B, g.beta_D.value_or(0));
    out << buf;
  }
  const auto checks = theorem_checks(r);
  if (!checks.empty()) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "    %-22s %-4s %12s %12s  %s\n", "quantity", "", "theory", "measured", "holds");
    out << buf;
    for (const auto& c : checks) {
      const char* ok = !c.holds ? "n/a" : *c.holds ? "yes" : (c.counts ? "NO" : "no (printed bound)");
      std::snprintf(buf, sizeof buf, "    %-22s %-4s %12s %12s  %s\n", c.label, c.upper ? "<=" : ">=",
                    fmt(c.bound, "%.4f").c_str(), fmt(c.measured, "%.4f").c_str(), ok);
      out << buf;
    }
    if (g.valid) out << "    all bounds hold: " << (guarantees_hold(r) ? "yes" : "NO") << '\n';
  }
}

}  // namespace fdr::quality
