// Mesh quality report: angles, radius-edge and R/f(c) ratios, conformity (FDR paper, Def. 2.1, §4).
#pragma once
#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>
#include "mesh/mesh_view.hpp"
#include "quality/model_ready.hpp"
#include "quality/orthogonality.hpp"
#include "sizing/sizing_field.hpp"

namespace fdr::quality {

// What the mesher measured while running; copied verbatim into the report.
// Unmeasured values stay std::nullopt and are written as JSON null / "n/a".
struct RunInfo {
  std::optional<double> cdt_s, refine_s, write_s, total_s;  // wall-clock timings in seconds
  std::optional<double> peak_rss_mb;                        // VmHWM of the process (see rss.hpp)
  std::uint64_t predicate_filtered = 0;                     // predicate decisions certified in double
  std::uint64_t predicate_exact = 0;                        // decisions that needed the exact fallback
  std::uint64_t exempt_small_angle_triangles = 0;           // triangles the refiner left alone (small input angles)
  std::uint64_t steiner_segment = 0;                        // Steiner points inserted on subsegments
  std::uint64_t steiner_interior = 0;                       // Steiner points inserted at circumcenters
  std::string input_file;                                   // input path as given by the user
  std::string spacing;                                      // spacing description (SizingField::describe())
  std::optional<double> min_angle_option_deg;               // the --min-angle option, if any
  // D of the conforming mesh M_c (refine::RefineStats::conforming_D): nn_Mc >= D f, the assumption
  // that bounds beta (paper, Section 4); unset when unknown (a mesh read from a file).
  std::optional<double> conforming_D;
  Point2 conforming_D_at{0, 0};                             // where it is attained (world)
  std::uint64_t steiner_total() const { return steiner_segment + steiner_interior; }
};

// Fixed-width histogram: bin i covers [lo + i*width, lo + (i+1)*width); the last bin is closed.
struct Histogram {
  double lo = 0;
  double width = 1;
  std::vector<std::uint64_t> counts;
  void add(double v);  // values outside [lo, lo + n*width] are clamped into the first/last bin
};

// Section 4 guarantees of FDR in 2D for given (alpha, B), valid only when 0 <= alpha*B < 1.
struct Guarantees {
  bool valid = false;
  std::string note;            // why not valid, or the assumptions behind the numbers
  double beta = 0;             // min(beta_B, beta_D): the protection radius factor of Section 4
  double beta_B = 0;           // B / (2*sqrt(2) + 3*alpha*B)
  std::optional<double> beta_D;  // D / (2 + alpha*D) when D of the conforming mesh is known
  double R_over_l_max = 0;     // Theorem 4.3 with that beta: (2*sqrt(2)+3aB) / (2(1-aB))
  double min_angle_deg = 0;    // asin((1-aB) / (2*sqrt(2)+3aB))
  double nn_over_f_min = 0;    // Theorem 4.4: 2*beta / (1 + alpha*beta)
  double el_over_f_max = 0;    // Theorem 4.5 as printed: 2B / (1 + alpha*B)
  // Theorem 4.5 with its sign slip fixed: the proof needs f(p) >= f(c) - alpha*R (Lipschitz), not
  // f(c) + alpha*R, which gives el(p) <= 2B / (1 - alpha*B) f(p). Measured meshes can exceed the
  // printed bound but stay within this one.
  double el_over_f_max_corrected = 0;
};
// D: the constant of nn_Mc >= D f (RunInfo::conforming_D); without it beta = beta_B is assumed.
Guarantees compute_guarantees(double alpha, double bound_B, std::optional<double> conforming_D = std::nullopt);

struct QualityReport {
  std::size_t vertices = 0;
  std::size_t triangles = 0;
  std::size_t degenerate_triangles = 0;  // zero signed area (collinear corners)
  std::size_t inverted_triangles = 0;    // clockwise (exact orient2d)
  double area = 0;                       // sum of signed triangle areas (compensated)

  // Triangle metrics; nullopt when the mesh has no triangles.
  std::optional<double> min_angle_deg, max_angle_deg;
  std::optional<double> max_radius_edge;  // max R/l (+inf if a triangle is degenerate)
  Histogram min_angle_histogram{0.0, 5.0, std::vector<std::uint64_t>(12, 0)};   // 0..60 deg
  Histogram max_angle_histogram{60.0, 5.0, std::vector<std::uint64_t>(24, 0)};  // 60..180 deg

  // Spacing metrics over triangles (need the SizingField; nullopt without it).
  std::optional<double> max_R_over_f, mean_R_over_f;
  std::optional<std::size_t> bad_triangles;  // R/f(c) > B

  // Vertex metrics (need f at the vertices: the SizingField, else MeshView::f).
  std::optional<double> nn_min;  // smallest distance between two distinct vertex indices
  std::optional<double> conformity_min, conformity_mean, conformity_p05;
  Histogram conformity_histogram{0.0, 0.1, std::vector<std::uint64_t>(10, 0)};  // 0..1
  std::optional<double> el_over_f_max;  // el(p) / f(p), el = longest edge of the triangles at p
  std::optional<double> nn_over_f_min;  // nn(p) / f(p)
  std::size_t spacing_invalid = 0;
  // Terrain runs: vertical error of the linear TIN against the DEM cells inside the domain.
  std::optional<double> vertical_error_max_m, vertical_error_rms_m;       // evaluations of f that were <= 0 or not finite (skipped)

  OrthogonalityStats orthogonality;  // Delft3D FM grid checks (quality/orthogonality.hpp)

  double bound_B = 0;
  double alpha = 0;
  std::string spacing;  // description of f ("none" without one)
  Guarantees guarantees;
  RunInfo run;
  std::optional<ModelReadiness> model_ready;  // model_ready.hpp (set by the pipeline / quality command)
  // Fixes made to the input constraints before triangulation (JSON "repairs").
  struct Repair {
    std::string kind;
    double x = 0, y = 0;  // world coordinates
    std::vector<std::int64_t> ids;
    std::string reason;
  };
  std::vector<Repair> repairs;
};

// One row of the theory table: a bound of the paper against the measured value.
struct TheoremCheck {
  const char* key;    // JSON key in "guarantees"
  const char* label;  // text table label
  bool upper;         // true: measured <= bound; false: measured >= bound
  double bound;
  std::optional<double> measured;
  std::optional<bool> holds;  // nullopt when not measured or no guarantee applies
  bool counts;        // false for Theorem 4.5 as printed (known sign slip): shown, not in "valid"
};
// The rows for `r` (FDR bound R/f(c) <= B, Theorems 4.3, the implied min angle, 4.4, 4.5 as
// printed and corrected); empty when no guarantee applies (alpha unknown or alpha*B >= 1).
std::vector<TheoremCheck> theorem_checks(const QualityReport& r);
// True when a guarantee applies and every counted row holds.
bool guarantees_hold(const QualityReport& r);

// Per-triangle values measured on the way (filled when asked for; writers reuse them instead of
// evaluating f again): signed area, smallest angle in degrees, R/f(c) (only with f; +inf for a
// degenerate triangle, R/f(c) as computed even where f(c) is unusable).
struct TriangleValues {
  std::vector<double> area, min_angle_deg, r_over_f;
};

// Measures every metric of `m` (in its local frame, where `f` is evaluated). `f` may be null.
// `alpha` is the Lipschitz constant the guarantees are computed for; negative means unknown and
// then f->lipschitz() is used when f knows it (else no guarantee is claimed).
// Throws fdr::Error(kInternal) if a triangle references a vertex that does not exist.
// `f_at_vertices`, when given, holds (*f)(m.vertices[i]) already evaluated (used instead of
// evaluating f again; must be exactly those values). `fill_f_at_vertices`, when given (and f is
// not null), gets those values here instead (a spacing that is not thread-safe is only ever
// evaluated on the calling thread).
QualityReport compute_quality(const mesh::MeshView& m, const sizing::SizingField* f, double bound_B,
                              double alpha, const RunInfo& run, TriangleValues* per_triangle = nullptr,
                              const std::vector<double>* f_at_vertices = nullptr,
                              std::vector<double>* fill_f_at_vertices = nullptr);

// Nearest other vertex distance for every vertex (exact, kd-tree); 0 for duplicated points,
// +inf when the mesh has a single vertex.
std::vector<double> nearest_neighbour_distances(const std::vector<Point2>& pts);

// JSON report; non-applicable or non-finite values are null.
void write_json(const QualityReport& r, std::ostream& out);
// Writes the JSON report to `path` atomically (temporary file, then rename); Error(kOutputError).
void write_json_file(const QualityReport& r, const std::string& path);
// Compact human summary with an ASCII angle histogram and a theory-vs-measured table.
void write_text(const QualityReport& r, std::ostream& out);

}  // namespace fdr::quality
