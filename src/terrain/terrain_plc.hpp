// The PLC of a terrain volume: a stack of surfaces on one TIN lifted to 3D facets, vertical side
// walls along the TIN's boundary, and one region (material) per layer.
#pragma once
#include <cstdint>
#include <limits>
#include <string>
#include <vector>
#include "plc/plc.hpp"
#include "terrain/surfaces.hpp"

namespace fdr::terrain {

// Boundary markers of the facets (the outputs' physical surface groups): the top, the base, the
// side walls, then one per horizon (kHorizonMarker0 + k for the k-th horizon from the top).
inline constexpr std::int32_t kTopMarker = 1;
inline constexpr std::int32_t kBaseMarker = 2;
inline constexpr std::int32_t kSideMarker = 3;
inline constexpr std::int32_t kHorizonMarker0 = 4;

// TerrainPlc::ids where a surface has no vertex (no facet of the PLC uses it there).
inline constexpr VertexId kNoVertex = std::numeric_limits<VertexId>::max();

struct TerrainPlc {
  plc::Plc plc;
  // ids[s][v]: the PLC vertex of stack surface s at TIN vertex v, or kNoVertex where no facet
  // uses it. A surface that meets the one above it at v (a pinch-out) shares that vertex id, so
  // the two surfaces share facets there.
  std::vector<std::vector<VertexId>> ids;
};

// Builds the PLC from a clamped stack (clamp_surfaces), top first, base last, under a layering
// (end_pinch_outs; empty: every surface on its own elevations):
// - vertices: (xy, z) per stack surface and TIN vertex that a facet uses, one vertex where
//   surfaces coincide;
// - facets: every TIN triangle on every surface (at its layering's elevations), except where it
//   coincides with the one above (all three vertices shared), so a layer of zero thickness has no
//   facets of its own;
// - walls: over every TIN edge, the vertical polygons between the two sides' columns where the
//   material differs: along the TIN's boundary (the outside beyond it) the side walls, one per
//   layer (a triangle where it is pinched at one end); inside, where the layering differs between
//   the edge's two triangles, the ends of layers (a horizon's marker: the lower surface of the
//   upper layer);
// - regions: layer i (between surfaces i and i+1) has material i + 1, named "upper-lower" after
//   its surfaces, with one region point per connected part of positive thickness.
// Every facet is a triangle or a vertical polygon whose xy lie on one line, so facets are planar
// and meet exactly. Material i + 1 and the markers above are named in the PLC.
TerrainPlc build_terrain_plc(const Tin& tin, const std::vector<Surface>& stack, const Layering& layering = {});

// The volume of each layer as triangulated: over every TIN triangle the prism between the two
// linear surfaces (at the layering's elevations), area times the mean thickness at its corners
// (exact for linear surfaces).
std::vector<double> layer_volumes(const Tin& tin, const std::vector<Surface>& stack, const Layering& layering = {});

// The TIN's boundary edges (used by a single triangle), each oriented as in its triangle.
std::vector<std::array<VertexId, 2>> boundary_edges(const Tin& tin);

}  // namespace fdr::terrain
