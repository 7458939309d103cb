// Step of the coast generalisation: removal of water cut off by a closed connection.
#pragma once
#include "coast/generalise.hpp"
#include "coast/geometry_ops.hpp"

namespace fdr::coast {

// One mesh piece per input water body (W0): the pieces of R cut off by a closed connection are
// removed (a water body the model cannot reach), keeping the largest piece of each input body;
// each removal is reported (cut_off_water_removed) and counted in res.cut_off, cut_off_area. A
// piece of at least connect_area keeps its lost connection instead, widened to connect_width
// (reconnect.hpp; water_connection_widened, counted in res.reconnected, reconnected_area).
GeomPtr remove_cut_off(GeomPtr R, const OGRGeometry& W0, const Options& o, Result& res);

}  // namespace fdr::coast
