// Step of the coast generalisation: widening of narrow water.
#pragma once
#include "coast/generalise.hpp"
#include "coast/geometry_ops.hpp"

namespace fdr::coast {

// Channels from close_width to widen_width wide are widened to about widen_width (their banks
// moved into the land), unless a widened piece would join two water bodies; each widened piece
// at least list_area large is reported (water_widened); res gets widened and widened_area.
// W unchanged when widen_width <= close_width or close_width is 0.
GeomPtr widen(GeomPtr W, const Options& o, Result& res);

}  // namespace fdr::coast
