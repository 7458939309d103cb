// The boundary the report measures the mesh's coast against: the input domain as the mesher
// sees it, its polygons united. Adjacent input polygons (districts sharing borders) mesh as one
// domain, so their shared borders have no counterpart in the mesh and are not coast.
#pragma once
#include <optional>

#include "coast/generalise.hpp"

namespace fdr::gis {

// The union of `input` (coast::unite, the generalisation's first step), as rings: outer rings
// counter-clockwise, holes clockwise. Nothing when the union cannot differ from `input`: fewer
// than two polygons, or no two of them overlapping (`overlaps` false) nor sharing a vertex.
std::optional<coast::Polygons> united_domain(const coast::Polygons& input, bool overlaps);

}  // namespace fdr::gis
