// The spacing's bound from the layers' thickness: between two nearly parallel facets that lie close
// the PLC's local feature size is their distance, so the spacing of a terrain volume may not exceed
// a constant times the thickness of a layer near it.
#pragma once
#include <cstddef>
#include <string>
#include <vector>
#include "base/point3.hpp"
#include "sizing/spacing3d.hpp"
#include "terrain/surfaces.hpp"

namespace fdr::terrain {

struct LayerSpacing {
  // f <= factor * thickness in the cells around a layer (> 0).
  double factor = 1.0;
  // The bound grows away from a layer by at most this per metre (> 0), as the local feature size
  // does (it is 1-Lipschitz); below 1 so that the bounded field keeps a gradient under 1.
  double grade = 0.5;
  // Places where the bound fell below this (hmin) are listed.
  double hmin = 0;
};

// Where a layer's thickness took the spacing below hmin: the thinnest positive thickness of that
// layer over a TIN triangle, at the triangle's centroid (the stack's frame).
struct ThinPlace {
  std::size_t layer = 0;  // 0: between stack[0] and stack[1]
  Point3 at;               // centroid in xy, z half-way between the two surfaces
  double thickness = 0;
};

struct LayerSpacingResult {
  std::size_t cells_below_hmin = 0;  // grid cells whose value the bound took below hmin
  double smallest = 0;               // the smallest value in the grid afterwards
  // Per layer its thinnest place when that took the spacing below hmin (one entry per layer at
  // most, thinnest first).
  std::vector<ThinPlace> places;
};

// Lowers g (filled, values > 0, in the frame of tin) to min(g, B) where B is factor * thickness
// in every cell within one cell of a TIN triangle's prism of a layer (its thinnest positive
// corner thickness there), then graded away from the layers at `grade` (limit_gradient3), so
// the result is max(alpha of g, grade)-Lipschitz. Layers of zero thickness on a whole triangle
// (pinched out) bound nothing there. The layers are those of the layering (end_pinch_outs; empty:
// every surface on its own elevations). Throws Error(kUsage) on a factor or grade that is not > 0.
LayerSpacingResult bound_by_layer_thickness(sizing::Grid3& g, const Tin& tin, const std::vector<Surface>& stack,
                                           const LayerSpacing& opt, const Layering& layering = {});

}  // namespace fdr::terrain
