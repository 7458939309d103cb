// The water of a global run (--global): the sphere minus the land polygons, as one planar domain
// in the stereographic frame whose point at infinity lies inside the land mass holding the pole.
#pragma once
#include <cstdint>
#include <string>
#include <vector>
#include "base/types.hpp"
#include "coast/generalise.hpp"
#include "gis/global_sphere.hpp"
#include "gis/vector_input.hpp"

namespace fdr::gis {

struct GlobalWater {
  // Water polygons in the projection's world coordinates (local frame, origin 0): rings without
  // the closing repeat, the outer ring (the coast of the pole's land mass) first, then holes.
  std::vector<std::vector<std::vector<Point2>>> polygons;
  std::string file, layer;
  std::int64_t pole_fid = -1;          // the land feature holding the pole (the outer coast)
  std::size_t land_polygons = 0;       // land polygons read
  std::size_t land_holes_filled = 0;   // holes of land polygons (lakes, enclosed seas) taken as land
  std::size_t antimeridian_rings = 0;  // rings with vertices on longitude +-180 (joined across it)
  std::size_t densify_points = 0;      // points added along long lon/lat edges
  double water_area_m2 = 0;            // on the sphere (spherical polygon areas of the rings)
  // With the generalisation: the water as read (polygons as above), its area on the sphere, the
  // generalisation's figures (repairs in the projection's world coordinates) and its batches.
  std::vector<std::vector<std::vector<Point2>>> input_polygons;
  double input_area_m2 = 0;
  coast::Result features;
  std::size_t groups = 0, batches = 0;
  double max_batch_scale = 1;  // the largest scale factor of the batches' planes
};

// A lon/lat ring as the sphere sees it: longitude -180 written as 180 (one meridian), every
// point at a pole given longitude 0 (one point), repeated points and back-and-forth spikes
// (a -> b -> a) removed, cyclically, until none is left. A polygon cut at the antimeridian and
// closed along a pole's latitude (how GSHHG-style files store Antarctica) becomes its coastline.
std::vector<LonLat> sphere_ring(std::vector<LonLat> ring);

// True when the lon/lat ring (as read, before sphere_ring) holds `pole`: a pole at latitude -90 or
// 90 is held by a ring with a vertex there; another point by the even-odd rule in lon/lat.
bool ring_holds_pole(const std::vector<LonLat>& ring, LonLat pole);

// Points along every edge longer than step degrees in longitude or latitude (the lon/lat line),
// so that the projected ring follows the edge (an edge across the antimeridian the short way
// round); returns how many were added.
std::size_t densify_lonlat(std::vector<LonLat>& ring, double step_deg);

// Reads `land` (polygons, any OGR source and CRS; s_srs for a layer without one), finds the land
// polygon holding proj.pole() (its coast becomes the outer ring; exit kInvalidGeometry when none
// holds it or its coast still reaches the pole), fills the holes of every land polygon, densifies
// the rings (step_deg), projects them and subtracts all other land (united: the parts of a
// polygon cut at the antimeridian meet again) with GEOS. With `generalise` (widths in ground
// metres), the land is generalised first (global_generalise.hpp) and the water as read is kept
// in input_polygons.
GlobalWater global_water(const LayerRef& land, const std::string& s_srs, const SphereStereo& proj, double step_deg,
                         const coast::Options* generalise = nullptr);

}  // namespace fdr::gis
