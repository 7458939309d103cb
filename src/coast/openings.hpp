// Step of the coast generalisation: the openings, channels kept and dead ends closed.
#pragma once
#include "coast/generalise.hpp"
#include "coast/geometry_ops.hpp"

namespace fdr::coast {

struct TwoOpenings {
  GeomPtr O1, O2;
};
// The openings O1 = open(W, r1) and O2 = open(W, r2) (a copy of W for r2 = 0), each with W's exact
// coast given back where it runs within `hair` of it (CoastRestorer), so that the two coincide
// bitwise there. Each is what the opening and restoration of W alone give (the same for any
// thread count).
TwoOpenings two_openings(const OGRGeometry& W, double r1, double r2, double hair, bool full_rounds = false);

// The openings O1 = open(W, close_width/2) and O2 = open(W, min_feature/2); each piece of
// O2 - O1 touching two or more pieces of O1 is a channel between water bodies (kept, counted in
// res.channels_kept), one touching none is a water body of its own (kept), one touching one is a
// dead end (closed). The result is O1 with the kept pieces, opened once more at the connection
// scale where kept parts touch at a point. A copy of W when close_width is 0.
GeomPtr open_water(const GeomPtr& W, const Options& o, Result& res);

}  // namespace fdr::coast
