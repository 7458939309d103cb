// Step of the coast generalisation: water left narrower than the minimum feature width closed
// (the land on both sides joined across it), or widened to one element across where closing it
// would cut off a large water body.
//
// Why: water narrower than --min-feature (hmin/10) cannot be meshed without edges as short as
// its width, whichever made it: the input (a channel, two islets almost touching) or a step
// (two tips of land left facing each other where thin land was cut). The mesh's time step is
// set by its shortest edge, so such a gap costs every element of the model. Closing it moves the
// coast by about the gap's width; each closure is listed (`narrow_gap_closed`, its area and
// place). A water body that closing would cut off and that is large keeps its connection,
// widened to `connect_width` like the openings' reconnections (`narrow_gap_widened`).
#pragma once
#include <vector>

#include "coast/generalise.hpp"
#include "coast/geometry_ops.hpp"

namespace fdr::coast {

// The water bridge over a gap: the convex hull of the coast of `rings` within r of c (the
// vertices inside the disk and the points where the segments cross its circle, a crossing within
// `snap` of its segment's end replaced by that end, so that the new coast has no edge shorter
// than snap there). Empty when the coast there does not span an area. The hull lies in the disk
// (but for the snaps), so its sides meet the coast only at its corners.
std::vector<Point2> gap_bridge(const Rings& rings, Point2 c, double r, double snap);

// Closes every place where the water of res.polygons is narrower than o.min_feature
// (narrow_gaps): the bridge of radius o.min_feature over the gap is taken out of the water, and
// the water the bridge cuts off from its polygon's largest piece is removed with it; where that
// removes a piece of at least o.gap_body_area, the gap is instead widened to o.connect_width
// (reconnect.hpp's widened_connection, inside `inbox`; kept as it is when that would meet
// another polygon). Up to three rounds (a long channel closes bridge by bridge). Crossings are
// snapped within close_width / 4 (gap_bridge).
// Repairs `narrow_gap_closed` (size: the water removed, m^2) and `narrow_gap_widened` (size: the
// land that became water), counted in res.closed / closed_area and res.reconnected /
// reconnected_area; res.output_area follows. Nothing when o.min_feature or o.gap_body_area is 0.
void close_narrow_gaps(const Options& o, const OGREnvelope& inbox, Result& res);

}  // namespace fdr::coast
