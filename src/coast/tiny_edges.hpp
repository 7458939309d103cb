// Step of the coast generalisation: tiny edges dropped where new coast meets the input's.
#pragma once
#include <cstdint>
#include <unordered_set>

#include "coast/generalise.hpp"

namespace fdr::coast {

// Where a cut or a widened bank meets the input coast, GEOS leaves a vertex a few metres from a
// corner (an arc point, an intersection point); the mesh would refine to that distance around
// it. A corner (turning by more than 30 degrees) that is not an input vertex (input_vertex, by
// point_key) and is nearer than `tiny` to a neighbour is dropped (the coast moves by less than
// that), in up to three passes, when the polygon stays valid; else the rings come back as given.
Rings drop_tiny_edges(Rings rings, const std::unordered_set<std::uint64_t>& input_vertex, double tiny);

}  // namespace fdr::coast
