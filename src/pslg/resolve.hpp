// Resolution of messy constraints with Triangle .poly semantics: the one resolver used by the
// .poly path, the library (cdt::CdtOptions::resolve) and, through pslg::clean, the GIS path.
#pragma once
#include <string>
#include <vector>
#include "pslg/clean.hpp"
#include "pslg/pslg.hpp"

namespace fdr::pslg {

struct ResolveOptions {
  // true: no repair; validate() throws Error(kInvalidGeometry) naming the first conflict.
  bool strict = false;
  std::string source = "input";   // named in error messages
  std::size_t max_iterations = 64;  // cap on crossing-split rounds (clean's cascade cap)
  // Snap rounding with a tolerance of max(2^-36 * extent, 2^-48 * largest |coordinate|):
  // vertices closer than it merge ("snap"), a vertex that close to a segment splits it
  // ("snap_to_segment"). false: exact coincidences only.
  bool snap = true;
};

// Returns a PSLG without conflicts: exact duplicate vertices merged into the lowest id,
// zero-length segments dropped, duplicate segments merged into the first copy (marker kept),
// a vertex in a segment's interior splits it, collinear overlaps are cut at each other's
// endpoints (then merged), crossing segments are split at their rounded intersection point,
// re-checked with exact predicates until nothing meets other than at shared endpoints (a
// segment is routed through any vertex a rounded point would move it across). Implemented by
// pslg::clean with boundary_parity = false and no snapping, so the GIS path shares the core.
// Every fix is appended to `repairs`; Repair::ids name input vertex ids and input segment
// indices (Repair::part is the input segment index). Vertex ids of the result: surviving input
// vertices keep their order, new intersection points follow. Segment::part of the result is
// the input segment's part. Non-finite coordinates and out-of-range indices always throw
// Error(kInvalidGeometry) naming the source, as does the cascade cap.
Pslg resolve(const Pslg& in, const ResolveOptions& options, std::vector<Repair>* repairs);

}  // namespace fdr::pslg
