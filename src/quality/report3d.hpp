// The quality report of a tetrahedral mesh: the 2D report's structure in 3D (counts, R/f(c),
// radius-edge, dihedral angles, edge length against f, the paper's Theorems 4.2-4.5 with their 3D
// constants beside the measured values, the refinement's splits and shortfalls).
#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>
#include "base/threads.hpp"
#include "sizing/spacing3d.hpp"
#include "tet/tet_mesh.hpp"
#include "tet/tetrahedralize.hpp"

namespace fdr::quality {

// The Section 4 bounds in 3D for given alpha and B: beta = B / (4 + (3 + 2 sqrt 2) alpha B)
// makes Theorem 4.2's termination condition hold; valid only when 0 <= alpha B < 1.
struct Guarantees3 {
  bool valid = false;
  std::string note;             // why not valid, or the assumption behind beta
  double beta = 0;
  double R_over_l_max = 0;      // Thm 4.3: B / (2 beta (1 - alpha B))
  double nn_over_f_min = 0;     // Thm 4.4: 2 beta / (1 + alpha beta)
  double el_over_f_max = 0;     // Thm 4.5 as printed: 2B / (1 + alpha B)
  double el_over_f_max_corrected = 0;  // Thm 4.5 with f(p) >= f(c) - alpha R: 2B / (1 - alpha B)
};
Guarantees3 compute_guarantees3(double alpha, double bound_B);

struct MaterialFigures {
  std::int32_t material = 0;
  std::size_t tets = 0;
  double volume = 0;
};

struct TheoremRow {
  std::string key, label;
  bool upper = true;           // the bound is a maximum (measured <= bound holds)
  double bound = 0, measured = 0;
  bool holds = false;
  bool applies = true;         // false: no guarantee (alpha unknown or alpha B >= 1)
  // Measured on a mesh the theorem does not cover (after sliver removal, whose vertices are not
  // FDR's): shown beside the theorem's row, never judged (applies is false).
  bool beyond_paper = false;
};

struct Report3 {
  std::string input_file, spacing;
  double bound_B = 0, alpha = -1;
  std::size_t vertices = 0, tets = 0, subfacets = 0, subsegments = 0;
  std::vector<MaterialFigures> materials;  // by material id
  double volume = 0;
  double max_R_over_f = 0, max_radius_edge = 0;
  std::size_t bad_tets = 0;                // R/f(c) > B
  double min_dihedral_deg = 0, max_dihedral_deg = 0;
  std::vector<std::size_t> dihedral_hist;  // 18 bins of 10 degrees over [0, 180]
  std::size_t tets_under_5deg = 0, tets_under_10deg = 0;  // by their smallest dihedral angle
  double min_l_over_f = 0, max_l_over_f = 0;  // every edge, f at its midpoint
  double nn_over_f_min = 0, el_over_f_max = 0;  // per vertex, shortest / longest incident edge over f(p)
  Guarantees3 guarantees;
  std::vector<TheoremRow> theorems;
  tet::TetStats stats;
  // Filled by the caller (pipeline): whole-process figures and stages.
  double wall_s = 0, peak_rss_mb = 0;
  std::vector<std::pair<std::string, double>> stage_seconds;
  std::vector<std::pair<std::string, double>> stage_peak_mb;
  std::optional<bool> check_passed;        // set when --check ran
};

// Per-tetrahedron values for the outputs' cell data, one per tetrahedron.
struct TetValues {
  std::vector<double> r_over_f, radius_edge, min_dihedral_deg;
};

// Measures `mesh` against f and B (stats.bound when B <= 0). `values`, when given, receives the
// per-tetrahedron figures. One pass over the tetrahedra on up to `threads` threads; the figures are
// the same, bit for bit, for every thread count.
Report3 measure_tets(const tet::TetMesh& mesh, const sizing::SizingField3& f, const tet::TetStats& stats,
                     TetValues* values = nullptr, unsigned threads = max_threads());

// The six interior dihedral angles' minimum and maximum of one tetrahedron, in degrees.
std::pair<double, double> dihedral_range_deg(Point3 a, Point3 b, Point3 c, Point3 d);

void write_text3(const Report3& r, std::ostream& out);
void write_json3(const Report3& r, std::ostream& out);

}  // namespace fdr::quality
