// A fast sufficient test of polygon validity with the mesher's exact contact finder, and that
// finder on two cores.
#pragma once
#include <vector>

#include "base/types.hpp"
#include "coast/geometry_ops.hpp"
#include "pslg/segment_grid.hpp"

namespace fdr::coast {

// pslg::find_contacts on two cores for large inputs (segments split at the median of their left
// ends); a contact may be listed twice. For callers that use the contacts as a set.
pslg::Contacts find_contacts_2(const std::vector<Point2>& pts, const std::vector<pslg::Segment>& segs,
                               const std::vector<char>* alive);

// True when the polygon of `rings` (outer first) is surely valid: every ring simple, no two rings
// meeting, every hole inside the outer ring and none inside another. False: GEOS must decide.
bool surely_valid(const Rings& rings);

}  // namespace fdr::coast
