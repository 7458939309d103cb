// Loose breakline ends and fixed points put on a boundary segment they nearly touch.
#pragma once
#include <vector>
#include "pslg/clean.hpp"
#include "pslg/pslg.hpp"

namespace fdr::pslg {

// Breakline ends and free points lying within `tol` of a boundary segment they do not touch are
// put on it: the segment is split at the point. Returns one Repair per split (local coordinates).
// (Why: see snap_loose_ends.cpp.)
std::vector<Repair> snap_loose_ends(Pslg& g, double tol);

}  // namespace fdr::pslg
