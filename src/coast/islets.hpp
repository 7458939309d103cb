// Steps of the coast generalisation: islands below the resolution (islets) replaced by
// triangles, joined to nearby land or removed; the triangles added after the widening; island
// remnants that the closing left below the resolution.
#pragma once
#include "coast/generalise.hpp"
#include "coast/geometry_ops.hpp"
#include "coast/islet_placer.hpp"

namespace fdr::coast {

// Islands below min_island_area become triangles where there is room (placer.tris, added to the
// water later by add_islet_triangles), else are joined to land nearer than islet_side
// (join_islets), else become water; islands below grow_island_area are grown by grow_island.
// Why grow or replace rather than drop: a dropped island near the coast moves the coastline the
// model sees by its whole distance. Every change is reported.
GeomPtr replace_islets(GeomPtr W, IsletPlacer& placer, const Options& o, Result& res);

// The islets' triangles go in after the widening: placed before it, the narrow water they leave
// to the next land (at least islet_side / 2 at the corners) was widened into them, and they came
// out with sides under hmin. The triangles are disjoint and inside the water with room around
// them (the widening only added water): they become holes without an overlay (minus_disjoint).
GeomPtr add_islet_triangles(GeomPtr W, const IsletPlacer& placer);

// Islands that the closing shrank below min_island_area (thin islands leave small remnants):
// a triangle where there is room on the land as it is now, else water (reported). Islets'
// triangles already placed stay.
GeomPtr replace_remnants(GeomPtr R, IsletPlacer& placer, const Options& o, Result& res);

}  // namespace fdr::coast
