// Gradient limiting of a gridded spacing: h(x) = min over y of h(y) + alpha |x - y|.
#pragma once
#include "sizing/grid.hpp"

namespace fdr::sizing {

// Lowers g in place so that it becomes alpha-Lipschitz (Persson's gradient limiting):
//   h(x) = min over cells y of ( h(y) + alpha * |x - y| ),
// evaluated by source propagation: every cell keeps the cell ("source") its value comes
// from and offers base(source) + alpha * exact Euclidean distance to its 8 neighbours (and
// the 8 knight-move cells, which relays sources past competing ones on anisotropic cells), in
// alternating forward/backward raster sweeps until a sweep pair changes nothing (typically
// 2-4 pairs, O(n) each). Afterwards, for all 8-neighbours p, q:
//   g(q) <= g(p) + alpha |p - q|   (up to a relative 1e-12, see below),
// hence along any 8-connected path. Each value is h(y) + alpha |x - y| for some y, so the
// result is never below the exact formula and never above the input. Against a brute-force
// evaluation of the formula on random grids it is exact for square cells; on anisotropic cells
// a few cells exceed it slightly, because the neighbour and knight moves miss some directions.
// - Values never increase; decreases smaller than 1e-12 relative are ignored, which makes
//   the limiter idempotent and leaves an already alpha-Lipschitz grid bit-for-bit unchanged.
// - NaN cells stay NaN and neither receive nor pass values: propagation goes around them
//   (8-connected: a diagonal step may pass the corner between two NaN cells; a knight step
//   needs both cells it crosses to hold data).
// - +inf cells ("no constraint") receive finite values where a finite source can reach them.
// - Anisotropic cells (dx != dy) use the true distances.
// - Cost: a read-only check on max_threads() threads first (would any offer of the first sweep
//   pair lower a cell? a margin pass, then the offers' exact tests); an already alpha-Lipschitz
//   grid returns there, unchanged (the usual case for the GIS rules). Otherwise the sweeps run on
//   one thread, O(cells) per sweep pair. Same result for every thread count.
// Throws Error(kUsage) unless alpha is finite and >= 0; Error(kInternal) on a malformed grid.
void limit_gradient(Grid& g, double alpha);

}  // namespace fdr::sizing
