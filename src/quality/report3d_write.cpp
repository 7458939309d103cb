// The 3D report as text (the CLI's stdout) and as JSON (--report FILE.json).
#include <nlohmann/json.hpp>
#include <cstdio>
#include <string>
#include <vector>
#include "quality/report3d.hpp"

namespace fdr::quality {
namespace {

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

// JSON has no infinity or NaN: such values become null.
nlohmann::ordered_json num(double v) {
  return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr);
}

void write_histogram(const std::vector<std::size_t>& hist, std::ostream& out) {
  for (std::size_t i = 0; i < hist.size(); ++i)
    if (hist[i]) out << " [" << i * 10 << "," << i * 10 + 10 << ") " << hist[i];
  out << "\n";
}

// Sliver removal: what it found, what it did, and the histogram before it ran (the one above is
// after).
void write_sliver_text(const tet::TetStats& s, std::ostream& out) {
  if (s.sliver_angle_deg <= 0) {
    out << "sliver removal: off\n";
    return;
  }
  out << "sliver removal (smallest dihedral under " << fmt("%.4g", s.sliver_angle_deg) << " deg): " << s.slivers_before
      << " before (min " << fmt("%.2f", s.min_dihedral_before_deg) << " deg), " << s.slivers_left << " left; "
      << s.sliver_splits << " points inserted, " << s.sliver_yields << " times split the boundary instead\n";
  out << "smallest dihedral per tetrahedron before sliver removal:";
  write_histogram(s.dihedral_hist_before, out);
  for (const auto& sf : s.slivers_listed)
    out << "  sliver at (" << sf.where.x << ", " << sf.where.y << ", " << sf.where.z << "): " << sf.what << "\n";
}

nlohmann::ordered_json sliver_json(const tet::TetStats& s) {
  using J = nlohmann::ordered_json;
  J listed = J::array();
  for (const auto& x : s.slivers_listed) listed.push_back({{"where", {x.where.x, x.where.y, x.where.z}}, {"what", x.what}});
  return {{"enabled", s.sliver_angle_deg > 0}, {"angle_deg", s.sliver_angle_deg}, {"before", s.slivers_before},
          {"left", s.slivers_left}, {"points_inserted", s.sliver_splits}, {"boundary_splits_instead", s.sliver_yields},
          {"min_dihedral_before_deg", s.min_dihedral_before_deg}, {"min_per_tet_histogram_before", s.dihedral_hist_before},
          {"listed", listed}};
}

}  // namespace

void write_text3(const Report3& r, std::ostream& out) {
  out << "3D mesh: " << r.vertices << " vertices, " << r.tets << " tetrahedra, " << r.subfacets << " subfacets, "
      << r.subsegments << " subsegments\n";
  out << "spacing: " << r.spacing << "; B = " << fmt("%.6g", r.bound_B)
      << "; alpha = " << (r.alpha >= 0 ? fmt("%.6g", r.alpha) : std::string("unknown")) << "\n";
  for (const auto& m : r.materials)
    out << "  material " << m.material << ": " << m.tets << " tetrahedra, volume " << fmt("%.9g", m.volume) << "\n";
  out << "R/f(c) max " << fmt("%.4f", r.max_R_over_f) << " (" << r.bad_tets << " above B); radius-edge max "
      << fmt("%.4f", r.max_radius_edge) << "\n";
  out << "dihedral angles: min " << fmt("%.2f", r.min_dihedral_deg) << " deg, max " << fmt("%.2f", r.max_dihedral_deg)
      << " deg; tetrahedra with an angle under 5 deg: " << r.tets_under_5deg << ", under 10 deg: " << r.tets_under_10deg
      << "\n";
  out << "smallest dihedral per tetrahedron (10-degree bins):";
  write_histogram(r.dihedral_hist, out);
  write_sliver_text(r.stats, out);
  out << "edge length / f: min " << fmt("%.4f", r.min_l_over_f) << ", max " << fmt("%.4f", r.max_l_over_f) << "\n";
  out << "theorems (" << r.guarantees.note << "):\n";
  for (const auto& t : r.theorems) {
    if (t.beyond_paper) {  // beside the theorem's row, not judged: the theorem does not cover it
      out << "  " << t.label << ": measured " << fmt("%.4g", t.measured) << " (beyond the paper; the theorem's "
          << (t.upper ? "<= " : ">= ") << fmt("%.4g", t.bound) << " covers FDR's vertices only)\n";
      continue;
    }
    out << "  " << t.label << ": bound " << (t.upper ? "<= " : ">= ") << fmt("%.4g", t.bound) << ", measured "
        << fmt("%.4g", t.measured) << ", " << (!t.applies ? "n/a" : t.holds ? "holds" : "FAILS") << "\n";
  }
  const auto& s = r.stats;
  out << "splits: " << s.segment_splits << " subsegment (rule 1), " << s.facet_splits << " subfacet (rule 2), "
      << s.tet_splits << " tetrahedron (rule 3), " << s.rejected << " rejected circumcentres"
      << (s.capped ? "; vertex cap reached" : "") << "\n";
  for (const auto& sf : s.shortfalls)
    out << "  shortfall at (" << sf.where.x << ", " << sf.where.y << ", " << sf.where.z << "): " << sf.what << "\n";
  if (r.check_passed) out << "check: " << (*r.check_passed ? "passed" : "FAILED") << "\n";
  out << "time " << fmt("%.2f", r.wall_s) << " s, peak memory " << fmt("%.1f", r.peak_rss_mb) << " MiB\n";
}

void write_json3(const Report3& r, std::ostream& out) {
  using J = nlohmann::ordered_json;
  J j;
  j["dimension"] = 3;
  j["input_file"] = r.input_file;
  j["spacing"] = r.spacing;
  j["bound_B"] = r.bound_B;
  j["alpha"] = r.alpha >= 0 ? J(r.alpha) : J(nullptr);
  j["counts"] = {{"vertices", r.vertices}, {"tetrahedra", r.tets}, {"subfacets", r.subfacets}, {"subsegments", r.subsegments}};
  J mats = J::array();
  for (const auto& m : r.materials) mats.push_back({{"material", m.material}, {"tetrahedra", m.tets}, {"volume", m.volume}});
  j["materials"] = mats;
  j["volume"] = r.volume;
  j["max_R_over_f"] = num(r.max_R_over_f);
  j["bad_tetrahedra"] = r.bad_tets;
  j["max_radius_edge"] = num(r.max_radius_edge);
  j["dihedral_deg"] = {{"min", r.min_dihedral_deg}, {"max", r.max_dihedral_deg}, {"tets_under_5", r.tets_under_5deg},
                       {"tets_under_10", r.tets_under_10deg}, {"min_per_tet_histogram_bin_deg", 10},
                       {"min_per_tet_histogram", r.dihedral_hist}};
  j["edge_length_over_f"] = {{"min", num(r.min_l_over_f)}, {"max", num(r.max_l_over_f)}};
  j["nn_over_f_min"] = num(r.nn_over_f_min);
  j["el_over_f_max"] = num(r.el_over_f_max);
  J g;
  g["valid"] = r.guarantees.valid;
  g["note"] = r.guarantees.note;
  g["beta"] = r.guarantees.beta;
  J th = J::array();
  for (const auto& t : r.theorems)
    th.push_back({{"key", t.key}, {"label", t.label}, {"kind", t.upper ? "max" : "min"}, {"bound", num(t.bound)},
                  {"measured", num(t.measured)}, {"applies", t.applies}, {"holds", t.holds},
                  {"beyond_paper", t.beyond_paper}});
  g["theorems"] = th;
  j["guarantees"] = g;
  const auto& s = r.stats;
  J sf = J::array();
  for (const auto& x : s.shortfalls) sf.push_back({{"where", {x.where.x, x.where.y, x.where.z}}, {"what", x.what}});
  j["refinement"] = {{"input_vertices", s.input_vertices}, {"segment_splits", s.segment_splits},
                     {"facet_splits", s.facet_splits}, {"tet_splits", s.tet_splits}, {"rejected", s.rejected},
                     {"capped", s.capped}, {"shortfalls", sf}};
  j["slivers"] = sliver_json(s);
  if (r.check_passed) j["check_passed"] = *r.check_passed;
  j["wall_s"] = r.wall_s;
  j["peak_rss_mb"] = r.peak_rss_mb;
  J st = J::array();
  for (std::size_t i = 0; i < r.stage_seconds.size(); ++i)
    st.push_back({{"name", r.stage_seconds[i].first}, {"seconds", r.stage_seconds[i].second},
                  {"peak_rss_mb", i < r.stage_peak_mb.size() ? r.stage_peak_mb[i].second : 0.0}});
  j["stages"] = st;
  out << j.dump(2) << "\n";
}

}  // namespace fdr::quality
