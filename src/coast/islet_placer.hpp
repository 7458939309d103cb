// Islets: the placement of the triangles that replace islands below the resolution, and the
// joins of islets to nearby land, shared by the islet step and the remnant step (islets.hpp).
//
// An island below --min-island with no other land near becomes an equilateral triangle of side
// islet_side (larger for a long islet, up to 1.6 islet_side) around its centroid, turned to fit
// the islet, instead of water. Why: a dropped islet moves the coast the model sees by its
// distance to the next coast (its vertices are input coast too), a kept one forces elements as
// small as itself; the triangle keeps it within about islet_side / 2 with elements near hmin.
// Other land (every ring but its own, the triangles placed and the hulls joined before it) must
// be farther than Options::islet_clearance from the triangle, so that the water between them
// holds elements of that size. The islet step judges room on the land after the union (later
// steps only take land away, so room there is room later too); the remnant step on the land as
// it is then.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "coast/convex.hpp"
#include "coast/generalise.hpp"
#include "coast/geometry_ops.hpp"
#include "pslg/segment_grid.hpp"

namespace fdr::coast {

// Land as segments of the water's rings (every ring but the islet's own counts as other land).
struct LandIndex {
  std::unique_ptr<pslg::SegmentGrid> grid;
  std::vector<std::pair<Point2, Point2>> seg;
  std::vector<int> ring;                                // ring id of each segment
  int rings = 0;
  std::unordered_map<const OGRLinearRing*, int> id_of;  // valid while the rings are
  std::vector<char> gone;                               // per ring: removed, not land (empty: none)
  std::vector<std::size_t> first;                       // per ring: its first segment (and one past the last)
};

// The triangles placed and hulls joined so far, and the tests and placements that read them.
struct IsletPlacer {
  IsletPlacer(const Options& options, Result& report);

  // L: the segments of the rings of ps.
  void build_land(const std::vector<std::unique_ptr<OGRPolygon>>& ps, LandIndex& L) const;
  // Room for every turn of a triangle of circumradius r (0: islet_side's) around c: other land,
  // the placed triangles and the joined hulls farther than cl beyond its circumcircle.
  bool has_room(const LandIndex& L, int own, Point2 c, double cl, double r = 0);
  // The convex polygon poly keeps cl from every ring of L that is land (not gone, not `own`), the
  // placed triangles and the joined hulls.
  bool land_clear(const LandIndex& L, int own, const std::vector<Point2>& poly, double cl);
  // The islet of ring `own` (area a) as a triangle around cen or, with no room there, around the
  // first of 24 points near it (8 directions at a third, two thirds and all of islet_shift) that
  // has room; added to `into` and reported (islet_simplified). At each point the triangle takes
  // the turn that fits the islet best among those that keep their clearance from all other land
  // (tri_cl, shift_cl; without islet_clearance, only where its circumcircle keeps it). Why the
  // shifts and turns: most islets that were dropped lie within hmin of other land, and the coast
  // the model saw moved by that distance; a triangle's corners reach twice as far from its centre
  // as its sides, so a turned one fits where its circumcircle does not. False: no room.
  bool place(const LandIndex& L, int own, const OGRLinearRing& shape, Point2 cen, double a, const std::string& what,
             OGRMultiPolygon* into);
  // The convex polygon h keeps cl from the input's box, the placed triangles and the joined
  // hulls and, with `rings`, from every ring of L that is land (not gone).
  bool hull_clear(const LandIndex& L, const std::vector<Point2>& h, const Box2& inbox, double cl, bool rings);
  // An islet with no room for its triangle, joined to the nearest other land when that is
  // nearer than islet_side: the convex hull of the islet and of that land's coast within
  // rho = len / 2 + d + 0.1 islet_side of the nearest point (len: the islet's length, d: the gap)
  // becomes land. Why: dropped, the islet moves the coast the model sees by its distance to the
  // next coast; joined, its outer side stays coast and the gap, narrower than an element, is no
  // longer water. The hull must meet the land's ring along that one run of coast only (so no
  // water is cut off: the land grows by a convex piece whose intersection with it is connected;
  // it may touch the run between its ends, round a convex corner), keep join_cl from every
  // other ring, placed triangle and earlier join, stay inside the input's box (open boundaries do
  // not move) and hold at most 3 islet_side^2. With islet_clearance, the ring's own coast beyond
  // the run keeps join_cl from the hull too, except near the run's ends, where it must leave the
  // hull at 60 degrees or more; where it does not, runs of 2 rho and 3 rho are tried (the corner
  // of water between the islet and the coast turning back becomes land). Returns the hull
  // (empty: not joined), the water it takes (*taken) and the gap (*gap).
  std::vector<Point2> join(const LandIndex& L, int own, const OGRLinearRing& shape, const Box2& inbox, double* taken,
                           double* gap);
  // join's hull for the run of ring L.ring[kb]'s coast within arc length rho of pb (on segment
  // kb, the nearest point to the islet isl), with the tests join describes; empty: none.
  std::vector<Point2> join_along(const LandIndex& L, int own, const std::vector<Point2>& isl, Index kb, Point2 pb,
                                 double rho, const Box2& inbox, double* taken);
  // A convex polygon (a triangle, a hull of islets) kept as land; placed_ring: the ring it
  // replaces (-1: several).
  std::size_t add_placed(std::vector<Point2> poly, int ring);
  // A hull joined to land.
  void add_joined(std::vector<Point2> hull);

  const Options& o;
  Result& res;
  const double tri_r;  // circumradius of a triangle of side islet_side
  // The room each placement keeps from all other land: islet_clearance, or without it (tests of
  // the older rules) islet_side / 2 around a triangle, a little more around a moved one, and
  // islet_side / 4 around a join.
  const double tri_cl, shift_cl, join_cl;
  std::vector<Point2> placed;    // centres of the islets kept as triangles (the remnant step keeps them)
  std::vector<double> placed_r;  // their circumradii
  std::vector<int> placed_ring;  // the ring each replaces (-1: several)
  std::vector<std::vector<Point2>> placed_poly;  // their corners (empty: left out of the tests)
  DiskGrid placed_grid;
  std::vector<std::vector<Point2>> joined;  // the islets' hulls joined to land
  std::vector<Box2> joined_box;             // their boxes
  DiskGrid joined_grid;                     // ... by the cells of a grid
  std::unique_ptr<OGRMultiPolygon> tris;  // the islet step's triangles (added after the widening)
  std::vector<std::uint32_t> cand;  // scratch: placed triangles near a place
  std::vector<Index> near;          // scratch: land segments near a place
};

}  // namespace fdr::coast
