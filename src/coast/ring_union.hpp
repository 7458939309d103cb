// The union of a water polygon with pieces that overlap it, ring by ring: what the widening
// adds to the water without an overlay of the whole domain.
#pragma once
#include "coast/geometry_ops.hpp"

namespace fdr::coast {

// p with the pieces added, the pieces' interiors pairwise disjoint and each overlapping p. For
// p = O - (L_1 + ... + L_n) (outer ring O, holes L_i) and pieces D,
//   p + D = (O + D_O) - ((L_1 - D_1) + ... + (L_n - D_n)),
// D_O the pieces that cross O, D_i those that meet L_i: the outer ring is overlaid only with the
// pieces that cross it, each hole only with the pieces that reach into it (the holes in parallel,
// in their order, so any thread count gives the same result), and the holes left go back in
// without an overlay. Why: an island far from every piece is not touched at all, where GEOS's
// overlay of the whole nodes and places every hole of p. Null when a hole's remainder has holes
// of its own (cannot be put back as rings): the caller unites by union_pieces.
GeomPtr union_by_rings(const OGRPolygon& p, const OwnedPolygons& pieces, const char* what);

}  // namespace fdr::coast
