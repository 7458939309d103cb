// The coast generalisation of a global run in ground metres: land polygons within reach of each
// other form groups, groups are batched by region, and every batch is generalised in a
// stereographic plane centred on it, where the scale factor is near 1, with the ground widths.
//
// Why not in the global plane: the global projection's scale factor runs from 1 to about 100
// (near its pole, inside Antarctica), so constant widths there stand for ground widths up to 100
// times too small, and the generalisation works at a far finer scale than the mesh needs.
#pragma once
#include <cstddef>
#include <vector>

#include "base/types.hpp"
#include "coast/generalise.hpp"

namespace fdr::gis {

// How near (ground metres) two land polygons must come to be generalised together: twice the
// farthest any step of the generalisation looks or moves the coast (widening, islet triangles
// with their shift and clearance, tips, gaps, reconnections), so that land in different groups
// stays out of each other's reach.
double group_reach(const coast::Options& ground);

// Groups of rings (lon/lat, cleaned as sphere_ring does) whose coasts come within `reach_m` of
// each other on the sphere (edges whose chords are within reach_m plus the arcs' sagittas: a few
// metres for edges of a tenth of a degree); every ring in exactly one group, rings ascending in a
// group, groups ordered by their first ring.
std::vector<std::vector<std::size_t>> land_groups(const std::vector<std::vector<LonLat>>& rings, double reach_m);

struct GeneralisedLand {
  std::vector<std::vector<LonLat>> rings;  // exterior rings of the generalised land, lon/lat
  std::vector<char> holds_pole;            // per ring: it holds the given pole
  // The generalisation's figures summed over the batches, areas in ground square metres (a
  // tile's counts include its halo, which its neighbours count too); repairs with `where` as
  // (longitude, latitude), a tile's those in its core only.
  coast::Result result;
  std::size_t groups = 0, batches = 0;
  double max_scale = 1;  // the largest scale factor over the batches' planes (1 at their centres)
};

// Generalises the land `rings` (lon/lat, cleaned and densified) as the water around them with
// `ground` (widths in ground metres, areas in ground square metres), batch by batch in parallel
// (base/parallel.hpp; the same result whatever the thread count). Water enclosed by land is
// land in the result (the ocean is what is meshed). Output edges are at most step_deg long.
GeneralisedLand generalise_land(const std::vector<std::vector<LonLat>>& rings, LonLat pole,
                                const coast::Options& ground, double step_deg);

}  // namespace fdr::gis
