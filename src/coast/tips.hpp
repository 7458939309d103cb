// Step of the coast generalisation: the closing that keeps tips of land.
#pragma once
#include "coast/generalise.hpp"
#include "coast/geometry_ops.hpp"

namespace fdr::coast {

// Closing of W at close_width/2 (land thinner than close_width becomes water), except for tips
// of land that have no other land near their end (tip_clearance); *land_cut: the area of thin
// land that became water. Kept tips are counted in res.tips_kept.
GeomPtr closing_keep_tips(const OGRGeometry* W, const Options& o, Result& res, double* land_cut);

// The closing step: land thinner than close_width (spits, slivers of land between two waters,
// thin islands) becomes water, tips kept when tip_clearance > 0 (closing_keep_tips); the land
// taken away is added to res.land_removed_area. Why: a sliver of land leaves two coast segments
// a fraction of hmin apart, and the water around it would need elements that small. W unchanged
// when close_width is 0.
GeomPtr close_thin_land(GeomPtr W, const Options& o, Result& res);

}  // namespace fdr::coast
