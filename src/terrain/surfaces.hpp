// The surfaces of a terrain volume on one 2D triangulation: the top (the DEM), the horizons and
// the base, each an elevation per vertex, ordered from the top down and clamped so that none
// crosses another.
#pragma once
#include <array>
#include <cstddef>
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

}  // namespace fdr::terrain
