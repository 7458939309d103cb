// EdgeKind: the kind of a constrained edge, shared vocabulary of gis (segment markers), pslg,
// mesh (MeshEdge::marker) and io (boundary layers / nodestrings).
#pragma once
#include <cstdint>

namespace fdr {

// Kind of a constrained (boundary or interior) edge; stored as the segment marker.
enum class EdgeKind : std::int32_t {
  kNone = 0,       // unconstrained / unknown
  kLand = 1,       // mainland coast (or generic outer boundary)
  kIsland = 2,     // island coast (hole boundary)
  kOpen = 3,       // open-ocean boundary
  kBreakline = 4,  // interior constraint (river, levee, channel)
};

}  // namespace fdr
