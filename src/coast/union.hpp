// Step 1 of the coast generalisation: union of overlaps.
#pragma once
#include "coast/generalise.hpp"
#include "coast/geometry_ops.hpp"

namespace fdr::coast {

// Valid copies of every polygon (made valid when GEOS says they are not), then their union:
// overlapping water polygons from merged layers become one (the parity rule of the mesher would
// make the overlap a hole). Each overlapping pair is reported (polygons_united); res gets
// united, united_overlap_area, input_area and input_pieces.
GeomPtr unite(const Polygons& input, Result& res);

}  // namespace fdr::coast
