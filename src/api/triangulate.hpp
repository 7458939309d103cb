// fdrmesh core API (no GDAL): PSLG + spacing f -> Functional Delaunay Refinement mesh + report.
//
//   #include "api/triangulate.hpp"
//   fdr::Pslg g = fdr::read_pslg("square.poly");
//   fdr::Mesh m = fdr::triangulate(g, *fdr::make_spacing("paper-f1"), {.bound = 1.0});
//   // m.view.vertices (local; world = m.view.origin + v), m.view.triangles (CCW), m.report
//
// The result is the same, bit for bit, as `fdrmesh mesh square.poly --spacing paper-f1` (the CLI's
// .poly path: local origin, CDT, FDR, quality report). Public names live in namespace fdr (not
// fdr::api): this header and pipeline/mesh_domain.hpp are the library's front door.
#pragma once
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>
#include "base/error.hpp"
#include "base/progress.hpp"
#include "mesh/mesh_view.hpp"
#include "mesh/triangulation.hpp"
#include "pslg/pslg.hpp"
#include "quality/report.hpp"
#include "sizing/grid.hpp"
#include "sizing/sizing_field.hpp"

namespace fdr {

using pslg::Pslg;
using sizing::SizingField;
using sizing::SizingPtr;
using mesh::MeshView;
using mesh::edge_kind_name;
using quality::QualityReport;

struct TriangulateOptions {
  double bound = 1.0;                    // B: a triangle is bad when R / f(c) > B (--bound)
  double min_angle_deg = 0.0;            // extra minimum-angle bound, [0, 60) (--min-angle)
  // Subsegment splits asked for by the angle bound alone: only into halves >= this * f (0: always,
  // as Triangle; GIS inputs: 0.5). See refine::RefineOptions::angle_split_min_f.
  double angle_split_min_f = 0.0;
  int smooth_passes = 0;                 // quality smoothing sweeps after refinement, [0, 100] (--smooth)
  // Frontal point placement with this target circumradius, a fraction of B f, in (0, 1); 0: the
  // circumcentre rule alone (--frontal; refine::RefineOptions::frontal).
  double frontal_radius = 0.0;
  std::uint64_t max_steiner = 20'000'000;  // Steiner point cap; reaching it is Error(kWorkLimit)
  bool check = false;                    // verify the invariants, Error(kCheckFailed) if one fails (--check)
  // Mesh the convex hull of the input, not the regions bounded by segments (--convex-hull).
  bool convex_hull = false;
  // Refuse crossing, overlapping, duplicate or zero-length constraints (Error(kInvalidGeometry)
  // naming the first) instead of resolving them with pslg::resolve (--strict).
  bool strict = false;
  // Triangle .poly regions: maximum triangle area per region (in Pslg::regions order; < 0 none).
  std::vector<double> region_max_area;
  std::string source = "input";          // named in error messages and in the report
  ProgressFn progress;                   // fraction 0..1, may cancel (Error(kCancelled))
  LogFn log;                             // warnings (alpha*B >= 1) and info lines
  // Called when a stage ends ("refine", "smooth", "check"): per-stage timing hooks (pipeline).
  std::function<void(const std::string& stage)> stage_done;
};

// A finished mesh: the compact view (local frame, triangles counter-clockwise, constrained edges
// with their markers/kinds, f at the vertices) and its quality report, plus what a writer needs.
struct Mesh {
  MeshView view;
  QualityReport report;
  SizingPtr f;            // the spacing in the mesh's local frame (R/f(c) columns of the writers)
  double bound = 1.0;
  double min_angle_deg = 0.0;
  double alpha = -1;      // Lipschitz constant the guarantees were computed for
  std::string source;     // input name (title of written meshes)
};

// Reads a Triangle .poly or .node file (by extension) and validates it, as the CLI does.
// Throws fdr::Error (kInputUnreadable, kInputMalformed, kInvalidGeometry).
Pslg read_pslg(const std::string& path);

// A spacing function from a specification as accepted by --spacing (number, preset, K*preset,
// expression in x, y); in world coordinates. Throws Error(kUsage / kInvalidSpacing).
SizingPtr make_spacing(const std::string& spec);
// The CLI's default for a bare PSLG: a twentieth of the bounding-box diagonal, as a spec string.
std::string default_spacing_spec(const Pslg& pslg);
// A spacing sampled on a regular grid (world coordinates; cell-centre values, bilinear in
// between, see sizing/grid.hpp); `label` is its description in reports.
SizingPtr grid_spacing(sizing::Grid grid, const std::string& label);

// One-shot: CDT of `pslg`, FDR refinement against `f`, quality report. `f` is given in the PSLG's
// world coordinates (origin + point); the PSLG is first shifted to a local origin when its
// coordinates are large compared to its extent, exactly like the CLI. Throws fdr::Error.
// This form leaves Mesh::f empty (f belongs to the caller); the SizingPtr form keeps it, so that
// written meshes get their R/f(c) columns.
Mesh triangulate(const Pslg& pslg, const SizingField& f, const TriangulateOptions& options = {});
Mesh triangulate(const Pslg& pslg, SizingPtr f, const TriangulateOptions& options = {});

// Step-wise form: the CDT alone, then one or more refinements (e.g. a coarse f, then a finer one).
//   fdr::Triangulator t(pslg);        // constrained Delaunay triangulation
//   MeshView cdt = t.view();          // the CDT (no Steiner points)
//   t.refine(f1); t.refine(f2);       // refine, then refine further against a smaller f2
//   fdr::Mesh m = t.mesh();           // report against the last f
// triangulate(p, f, o) == Triangulator(p, o).refine(f).mesh() bit for bit.
class Triangulator {
 public:
  explicit Triangulator(const Pslg& pslg, const TriangulateOptions& options = {});
  // Refines until every triangle has R/f(c) <= bound (f in world coordinates). The field must
  // outlive the Triangulator only if it is passed by reference; SizingPtr is shared.
  Triangulator& refine(const SizingField& f);
  Triangulator& refine(SizingPtr f);
  // The current mesh (CDT before refine()).
  MeshView view() const;
  // The mesh and its quality report against the last refinement's f (no f before refine()).
  Mesh mesh() const;
  // The triangulation itself (for callers that run the mesh checkers or their own steps).
  const mesh::Triangulation& triangulation() const { return tri_; }
  const Pslg& pslg() const { return pslg_; }  // shifted to the local frame

 private:
  TriangulateOptions opt_;
  Pslg pslg_;
  mesh::Triangulation tri_;
  SizingPtr f_;        // last refinement's spacing, local frame
  double alpha_ = -1;
  std::optional<double> cdt_s_, refine_s_;
  std::vector<quality::QualityReport::Repair> repairs_;  // constraint fixes (world coordinates)
  std::uint64_t seg_splits_ = 0, circumcenters_ = 0, angle_exempt_ = 0;
  double conforming_D_ = std::numeric_limits<double>::quiet_NaN();  // RefineStats::conforming_D
  Point2 conforming_D_at_{0, 0};
};

// The JSON quality report (the document written by --report) as a string.
std::string report_json(const QualityReport& report);

}  // namespace fdr
