// The coast generalisation (resolution filter) for water polygons, GEOS through OGR: unites
// overlapping polygons, closes water narrower than the mesh can resolve while keeping
// connections between water bodies, replaces or joins islands smaller than the resolution, keeps
// thin tips of land, widens narrow channels. Every change is reported.
//
// Why morphological opening: the FDR bounds (paper, Section 5) need f <= D * lfs; a channel
// narrower than hmin forces elements narrower than hmin. The opening of the water W by a disk of
// radius r, (W - r) + r, removes exactly the parts of W that no disk of radius r fits in (narrow
// inlets, gaps between islands and the coast, slivers) and rounds convex water corners with
// radius r, and leaves the rest of the coast where it is. Two openings are used:
//   O1 = open(W, close_width/2)   what the resolution keeps,
//   O2 = open(W, min_feature/2)   what is wide enough to keep as a connection;
// a piece of O2 - O1 that touches two or more pieces of O1 is a channel joining water bodies
// (kept), a piece touching none is a small water body of its own (kept), a piece touching one is
// a dead end (closed). Result R = O1 + kept pieces; W - R is listed as repairs.
//
// The steps, in order (one file each): union.hpp, islets.hpp, widen.hpp, tips.hpp (closing),
// openings.hpp, cut_off.hpp, islets.hpp (remnants), restore.hpp, removed.hpp, tiny_edges.hpp,
// gap_closure.hpp, narrow_gaps.hpp.
#pragma once
#include <cstddef>
#include <memory>
#include <vector>

#include "base/types.hpp"
#include "pslg/clean.hpp"

namespace fdr::coast {

// Polygons in the local frame: rings (outer first, then holes), without the closing repeat.
using Rings = std::vector<std::vector<Point2>>;
using Polygons = std::vector<Rings>;

struct Options {
  double close_width = 0;      // dead-end water narrower than this is closed (0: no opening)
  double min_feature = 0;      // connections narrower than this are closed too (<= close_width)
  double min_island_area = 0;  // islands (holes) with a smaller area are removed (m^2); 0 keeps all
  double grow_island_area = 0; // islands with a smaller area (but >= min_island_area) are grown
  double grow_island = 0;      // ... by this distance (m)
  double list_area = 0;        // removed water pieces at least this large are listed one by one
  double widen_width = 0;      // water narrower than this (and at least close_width wide) is
                               // widened to about this width (m); 0: not widened
  double islet_side = 0;       // an island below min_island_area with no other land within this of
                               // its replacement becomes a triangle of this side (m); 0: removed
  double islet_shift = 0;      // no room at its centroid: the triangle may move up to this far from it
  bool join_islets = false;    // an islet with no room for its triangle is joined to land nearer
                               // than islet_side (convex hull with that coast) instead of removed
  double islet_clearance = 0;  // every islet triangle, join and cluster hull keeps this from all
                               // other land, and islets nearer than this to each other are
                               // handled as one cluster (islet_clusters.hpp) (m); 0: the rules
                               // without it (islet_placer.hpp)
  double connect_area = 0;     // a water body at least this large (m^2) cut off by a closed
                               // connection gets that connection widened instead of being
                               // removed (cut_off.hpp); 0: every cut-off body is removed
  double connect_width = 0;    // ... to at least this width (m)
  double gap_body_area = 0;    // water left narrower than min_feature is closed, unless that cuts
                               // off a water body at least this large (m^2), whose connection is
                               // widened to connect_width (gap_closure.hpp); 0: neither
  double narrow_gap = 0;       // water left narrower than this is listed, place by place
                               // (narrow_gaps.hpp, narrow_gap_kept); 0: not listed
  double tip_clearance = 0;    // tips of land thinner than close_width stay land unless other
                               // land is this near their end (m); 0: every thin part is cut
  bool defer_removed = false;  // the listing of removed water (input minus result: thousands of
                               // pieces on a large input) goes on on another thread after
                               // generalise returns; finish_removed() adds it to the result
  // With defer_removed: the listing starts at once (beside the rest of the read) when the process
  // holds at least this many bytes there, a large input whose read goes on long enough to hide
  // it and whose filter's peak dwarfs what the spacing stage adds; else the caller starts it
  // (start_removed). 0: never at once.
  std::size_t early_listing_rss = 0;
  // Cross-checks for tests (the same result by slower paths):
  bool diff_overlay = false;         // every difference by GEOS's overlay of the whole
  bool restore_full_rounds = false;  // every round of the coast restoration examines everything
};

// The listing of removed water: its repairs (narrow_water_closed) and figures.
struct RemovedWater {
  std::vector<pslg::Repair> repairs;
  std::vector<double> areas;      // every removed piece counted, in order (added to closed_area)
  std::size_t closed = 0, corner_pieces = 0;
};
struct PendingRemoved;  // removed.hpp

struct Result {
  Polygons polygons;                 // outer rings counter-clockwise, holes clockwise
  std::vector<pslg::Repair> repairs; // local coordinates
  std::size_t input_pieces = 0;      // connected water bodies of the input (after union)
  std::size_t output_pieces = 0;
  std::size_t united = 0;            // overlapping polygon pairs united
  double united_overlap_area = 0;
  std::size_t closed = 0;            // listed closures (narrow water, dead ends)
  double closed_area = 0;            // area of every removed water piece (m^2)
  std::size_t corner_pieces = 0;     // removed pieces below list_area (corner rounding, slivers)
  std::size_t channels_kept = 0;     // narrow connections kept (O2 - O1 pieces joining bodies)
  std::size_t cut_off = 0;           // water bodies cut off by a closed connection, removed
  double cut_off_area = 0;
  std::size_t reconnected = 0;       // water bodies cut off whose connection was widened instead
  double reconnected_area = 0;       // land that became water in those connections (m^2)
  std::size_t narrow_gaps = 0;       // places where the water stays narrower than narrow_gap
  std::size_t narrow_gaps_made = 0;  // ... of them, where the generalisation moved the coast
  double land_removed_area = 0;      // land thinner than close_width that became water (m^2)
  std::size_t widened = 0;           // pieces of narrow water widened
  double widened_area = 0;           // land that became water by widening (m^2)
  std::size_t islets_replaced = 0;   // islands below --min-island kept as triangles of islet_side
  std::size_t islets_joined = 0;     // islands below --min-island joined to land nearer than islet_side
  double islets_joined_area = 0;     // water between them that became land (m^2)
  std::size_t tips_kept = 0;         // thin land tips (and thin islands) kept instead of cut
  std::size_t islands_grown = 0;
  double islands_grown_area = 0;     // land added
  std::size_t islands_removed = 0;
  double islands_area = 0;
  double input_area = 0, output_area = 0;
  double close_width = 0;            // the close width used (0: no opening)
  // With Options::defer_removed: the removed-water listing still running (null without);
  // closed, closed_area, corner_pieces and repairs lack it until finish_removed().
  std::shared_ptr<PendingRemoved> removed_pending;
};

// The generalisation at resolution hmin as fdrmesh runs it by default (every width a fraction of
// hmin, every area of hmin^2), so that the CLI, the global path and the tests share one set.
Options resolution_options(double hmin);

// Throws Error(kInvalidGeometry) when GEOS fails or nothing is left.
Result generalise(const Polygons& input, const Options& options);

// Starts a deferred removed-water listing on a thread of its own (with two threads allowed), so
// that it runs beside what the caller does next, its allocations on an arena of its own
// (OwnArena) when `own_arena`; finish_removed then only waits. Nothing if it already runs.
void start_removed(Result& res, bool own_arena = true);

// Waits for a deferred removed-water listing and adds it to res (repairs appended); returns the
// repairs it added (none when nothing was pending). Rethrows the listing's error.
std::vector<pslg::Repair> finish_removed(Result& res);

// The polygons grown (d > 0) or shrunk (d < 0) by |d| (GEOS buffer, ring by ring).
Polygons offset_polygons(const Polygons& input, double d);

}  // namespace fdr::coast
