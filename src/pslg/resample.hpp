// Boundary resampling to the spacing f: every chain of segments (coast, island, open boundary,
// breakline) is re-discretised so that its vertex spacing follows f, within a shape tolerance.
//
// Why: GIS coastlines carry vertices every few metres; a mesh with spacing f keeps every one of
// them as a mesh vertex, so the smallest element is set by the digitising, not by f, and the
// FDR bounds (which need f <= D * lfs) fail. Resampling makes the input's local feature size
// follow f.
//
// Method, per chain between anchor vertices (degree != 2, marker or part change, point
// markers, closed rings: the sharpest corner):
//   1. Douglas-Peucker key vertices with tolerance tol = tolerance_factor * f: the corners the
//      tolerance cannot remove;
//   2. between consecutive key vertices, points on the input polyline at equal steps of
//      integral ds / (spacing_factor * f), so spacing follows f;
//   3. a piece whose chord strays more than tol from an input vertex gets that vertex back;
//   4. a small ring (an island a few f round) whose plan has a piece under 0.6 f: n points at
//      equal steps along it from the start that makes the shortest chord longest within tol.
// Then, with exact predicates, every piece that crosses or touches another segment, or whose
// swept region (between the new chord and the input polyline) contains any other vertex, is put
// back to its input vertices, until none is left (rings are never merged, split or crossed).
#pragma once
#include <cstddef>
#include <functional>
#include <vector>
#include "pslg/pslg.hpp"

namespace fdr::pslg {

struct ResampleOptions {
  std::function<double(Point2)> spacing;  // f in the local frame (> 0)
  double spacing_factor = 1.3;            // target distance between boundary vertices / f
  double tolerance_factor = 0.25;         // max distance input vertex - new chain / f
  std::size_t max_rounds = 100;           // conflict rounds before whole chains are put back
  // The domain is the parity of the boundary segments (GIS inputs): a sharp wedge that resampling
  // makes outside it (a needle of land) is allowed; otherwise every side is checked.
  bool domain_by_parity = false;
  // A ring without anchors at most 12 steps round whose plan has a piece under 0.6 f is planned
  // again as points at equal steps from the best start (resample_plan.cpp, small_ring).
  bool small_rings = true;
};

struct ResampleStats {
  std::size_t vertices_in = 0, vertices_out = 0;  // boundary/breakline vertices
  std::size_t chains = 0;
  std::size_t pieces = 0, pieces_restored = 0;    // pieces put back to the input (conflicts)
  std::size_t rounds = 0;
  double max_deviation = 0;                       // max distance input vertex -> new chain
};

// Returns the resampled PSLG (points not on any segment are kept unchanged; holes, regions and
// origin copied). The input must be clean (pslg::clean): no crossings, no duplicates.
Pslg resample(const Pslg& in, const ResampleOptions& options, ResampleStats* stats = nullptr);

}  // namespace fdr::pslg
