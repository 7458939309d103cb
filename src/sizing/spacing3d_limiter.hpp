// Gradient limiting of a 3D spacing grid: h(x) = min over cells y of h(y) + alpha |x - y|.
#pragma once
#include "sizing/spacing3d.hpp"

namespace fdr::sizing {

// Lowers g in place so that it becomes alpha-Lipschitz: the 2D limiter's method
// (gradient_limiter.hpp) lifted to 3D. Every cell keeps the cell ("source") its value comes from
// and offers base(source) + alpha * exact Euclidean distance to its 26 neighbours, in raster
// sweeps along the eight octant orders (each cell taking the offers of the 13 neighbours already
// swept) until a round of eight sweeps changes nothing. Afterwards,
// for all 26-neighbours p, q (hence along any 26-connected path of cells):
//   g(q) <= g(p) + alpha |p - q|   (up to a relative 1e-12, see below).
// Each value is h(y) + alpha |x - y| for some cell y, so the result is never below the exact
// formula and never above the input.
// - Values never increase; decreases smaller than 1e-12 relative are ignored, which makes the
//   limiter idempotent and leaves an already alpha-Lipschitz grid bit for bit unchanged.
// - NaN cells stay NaN and neither receive nor pass values: propagation goes around them.
// - +inf cells ("no constraint") receive finite values where a finite source can reach them.
// - Anisotropic cells (dx, dy, dz different) use the true distances.
// - Cost: a read-only check on every thread first (would any offer of the first round lower a
//   cell?); an already alpha-Lipschitz grid returns there, unchanged. Otherwise the sweeps run
//   on one thread, 13 offers per cell and sweep. Same result for every thread count.
// Throws Error(kUsage) unless alpha is finite and >= 0; Error(kInternal) on a malformed grid;
// Error(kWorkLimit) if the sweeps do not settle (a pathological nodata maze).
void limit_gradient3(Grid3& g, double alpha);

}  // namespace fdr::sizing
