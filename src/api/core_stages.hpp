// The core's stages (no GDAL), shared by fdr::Triangulator and pipeline::run: one implementation
// of the local frame, the CDT, Functional Delaunay Refinement + smoothing + checks.
#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include "api/triangulate.hpp"
#include "cdt/cdt.hpp"
#include "pslg/clean.hpp"
#include "mesh/triangulation.hpp"
#include "refine/refine.hpp"

namespace fdr {

// `pslg` shifted to a local origin when its coordinates are far from 0 relative to its extent
// (e.g. projected metres), so that small inputs keep their exact coordinates; Pslg::origin grows
// by the shift.
Pslg to_local_frame(Pslg pslg);

// A .poly/library PSLG made ready for the CDT, in its local frame: with `strict`, conflicting
// constraints are refused (pslg::validate, exit 5 naming the first); else they are resolved
// exactly (pslg::resolve: crossings split, overlaps and duplicates merged, vertices on segments
// split there, zero-length segments dropped), each fix appended to `repairs` (local coordinates).
Pslg prepare_pslg(Pslg pslg, const std::string& source, bool strict, std::vector<pslg::Repair>* repairs);

// Constrained Delaunay triangulation of a PSLG in its local frame; `seconds` gets its wall time.
// `regions`: kAuto (GIS: parity), kSeeds (Triangle .poly semantics), kHull (--convex-hull).
// Error(kInvalidGeometry) naming `source` when no region is enclosed by segments (suggesting
// --convex-hull when `suggest_hull`).
mesh::Triangulation build_cdt(const Pslg& local, const std::string& source, double* seconds = nullptr,
                              cdt::CdtOptions::Regions regions = cdt::CdtOptions::Regions::kAuto,
                              bool suggest_hull = false);

// The region mode of a .poly/library input: --convex-hull, else Triangle's seeds when there are
// segments, else parity.
cdt::CdtOptions::Regions poly_regions(const Pslg& pslg, bool convex_hull);

// Spacing stage of the .poly path and of `fdrmesh quality`: f from a --spacing specification
// (world coordinates) evaluated in a local frame with the given origin.
SizingPtr spacing_in_frame(const std::string& spec, Point2 origin);

// The Lipschitz constant of f: its own when it knows it, else estimated on `box` (64x64 samples).
double lipschitz_of(const SizingField& f, const Box2& box);

// What the refinement stage did (for the quality report).
struct RefineOutcome {
  double alpha = -1;                 // Lipschitz constant of f (given or estimated on `box`)
  double refine_s = 0;               // wall time of the refinement proper (not smoothing)
  refine::RefineStats stats;
  std::size_t angle_exempt = 0;      // triangles left below min_angle_deg (0 when it is 0)
};

// FDR refinement of `tri` against `f` (local frame) with options.bound / min_angle_deg /
// max_steiner, then options.smooth_passes smoothing sweeps, then the checks when options.check.
// Warns on alpha*B >= 1; Error(kWorkLimit) when f asks for more than max_steiner allows,
// Error(kCheckFailed), Error(kCancelled) from options.progress (mapped to 0.05..0.8, "refine").
// options.stage_done, when set, is called after "refine", "smooth" (if any) and "check" (if any).
RefineOutcome refine_stage(mesh::Triangulation& tri, const SizingField& f, const Box2& box,
                           const TriangulateOptions& options);

// The figures of a CDT + refinement run that the quality report states.
struct RunFigures {
  std::optional<double> cdt_s, refine_s;  // wall times (unset: stage not run)
  std::uint64_t segment_splits = 0, circumcenters = 0;  // Steiner points
  std::uint64_t angle_exempt = 0;          // RefineOutcome::angle_exempt
  double alpha = -1;                       // RefineOutcome::alpha
  double conforming_D = std::numeric_limits<double>::quiet_NaN();  // RefineStats::conforming_D
  Point2 conforming_D_at{0, 0};
};

// What the quality report states of the run (RunInfo) from its figures, the options and f (may be
// null); the predicate counters are read now.
quality::RunInfo run_info(const SizingField* f, const TriangulateOptions& options, const RunFigures& figures);

// Measure stage (core): f at the vertices when the mesh does not carry it, then the quality
// report (quality::compute_quality) against f (may be null), options.bound and the run's figures;
// `per_triangle`, when not null, gets the per-triangle values the writers store. Releases
// m.neighbours (the adjacency the report walks) afterwards unless `keep_adjacency` (the outputs
// that carry boundary lists read it: io::carries_boundaries).
QualityReport measure_mesh(MeshView& m, const SizingField* f, const TriangulateOptions& options,
                           const RunFigures& figures, quality::TriangleValues* per_triangle = nullptr,
                           bool keep_adjacency = false);

}  // namespace fdr
