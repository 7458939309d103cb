// Step of the coast generalisation: a large water body cut off by a closed connection gets that
// connection back, widened to one element across, instead of being removed.
//
// Why: the openings close every connection narrower than --min-feature; a lagoon or a fjord
// behind such an inlet was then removed as cut off, and a tide or surge model lost its whole
// prism, the coast the model saw moving by the body's whole size. The lost connection is the
// water of the input body that the result no longer holds and that meets both the body and the
// rest of the water; grown by half the connection width, it is at least that wide and the mesh
// keeps elements near hmin across it.
#pragma once
#include "coast/generalise.hpp"
#include "coast/geometry_ops.hpp"

namespace fdr::coast {

// The water of `body` that `result` lost (body minus the result's pieces `piece` and `main`,
// shrunk by `hair`: hairlines left out) and that meets both `piece` and `main`: the smallest such
// connected part, searched in a box around `piece` grown by `reach` and doubled (up to the
// body's box) while a part that meets `piece` reaches the box's edge. Null: none found.
GeomPtr lost_connection(const OGRPolygon& body, const OGRPolygon& piece, const OGRPolygon& main, double reach,
                        double hair);

// The lost connection grown by half of `width` (a channel of any width at least `width` across),
// kept inside `inbox` (open boundaries do not move). Null when it would meet one of `others`
// (water of other input bodies, which the model keeps apart).
GeomPtr widened_connection(const OGRGeometry& connection, double width, const OGREnvelope& inbox,
                           const std::vector<const OGRPolygon*>& others);

}  // namespace fdr::coast
