// The surfaces of a terrain volume on one 2D triangulation: the top (the DEM), the horizons and
// the base, each an elevation per vertex, ordered from the top down and clamped so that none
// crosses another.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>
#include "base/types.hpp"

namespace fdr::terrain {

// The 2D triangulation every surface shares (the terrain TIN): vertices in the local frame and
// counter-clockwise triangles.
struct Tin {
  std::vector<Point2> xy;
  std::vector<std::array<VertexId, 3>> triangles;
};

// One surface: a name for the outputs (top, a horizon's name, base) and its elevation at every
// TIN vertex (metres, positive up).
struct Surface {
  std::string name;
  std::vector<double> z;
};

// What clamp_surfaces changed: per surface (same order as the stack), the vertices moved down to
// the surface above, those moved up to the base, and those of a layer thinner than the minimum
// thickness moved onto the surface above (collapsed).
struct ClampCounts {
  std::vector<std::size_t> lowered, raised, collapsed;
};

// Orders a stack top, horizons..., base into non-crossing surfaces: every horizon is clamped
// between the surface above it (already clamped) and the base, vertex by vertex, so a horizon
// that rises above the DEM or one above it follows that surface there (its layer pinches out).
// Where a layer above a horizon is thinner than min_thickness (> 0) at a vertex, the horizon
// moves onto the surface above there (the layer collapses locally; the same onto the base for a
// thin layer above the base): a pinch-out then rises from
// zero to at least min_thickness over one TIN edge, so the facets that meet there do so at an
// angle of about min_thickness / edge length instead of an arbitrarily small one.
// Throws Error(kInvalidGeometry) when the stack has fewer than two surfaces or sizes differ, when
// the base is not strictly below the top at some vertex (naming the first such vertex and its
// coordinates in `world` terms: origin + xy), or when a horizon lies outside the top and base
// everywhere (its layer would be empty).
ClampCounts clamp_surfaces(std::vector<Surface>& stack, const Tin& tin, Point2 origin, double min_thickness = 0);

// The minimum layer thickness when none is given: kMinThicknessPerHmin of the smallest spacing,
// and no less than the TIN's vertical tolerance (0 when neither is known). Between the two facets
// of a layer the local feature size is its thickness, and the spacing follows it
// (layer_spacing.hpp), so a layer thinner than the resolution asks for elements finer than hmin
// over all its extent, and a pinch-out for a wedge as thin as the layer's last thickness before
// zero. The fraction is the one below which the 2D coast's repairs remove land (--close-width):
// features under it are not resolved but removed, and the finest spacing a layer asks for stays
// within that factor of hmin.
inline constexpr double kMinThicknessPerHmin = 0.15;
double default_min_thickness(double hmin, double vertical_tol);

// Which surface of the stack each surface follows over each TIN triangle: surface s lies on
// stack[at(t, s)] over triangle t. Empty (surfaces == 0) is the identity, every surface on its own
// elevations everywhere. at(t, .) never decreases with s, starts at the top and ends at the base,
// so layer s over t lies between stack[at(t, s)] and stack[at(t, s + 1)] (nothing when equal).
struct Layering {
  std::size_t surfaces = 0;
  std::vector<std::uint16_t> on;  // on[t * surfaces + s]
  std::size_t at(std::size_t t, std::size_t s) const { return surfaces ? on[t * surfaces + s] : s; }
  bool identity() const { return surfaces == 0; }
};

// The elevation of surface s at corner k of triangle t under a layering.
inline double corner_z(const std::vector<Surface>& stack, const Layering& l, const Tin& tin, std::size_t t,
                       std::size_t s, int k) {
  return stack[l.at(t, s)].z[tin.triangles[t][k]];
}

// What end_pinch_outs changed: per layer (0: below the top), the TIN triangles it was removed from
// and the volume they held (moved to the layer above or below), and the largest vertical move of
// a surface with the TIN vertex where it happened.
struct PinchOutRepair {
  Layering layering;
  std::vector<std::size_t> triangles;
  std::vector<double> volume;
  double largest_move = 0;
  VertexId largest_at = 0;
};

// Ends every pinch-out at a vertical wall instead of a wedge. Where a layer is zero at some
// corners of a TIN triangle and positive at others (it thins to nothing inside the triangle), its
// two facets would meet there at the angle of its last thickness over the triangle's width, and
// no tetrahedra conforming to both have good angles in such a wedge. So the layer is removed from
// that triangle: its lower surface follows its upper one there (for the layer above the base, its
// upper surface follows the base), processed from the top down so that a removal may extend the
// layer below or above, which then has positive thickness at every corner. Afterwards every layer
// over every triangle is either empty or positive at all three corners, and where it ends the PLC
// closes it by vertical walls over TIN edges (build_terrain_plc) as high as its thickness there
// (at least the minimum thickness of clamp_surfaces), meeting the surfaces at about right angles.
PinchOutRepair end_pinch_outs(const Tin& tin, const std::vector<Surface>& stack);

}  // namespace fdr::terrain
