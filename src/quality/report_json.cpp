// The JSON report, written atomically to a file.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <ostream>
#include <string>
#include <nlohmann/json.hpp>
#include "base/error.hpp"
#include "quality/report.hpp"

namespace fdr::quality {
namespace {

using Json = nlohmann::ordered_json;
constexpr const char* kRepairsSpliceMark = "\x01" "fdrmesh repairs" "\x01";

Json num(std::optional<double> v) {
  if (!v || !std::isfinite(*v)) return nullptr;
  return *v;
}
Json num(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }
Json count(std::optional<std::size_t> v) { return v ? Json(*v) : Json(nullptr); }

Json histogram_json(const Histogram& h) {
  Json j;
  // Integral widths (5 degrees) are written as integers: {"bin_deg": 5}.
  if (h.width == std::floor(h.width)) j["bin_deg"] = static_cast<long long>(h.width);
  else j["bin_deg"] = h.width;
  j["from_deg"] = h.lo;
  j["counts"] = h.counts;
  return j;
}

}  // namespace

void write_json(const QualityReport& r, std::ostream& out) {
  Json j;
  j["vertices"] = r.vertices;
  j["triangles"] = r.triangles;
  j["min_angle_deg"] = num(r.min_angle_deg);
  j["max_angle_deg"] = num(r.max_angle_deg);
  j["max_radius_edge"] = num(r.max_radius_edge);
  j["max_R_over_f"] = num(r.max_R_over_f);
  j["mean_R_over_f"] = num(r.mean_R_over_f);
  j["bad_triangles"] = count(r.bad_triangles);
  j["exempt_small_angle_triangles"] = r.run.exempt_small_angle_triangles;
  j["conformity"] = {{"min", num(r.conformity_min)}, {"mean", num(r.conformity_mean)},
                     {"p05", num(r.conformity_p05)}};
  j["el_over_f_max"] = num(r.el_over_f_max);
  if (r.vertical_error_max_m) {
    j["vertical_error_max_m"] = num(r.vertical_error_max_m);
    j["vertical_error_rms_m"] = num(r.vertical_error_rms_m);
  }
  j["nn_over_f_min"] = num(r.nn_over_f_min);
  j["orthogonality"] = {{"max", num(r.orthogonality.orthogonality_max)}, {"p99", num(r.orthogonality.orthogonality_p99)}};
  j["smoothness"] = {{"max", num(r.orthogonality.smoothness_max)}, {"p99", num(r.orthogonality.smoothness_p99)}};
  j["min_angle_histogram"] = histogram_json(r.min_angle_histogram);
  j["max_angle_histogram"] = histogram_json(r.max_angle_histogram);
  {
    Json h;
    h["bin"] = r.conformity_histogram.width;
    h["counts"] = r.conformity_histogram.counts;
    j["conformity_histogram"] = h;
  }
  j["timings_s"] = {{"cdt", num(r.run.cdt_s)}, {"refine", num(r.run.refine_s)},
                    {"write", num(r.run.write_s)}, {"total", num(r.run.total_s)}};
  j["peak_rss_mb"] = num(r.run.peak_rss_mb);
  j["predicate_calls"] = {{"filtered", r.run.predicate_filtered}, {"exact", r.run.predicate_exact}};
  j["steiner_points"] = {{"segment", r.run.steiner_segment}, {"interior", r.run.steiner_interior},
                         {"total", r.run.steiner_total()}};
  j["area"] = num(r.area);
  j["degenerate_triangles"] = r.degenerate_triangles;
  j["inverted_triangles"] = r.inverted_triangles;
  j["nn_min"] = num(r.nn_min);
  j["spacing_invalid_evaluations"] = r.spacing_invalid;
  j["bound_B"] = num(r.bound_B);
  j["alpha"] = r.alpha >= 0 ? num(r.alpha) : Json(nullptr);
  j["spacing"] = r.spacing;
  j["input_file"] = r.run.input_file;
  j["min_angle_option_deg"] = num(r.run.min_angle_option_deg);
  // The repairs (up to hundreds of thousands on real coasts) are streamed below instead of held as
  // one document: the text is cut at this mark and the repairs are written there.
  j["repairs"] = kRepairsSpliceMark;
  const Guarantees& g = r.guarantees;
  auto gv = [&](double v) { return g.valid ? num(v) : Json(nullptr); };
  j["guarantees"] = {{"beta", gv(g.beta)},
                     {"beta_B", gv(g.beta_B)},
                     {"beta_D", g.valid && g.beta_D ? num(*g.beta_D) : Json(nullptr)},
                     {"conforming_D", r.run.conforming_D ? num(*r.run.conforming_D) : Json(nullptr)},
                     {"conforming_D_at", r.run.conforming_D ? Json::array({num(r.run.conforming_D_at.x), num(r.run.conforming_D_at.y)})
                                                            : Json(nullptr)},
                     {"R_over_l_max", gv(g.R_over_l_max)},
                     {"min_angle_deg", gv(g.min_angle_deg)},
                     {"nn_over_f_min", gv(g.nn_over_f_min)},
                     {"el_over_f_max", gv(g.el_over_f_max)},
                     {"el_over_f_max_corrected", gv(g.el_over_f_max_corrected)},
                     {"valid", guarantees_hold(r)},  // applicable and every counted bound holds
                     {"applicable", g.valid},
                     {"note", g.note}};
  for (const auto& c : theorem_checks(r))
    j["guarantees"][c.key] = {{"relation", c.upper ? "<=" : ">="}, {"bound", num(c.bound)},
                              {"measured", num(c.measured)},
                              {"holds", c.holds ? Json(*c.holds) : Json(nullptr)},
                              {"counts_for_valid", c.counts}};
  j["measured"] = {{"R_over_l_max", num(r.max_radius_edge)},
                   {"min_angle_deg", num(r.min_angle_deg)},
                   {"nn_over_f_min", num(r.nn_over_f_min)},
                   {"el_over_f_max", num(r.el_over_f_max)}};
  if (r.model_ready) j["model_ready"] = model_ready_json(*r.model_ready);
  const std::string text = j.dump(2);
  const std::string mark = Json(kRepairsSpliceMark).dump();
  const std::size_t at = text.find(mark);
  if (at == std::string::npos) throw Error(ExitCode::kInternal, "quality: report JSON without its repairs");
  out.write(text.data(), static_cast<std::streamsize>(at));
  // Pretty printing nests: a repair object printed on its own with indent 2, its lines after
  // the first shifted by its depth (4 spaces), is the text the whole document would hold.
  if (r.repairs.empty()) {
    out << "[]";
  } else {
    out << "[\n";
    std::string obj;
    for (std::size_t i = 0; i < r.repairs.size(); ++i) {
      const auto& rp = r.repairs[i];
      obj = Json({{"kind", rp.kind}, {"x", num(rp.x)}, {"y", num(rp.y)}, {"ids", rp.ids}, {"reason", rp.reason}}).dump(2);
      out << "    ";
      std::size_t from = 0;
      for (std::size_t nl = obj.find('\n'); nl != std::string::npos; nl = obj.find('\n', from)) {
        out.write(obj.data() + from, static_cast<std::streamsize>(nl + 1 - from));
        out << "    ";
        from = nl + 1;
      }
      out.write(obj.data() + from, static_cast<std::streamsize>(obj.size() - from));
      out << (i + 1 < r.repairs.size() ? ",\n" : "\n");
    }
    out << "  ]";
  }
  out.write(text.data() + at + mark.size(), static_cast<std::streamsize>(text.size() - at - mark.size()));
  out << '\n';
}

void write_json_file(const QualityReport& r, const std::string& path) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    if (!out) throw Error(ExitCode::kOutputError, path + ": cannot write");
    write_json(r, out);
    out.flush();
    if (!out) {
      out.close();
      std::remove(tmp.c_str());
      throw Error(ExitCode::kOutputError, path + ": write failed");
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw Error(ExitCode::kOutputError, path + ": cannot rename the temporary file");
  }
}

}  // namespace fdr::quality
