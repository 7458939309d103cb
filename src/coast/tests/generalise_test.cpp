// The coast generalisation as a whole (coast/generalise.hpp): synthetic channels of known widths are kept or
// closed and reported, connections between water bodies are kept down to --min-feature, small
// islands are removed, overlapping polygons are united.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <cstdlib>
#include <limits>
#include <set>
#include <string>

#include "base/error.hpp"
#include "base/tests/scoped_env.hpp"
#include "coast/generalise.hpp"

namespace fdr::coast {
namespace {

using fdr::ThreadsEnv;

Rings rect(double x0, double y0, double x1, double y1) { return {{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}}; }

double area(const Polygons& ps) {
  double a = 0;
  for (const auto& p : ps)
    for (std::size_t k = 0; k < p.size(); ++k) {
      double s = 0;
      const auto& r = p[k];
      for (std::size_t i = 0; i < r.size(); ++i) {
        const Point2 u = r[i], v = r[(i + 1) % r.size()];
        s += u.x * v.y - v.x * u.y;
      }
      a += (k == 0 ? 1 : -1) * std::fabs(0.5 * s);
    }
  return a;
}

std::size_t count(const Result& r, const std::string& kind) {
  std::size_t n = 0;
  for (const auto& x : r.repairs) n += x.kind == kind;
  return n;
}

// A 1000 x 1000 basin with a dead-end inlet of width w and length 500 on its east side.
Polygons basin_with_inlet(double w) {
  Rings r{{{0, 0}, {1000, 0}, {1000, 500 - w / 2}, {1500, 500 - w / 2}, {1500, 500 + w / 2}, {1000, 500 + w / 2}, {1000, 1000}, {0, 1000}}};
  return {r};
}

Options opts(double hmin) {
  Options o;
  o.close_width = 0.25 * hmin;
  o.min_feature = 0.1 * hmin;
  o.min_island_area = 0.1 * hmin * hmin;
  o.list_area = 0.1 * hmin * hmin;
  return o;
}

// Convex water corners are rounded with radius close_width / 2: r^2 (1 - pi/4) per right angle.
double corner_loss(const Options& o, int right_angles) {
  const double r = 0.5 * o.close_width;
  return right_angles * r * r * (1 - 3.14159265358979 / 4) * 1.2 + 1.0;
}

TEST(Generalise, NarrowDeadEndInletIsClosedAndListed) {
  const Result r = generalise(basin_with_inlet(10), opts(100));  // 10 m < 25 m
  EXPECT_EQ(r.output_pieces, 1u);
  EXPECT_NEAR(area(r.polygons), 1e6, 1e6 * 1e-3);  // the 5000 m^2 inlet is gone
  EXPECT_GE(r.closed_area, 4900.0);
  ASSERT_EQ(count(r, "narrow_water_closed"), 1u);
  for (const auto& x : r.repairs)
    if (x.kind == "narrow_water_closed") {
      EXPECT_GT(x.where.x, 1000.0);  // located in the inlet
      EXPECT_NEAR(x.size, 5000.0, 100.0);
    }
}

// The removed-water listing deferred to another thread (defer_removed, as the pipeline runs it)
// gives the same repairs, in the same order, and the same figures once finish_removed() took it;
// before that it is missing (so the test sees a listing that was really deferred).
TEST(Generalise, DeferredRemovedListingEqualsTheDirectOne) {
  Polygons in = basin_with_inlet(10);
  in.push_back(rect(2000, 0, 2300, 8));  // a water body nowhere min_feature wide
  in[0].push_back({{200, 200}, {200, 203}, {260, 203}, {260, 200}});  // a thin island (cut)
  for (const int threads : {1, 2}) {
    ThreadsEnv env(threads);
    Options o = opts(100);
    const Result direct = generalise(in, o);
    o.defer_removed = true;
    Result later = generalise(in, o);
    ASSERT_TRUE(later.removed_pending != nullptr);
    EXPECT_EQ(count(later, "narrow_water_closed"), 0u);
    const std::vector<pslg::Repair> added = finish_removed(later);
    EXPECT_EQ(later.removed_pending, nullptr);
    EXPECT_TRUE(finish_removed(later).empty());  // taken once
    ASSERT_EQ(count(direct, "narrow_water_closed"), 1u);
    EXPECT_EQ(added.size(), 1u);
    ASSERT_EQ(later.repairs.size(), direct.repairs.size());
    for (std::size_t i = 0; i < direct.repairs.size(); ++i) {
      EXPECT_EQ(later.repairs[i].kind, direct.repairs[i].kind);
      EXPECT_EQ(later.repairs[i].where, direct.repairs[i].where);
      EXPECT_EQ(later.repairs[i].size, direct.repairs[i].size);
      EXPECT_EQ(later.repairs[i].reason, direct.repairs[i].reason);
    }
    EXPECT_EQ(later.closed, direct.closed);
    EXPECT_EQ(later.closed_area, direct.closed_area);  // bit for bit: the same sums in the same order
    EXPECT_EQ(later.corner_pieces, direct.corner_pieces);
    EXPECT_EQ(later.polygons, direct.polygons);
  }
}

TEST(Generalise, InletWiderThanCloseWidthIsKeptAsDrawn) {
  const Polygons in = basin_with_inlet(40);  // 40 m > 25 m
  const Result r = generalise(in, opts(100));
  EXPECT_NEAR(area(r.polygons), area(in), corner_loss(opts(100), 6));
  EXPECT_EQ(count(r, "narrow_water_closed"), 0u);
  // Straight coast keeps the input's exact coordinates (the changes are applied to the input, not
  // re-drawn by the buffers): the inlet walls y = 480 and y = 520 are still there, exactly; only
  // corners are rounded, with radius close_width / 2, so every vertex stays that close.
  bool wall_lo = false, wall_hi = false;
  const auto& ring = r.polygons[0][0];
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Point2 a = ring[i], b = ring[(i + 1) % ring.size()];
    wall_lo |= a.y == 480 && b.y == 480 && std::min(a.x, b.x) < 1100 && std::max(a.x, b.x) > 1400;
    wall_hi |= a.y == 520 && b.y == 520 && std::min(a.x, b.x) < 1100 && std::max(a.x, b.x) > 1400;
    double d = 1e300;
    for (std::size_t k = 0; k < in[0][0].size(); ++k)
      d = std::min(d, dist_to_segment(a, in[0][0][k], in[0][0][(k + 1) % in[0][0].size()]));
    EXPECT_LE(d, 0.5 * opts(100).close_width) << a.x << "," << a.y;
  }
  EXPECT_TRUE(wall_lo);
  EXPECT_TRUE(wall_hi);
}

// Two basins joined by a channel of width w and length 400.
Polygons two_basins(double w) {
  Rings r{{{0, 0}, {1000, 0}, {1000, 500 - w / 2}, {1400, 500 - w / 2}, {1400, 0}, {2400, 0}, {2400, 1000}, {1400, 1000},
           {1400, 500 + w / 2}, {1000, 500 + w / 2}, {1000, 1000}, {0, 1000}}};
  return {r};
}

TEST(Generalise, ConnectionBetweenWaterBodiesIsKeptDownToMinFeature) {
  // 15 m: narrower than close_width (25 m), wider than min_feature (10 m): kept, one piece.
  const Result r = generalise(two_basins(15), opts(100));
  EXPECT_EQ(r.output_pieces, 1u);
  EXPECT_GE(r.channels_kept, 1u);
  EXPECT_NEAR(area(r.polygons), area(two_basins(15)), corner_loss(opts(100), 8));
}

TEST(Generalise, ConnectionNarrowerThanMinFeatureIsClosedAndTheCutOffBodyListed) {
  // 5 m < min_feature: closed; the smaller body is cut off and removed, listed with its area.
  Polygons in = two_basins(5);
  in[0][0][4].x = 1400;  // make the east basin smaller than the west one
  in[0][0][5] = {1900, 0};
  in[0][0][6] = {1900, 1000};
  const Result r = generalise(in, opts(100));
  EXPECT_EQ(r.output_pieces, 1u);
  EXPECT_EQ(r.input_pieces, 1u);
  ASSERT_EQ(count(r, "cut_off_water_removed"), 1u);
  for (const auto& x : r.repairs)
    if (x.kind == "cut_off_water_removed") {
      EXPECT_GT(x.where.x, 1400.0);
      EXPECT_NEAR(x.size, 5e5, 5e3);
    }
  EXPECT_NEAR(area(r.polygons), 1e6, 1e4);
}

TEST(Generalise, SmallIslandsRemovedLargeOnesKept) {
  const Rings sea = rect(0, 0, 2000, 2000);
  const Polygons in{{sea[0], {{100, 100}, {100, 120}, {120, 120}, {120, 100}},  // 400 m^2 < 1000 m^2
                     {{500, 500}, {500, 800}, {800, 800}, {800, 500}}}};       // 90000 m^2
  const Result r = generalise(in, opts(100));
  ASSERT_EQ(r.polygons.size(), 1u);
  EXPECT_EQ(r.polygons[0].size(), 2u);  // outer + the large island
  EXPECT_EQ(r.islands_removed, 1u);
  EXPECT_EQ(count(r, "island_removed"), 1u);
  EXPECT_NEAR(area(r.polygons), 4e6 - 9e4, corner_loss(opts(100), 4));
}

// A 600 m square island with a needle of land 20 m wide at its base (thinner than close_width
// everywhere) running 400 m east to a tip at (x1 + 400, yc).
Rings island_with_needle(double x0, double y0) {
  const double x1 = x0 + 600, yc = y0 + 300;
  // clockwise (a hole)
  return {{{x0, y0}, {x0, y0 + 600}, {x1, y0 + 600}, {x1, yc + 10}, {x1 + 400, yc}, {x1, yc - 10}, {x1, y0}}};
}

bool has_vertex(const Result& r, Point2 p) {
  for (const auto& poly : r.polygons)
    for (const auto& ring : poly)
      for (const Point2& q : ring)
        if (q == p) return true;
  return false;
}

TEST(Generalise, TipsOfLandStayUnlessOtherLandIsNearTheirEnd) {
  // hmin 100: close_width 25 m, tips kept unless other land is within 80 m of their end.
  const Rings sea = rect(0, 0, 4000, 4000);
  const Rings a = island_with_needle(1000, 1000);  // tip (2000, 1300): open water around it
  const Rings b = island_with_needle(1000, 2400);  // tip (2000, 2700): 40 m from island c
  const Rings c{{{2040, 2400}, {2040, 3000}, {2600, 3000}, {2600, 2400}}};
  const Polygons in{{sea[0], a[0], b[0], c[0]}};
  Options o = opts(100);
  o.tip_clearance = 80;
  const Result r = generalise(in, o);
  ASSERT_EQ(r.polygons.size(), 1u);
  EXPECT_EQ(r.polygons[0].size(), 4u);  // sea and three islands
  EXPECT_TRUE(has_vertex(r, {2000, 1300})) << "the needle in open water keeps its tip";
  EXPECT_FALSE(has_vertex(r, {2000, 2700})) << "the needle pointing 40 m from island c is cut";
  EXPECT_GE(r.tips_kept, 1u);
  EXPECT_GT(r.land_removed_area, 1000.0);  // the cut needle (about 4000 m^2)
  EXPECT_LT(r.land_removed_area, 4000.0 + 1000.0);
  // Deterministic, whatever the thread count (the rings are closed on several threads).
  for (int t : {1, 2, 3}) {
    ThreadsEnv env(t);
    const Result r2 = generalise(in, o);
    EXPECT_EQ(r2.polygons, r.polygons) << "FDR_THREADS=" << t;
  }
  // Without tip clearance every thin part is cut, as before.
  const Result r0 = generalise(in, opts(100));
  EXPECT_FALSE(has_vertex(r0, {2000, 1300}));
  EXPECT_FALSE(has_vertex(r0, {2000, 2700}));
  EXPECT_EQ(r0.tips_kept, 0u);
}

TEST(Generalise, ThinIslandKeptInOpenWaterRemovedNearLand) {
  // Islands 400 m long and 20 m wide (thinner than close_width everywhere): one in open water,
  // one 50 m from the coast.
  const Rings sea = rect(0, 0, 4000, 4000);
  const Rings open{{{1000, 2000}, {1000, 2020}, {1400, 2020}, {1400, 2000}}};
  const Rings near{{{1000, 50}, {1000, 70}, {1400, 70}, {1400, 50}}};
  Options o = opts(100);
  o.min_island_area = 1000;  // both (8000 m^2) are above it
  o.tip_clearance = 80;
  const Result r = generalise({{sea[0], open[0], near[0]}}, o);
  ASSERT_EQ(r.polygons.size(), 1u);
  EXPECT_EQ(r.polygons[0].size(), 2u);
  EXPECT_TRUE(has_vertex(r, {1400, 2020}));
  EXPECT_FALSE(has_vertex(r, {1400, 70}));
}

// Even-odd point-in-polygon over every ring (test helper; points well away from edges).
bool water_at(const Result& r, Point2 q) {
  bool in = false;
  for (const auto& poly : r.polygons)
    for (const auto& ring : poly)
      for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++)
        if ((ring[i].y > q.y) != (ring[j].y > q.y) &&
            q.x < ring[j].x + (q.y - ring[j].y) * (ring[i].x - ring[j].x) / (ring[i].y - ring[j].y))
          in = !in;
  return in;
}

Options widen_opts() {  // the CLI's defaults at hmin 100
  Options o = opts(100);
  o.close_width = 15;
  o.widen_width = 60;
  return o;
}

TEST(Generalise, NarrowInletIsWidenedToTheWidenWidthAndListed) {
  // A 30 m inlet (close_width 15 <= 30 < widen_width 60): its banks move by
  // widen_width / 2 - close_width = 15 m into the land, so it becomes 60 m wide.
  const Polygons in = basin_with_inlet(30);
  const Result r = generalise(in, widen_opts());
  EXPECT_EQ(r.output_pieces, 1u);
  EXPECT_GE(r.widened, 1u);
  EXPECT_GE(count(r, "water_widened"), 1u);
  for (double x : {1100.0, 1250.0, 1400.0}) {
    EXPECT_TRUE(water_at(r, {x, 500 + 27})) << x;  // was land
    EXPECT_TRUE(water_at(r, {x, 500 - 27})) << x;
    EXPECT_FALSE(water_at(r, {x, 500 + 34})) << x;  // stays land: the coast moved by about 15 m
    EXPECT_FALSE(water_at(r, {x, 500 - 34})) << x;
  }
  // About 2 x 15 m along the inlet's 500 m; the basin's corners and the inlet's end round a little.
  EXPECT_NEAR(r.widened_area, 15000.0, 2500.0);
  EXPECT_NEAR(area(r.polygons), area(in) + r.widened_area, corner_loss(widen_opts(), 8) + 2000.0);
  // An inlet at least widen_width wide keeps its banks; only its convex corners (right angles,
  // like sharper ones, would need narrow elements) are blunted by a few metres.
  const Polygons wide = basin_with_inlet(80);
  const Result r2 = generalise(wide, widen_opts());
  for (double x : {1100.0, 1250.0, 1400.0}) {
    EXPECT_TRUE(water_at(r2, {x, 500 + 38})) << x;
    EXPECT_FALSE(water_at(r2, {x, 500 + 42})) << x;
    EXPECT_FALSE(water_at(r2, {x, 500 - 42})) << x;
  }
  EXPECT_LT(r2.widened_area, 6 * 300.0);
  // Off: as before.
  Options off = widen_opts();
  off.widen_width = 0;
  EXPECT_EQ(generalise(in, off).widened, 0u);
  // Same polygons whatever the thread count.
  for (int t : {1, 2, 3}) {
    ThreadsEnv env(t);
    EXPECT_EQ(generalise(in, widen_opts()).polygons, r.polygons) << "FDR_THREADS=" << t;
  }
}

TEST(Generalise, WideningNeverJoinsTwoWaterBodies) {
  // The 30 m inlet runs 20 m below a second water body: widening it would leave 5 m of land
  // between them (less than close_width, which the closing removes), so it is not widened and
  // the two bodies stay apart.
  const Polygons in{basin_with_inlet(30)[0] /* inlet y 485..515 */, rect(1040, 535, 1500, 1000)};
  const Result r = generalise(in, widen_opts());
  EXPECT_EQ(r.input_pieces, 2u);
  EXPECT_EQ(r.output_pieces, 2u);
  EXPECT_FALSE(water_at(r, {1250, 525}));
  EXPECT_FALSE(water_at(r, {1250, 475 - 4}));  // the piece is judged whole: the south bank stays too
}

TEST(Generalise, NoTinyEdgesAtVerticesTheFilterMade) {
  // A needle cut near other land and an inlet widened: every edge with an endpoint that is not
  // an input vertex is at least close_width / 4 long.
  const Rings sea = rect(0, 0, 4000, 4000);
  const Rings b = island_with_needle(1000, 2400);  // its tip 40 m from island c: cut
  const Rings c{{{2040, 2400}, {2040, 3000}, {2600, 3000}, {2600, 2400}}};
  const Polygons in{{sea[0], b[0], c[0]}};
  Options o = widen_opts();
  o.tip_clearance = 50;
  const Result r = generalise(in, o);
  std::size_t checked = 0;
  std::set<std::pair<double, double>> input;
  for (const auto& ring : in[0])
    for (const Point2& q : ring) input.insert({q.x, q.y});
  for (const auto& poly : r.polygons)
    for (const auto& ring : poly)
      for (std::size_t i = 0; i < ring.size(); ++i) {
        const Point2 a = ring[i], q = ring[(i + 1) % ring.size()];
        if (input.count({a.x, a.y}) && input.count({q.x, q.y})) continue;
        // at a corner (a turn of more than 60 degrees at either end; arcs turn less)
        auto turn = [&](Point2 u, Point2 v, Point2 w) {
          const double cx = (v.x - u.x) * (w.y - v.y) - (v.y - u.y) * (w.x - v.x);
          const double dt = (v.x - u.x) * (w.x - v.x) + (v.y - u.y) * (w.y - v.y);
          return std::atan2(std::fabs(cx), dt);
        };
        const std::size_t n = ring.size();
        const bool corner = (!input.count({a.x, a.y}) && turn(ring[(i + n - 1) % n], a, q) > 1.05) ||
                            (!input.count({q.x, q.y}) && turn(a, q, ring[(i + 2) % n]) > 1.05);
        if (corner) { EXPECT_GE(std::hypot(a.x - q.x, a.y - q.y), o.close_width / 4) << a.x << " " << a.y; }
        ++checked;
      }
  EXPECT_GT(checked, 10u);
}

// hmin 100: --min-island 0.3 hmin^2 = 3000 m^2, triangles of side 70 m.
Options islet_opts() {
  Options o = widen_opts();
  o.min_island_area = 3000;
  o.islet_side = 70;
  return o;
}

// A sea with a large island and two islets of 400 m^2, one in open water, one 30 m from the island.
Polygons islets_and_big_island() {
  const Rings sea = rect(0, 0, 4000, 4000);
  const Rings open_islet{{{2000, 2000}, {2000, 2020}, {2020, 2020}, {2020, 2000}}};
  const Rings big{{{500, 500}, {500, 1500}, {1500, 1500}, {1500, 500}}};
  const Rings near_islet{{{1530, 1000}, {1530, 1020}, {1550, 1020}, {1550, 1000}}};
  return {{sea[0], open_islet[0], big[0], near_islet[0]}};
}

TEST(Generalise, IsletsInOpenWaterBecomeTrianglesNearLandTheyAreRemoved) {
  Options o = islet_opts();
  const Result r = generalise(islets_and_big_island(), o);
  ASSERT_EQ(r.polygons.size(), 1u);
  EXPECT_EQ(r.polygons[0].size(), 3u);  // sea, the big island, the open islet's triangle
  EXPECT_EQ(r.islets_replaced, 1u);
  EXPECT_EQ(count(r, "islet_simplified"), 1u);
  EXPECT_EQ(r.islands_removed, 1u);
  EXPECT_FALSE(water_at(r, {2010, 2010}));  // land: inside the triangle around (2010, 2010)
  EXPECT_TRUE(water_at(r, {1540, 1010}));   // the islet near the big island is water
  EXPECT_NEAR(area(r.polygons), 4000.0 * 4000 - 1e6 - std::sqrt(3.0) / 4 * 70 * 70, 300.0);
  // Without islet_side: both removed.
  o.islet_side = 0;
  const Result r0 = generalise(islets_and_big_island(), o);
  EXPECT_EQ(r0.polygons[0].size(), 2u);
  EXPECT_EQ(r0.islands_removed, 2u);
}

// The largest distance from a point of pts to the boundary of ring.
double farthest_from(const std::vector<Point2>& pts, const std::vector<Point2>& ring) {
  double worst = 0;
  for (const Point2& v : pts) {
    double d = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < ring.size(); ++k) d = std::min(d, dist_to_segment(v, ring[k], ring[(k + 1) % ring.size()]));
    worst = std::max(worst, d);
  }


  return worst;
}

// With join_islets (the CLI's default), the islet 30 m from the big island, with no room for its
// triangle, is joined to it: the convex hull of the islet and of the island's coast near it becomes
// land, so the islet's outer side stays coast; nothing is removed and no water is cut off.
TEST(Generalise, IsletNearLandWithoutRoomIsJoinedToIt) {
  Options o = islet_opts();
  o.join_islets = true;
  const Result r = generalise(islets_and_big_island(), o);
  ASSERT_EQ(r.polygons.size(), 1u);
  ASSERT_EQ(r.polygons[0].size(), 3u);  // sea, the big island with the islet joined, the open islet's triangle
  EXPECT_EQ(r.islets_replaced, 1u);
  EXPECT_EQ(r.islets_joined, 1u);
  EXPECT_EQ(count(r, "islet_joined"), 1u);
  EXPECT_EQ(r.islands_removed, 0u);
  EXPECT_EQ(r.output_pieces, 1u);
  EXPECT_FALSE(water_at(r, {1540, 1010}));  // the islet
  EXPECT_FALSE(water_at(r, {1515, 1010}));  // the gap between it and the island
  EXPECT_TRUE(water_at(r, {1560, 1010}));   // beyond it
  EXPECT_TRUE(water_at(r, {1520, 900}));    // the island's coast away from the islet is where it was
  // The islet's outer corners are on the new coast (within the buffers' rounding).
  const std::vector<Point2> outer{{1550, 1000}, {1550, 1020}};
  const auto& island = r.polygons[0][1].size() > 3 ? r.polygons[0][1] : r.polygons[0][2];
  EXPECT_LT(farthest_from(outer, island), 2.0);
  // The water taken: the islet, its gap (30 m x 20 m) and the hull's sides; listed with its area.
  EXPECT_GT(r.islets_joined_area, 600.0);
  EXPECT_LT(r.islets_joined_area, 3 * 70.0 * 70.0);
}

// An islet 30 m off the big island's east side, 10 m below its north-east corner: the coast near it
// runs round the corner, and the hull has an edge along the north side (it touches the coast at the
// corner between the run's ends). Joined all the same: refused, the islet was removed and the
// coast the model sees moved by its distance to the island.
TEST(Generalise, IsletBesideACornerIsJoinedRoundIt) {
  const Rings sea = rect(0, 0, 4000, 4000);
  const Rings big{{{500, 500}, {500, 1500}, {1500, 1500}, {1500, 500}}};
  const Rings islet{{{1530, 1470}, {1530, 1490}, {1550, 1490}, {1550, 1470}}};
  Options o = islet_opts();
  o.join_islets = true;
  const Result r = generalise({{sea[0], big[0], islet[0]}}, o);
  ASSERT_EQ(r.polygons.size(), 1u);
  ASSERT_EQ(r.polygons[0].size(), 2u);  // sea, the big island with the islet joined
  EXPECT_EQ(r.islets_joined, 1u);
  EXPECT_EQ(r.islands_removed, 0u);
  EXPECT_EQ(r.output_pieces, 1u);
  EXPECT_FALSE(water_at(r, {1540, 1480}));  // the islet
  EXPECT_FALSE(water_at(r, {1515, 1480}));  // the gap
  EXPECT_TRUE(water_at(r, {1560, 1480}));   // beyond it
  EXPECT_TRUE(water_at(r, {1480, 1510}));   // north of the island, near the corner: still water
  EXPECT_TRUE(water_at(r, {1520, 1300}));   // the east coast away from the islet
  const std::vector<Point2> outer{{1550, 1470}, {1550, 1490}};
  EXPECT_LT(farthest_from(outer, r.polygons[0][1]), 5.0);  // (the buffers round the corners)
}

// An islet in a channel 90 m wide, 35 m from either bank: joined to one bank where the hull keeps
// islet_side / 4 from the other, never across the channel (the water stays one piece).
TEST(Generalise, IsletInAChannelIsNeverJoinedAcrossIt) {
  // Two basins joined by a channel y in [1000, 1090], x in [1000, 2000].
  const Rings water{{{0, 0}, {1000, 0}, {1000, 1000}, {2000, 1000}, {2000, 0}, {3000, 0}, {3000, 2090}, {2000, 2090},
                     {2000, 1090}, {1000, 1090}, {1000, 2090}, {0, 2090}}};
  const Rings islet{{{1490, 1035}, {1490, 1055}, {1510, 1055}, {1510, 1035}}};
  Options o = islet_opts();
  o.join_islets = true;
  const Result r = generalise({{water[0], islet[0]}}, o);
  EXPECT_EQ(r.output_pieces, 1u);
  ASSERT_EQ(r.polygons.size(), 1u);
  EXPECT_TRUE(water_at(r, {500, 1000}));
  EXPECT_TRUE(water_at(r, {2500, 1000}));
  // A way through the channel: at x = 1500 some water between the banks.
  bool through = false;
  for (double y = 1001; y < 1090; y += 1) through = through || water_at(r, {1500, y});
  EXPECT_TRUE(through);
  EXPECT_EQ(r.islets_joined + r.islands_removed, 1u);
}

// Three islets 30 m apart in open water: judged one by one with the others as land, none had room;
// judged again with the others left out, the first gets its triangle and the other two are joined
// to it (the convex hull of triangle and islet): one island, nothing removed.
TEST(Generalise, RowOfIsletsBecomesOneIsland) {
  const Rings sea = rect(0, 0, 4000, 4000);
  Options o = islet_opts();
  o.join_islets = true;
  Polygons in{{sea[0]}};
  std::vector<Point2> verts;
  for (int k = 0; k < 3; ++k) {
    const double x = 2000 + 50 * k;
    const std::vector<Point2> h{{x, 2000}, {x, 2020}, {x + 20, 2020}, {x + 20, 2000}};
    in[0].push_back(h);
    verts.insert(verts.end(), h.begin(), h.end());
  }
  const Result r = generalise(in, o);
  ASSERT_EQ(r.polygons.size(), 1u);
  ASSERT_EQ(r.polygons[0].size(), 2u);
  EXPECT_EQ(r.islands_removed, 0u);
  EXPECT_EQ(r.islets_replaced, 1u);
  EXPECT_EQ(r.islets_joined, 2u);
  for (const double x : {2010.0, 2035.0, 2060.0, 2085.0, 2110.0}) EXPECT_FALSE(water_at(r, {x, 2010})) << x;
  // Every islet vertex within islet_side / 2 of the island's coast (hmin 100: within hmin/2).
  EXPECT_LT(farthest_from(verts, r.polygons[0][1]), 35.0);
  // Without joining, the pass with the others left out still places one triangle.
  o.join_islets = false;
  const Result r0 = generalise(in, o);
  EXPECT_EQ(r0.islets_replaced, 1u);
}

// A long islet's triangle is turned to fit it: with the apex always up, the ends of an islet
// 100 m long lying at 30 degrees stuck out 29.8 m from its triangle of side 70 (corners rounded
// by the closing); turned, 22.8 m.
TEST(Generalise, IsletTriangleIsTurnedToFitTheIslet) {
  const Rings sea = rect(0, 0, 4000, 4000);
  const std::vector<Point2> islet{{1956.699, 1975.0}, {1998.0, 2003.464}, {2043.301, 2025.0}};  // clockwise
  Options o = widen_opts();
  o.min_island_area = 3000;
  o.islet_side = 70;
  const Result r = generalise({{sea[0], islet}}, o);
  ASSERT_EQ(r.islets_replaced, 1u);
  ASSERT_EQ(r.polygons.size(), 1u);
  ASSERT_EQ(r.polygons[0].size(), 2u);
  const double worst = farthest_from(islet, r.polygons[0][1]);  // the triangle, corners rounded by the closing
  EXPECT_LT(worst, 23.0);
}

// A long islet in open water gets a larger triangle (side 90 m for 150 m, up to 1.6 x 70), which
// keeps its ends within 40 m; the side is in the repair.
TEST(Generalise, LongIsletGetsALargerTriangle) {
  const Rings sea = rect(0, 0, 4000, 4000);
  const std::vector<Point2> islet{{1925.0, 2000.0}, {2000.0, 2006.0}, {2075.0, 2000.0}};  // 450 m^2
  Options o = widen_opts();
  o.min_island_area = 3000;
  o.islet_side = 70;
  const Result r = generalise({{sea[0], islet}}, o);
  ASSERT_EQ(r.islets_replaced, 1u);
  ASSERT_EQ(r.polygons[0].size(), 2u);
  const double worst = farthest_from(islet, r.polygons[0][1]);
  EXPECT_LT(worst, 41.0);
  bool said = false;
  for (const auto& x : r.repairs)
    if (x.kind == "islet_simplified") said = x.reason.find("triangle of side 90") != std::string::npos;
  EXPECT_TRUE(said);
  // With a large island 78 m from its centroid there is room for the usual triangle only: side 70.
  const Rings big{{{1500, 2080}, {1500, 3000}, {2500, 3000}, {2500, 2080}}};
  const Result r2 = generalise({{sea[0], islet, big[0]}}, o);
  EXPECT_EQ(r2.islets_replaced, 1u);
  for (const auto& x : r2.repairs)
    if (x.kind == "islet_simplified") { EXPECT_NE(x.reason.find("triangle of side 70 m"), std::string::npos) << x.reason; }
}

// An island above --min-island (4000 m^2 > 3000) but thinner than --close-width (10 m < 15)
// everywhere: the closing would leave nothing of it, so it is an islet and becomes a triangle.
TEST(Generalise, ThinIslandAboveMinIslandBecomesATriangle) {
  const Rings sea = rect(0, 0, 4000, 4000);
  const Rings thin = rect(2000, 2000, 2400, 2010);
  Options o = widen_opts();
  o.min_island_area = 3000;
  o.islet_side = 70;
  const Result r = generalise({{sea[0], thin[0]}}, o);
  ASSERT_EQ(r.polygons.size(), 1u);
  EXPECT_EQ(r.polygons[0].size(), 2u);  // sea and the triangle
  EXPECT_EQ(r.islets_replaced, 1u);
  EXPECT_EQ(r.islands_removed, 0u);
  EXPECT_FALSE(water_at(r, {2200, 2005}));  // the triangle around the centroid
  bool said = false;
  for (const auto& x : r.repairs)
    if (x.kind == "islet_simplified") said = x.reason.find("0 m^2 of it wider than 15 m") != std::string::npos;
  EXPECT_TRUE(said);
  // 400 m long: the larger triangle of a long islet, at its largest side (1.6 x 70 m).
  EXPECT_NEAR(area(r.polygons), 4000.0 * 4000 - std::sqrt(3.0) / 4 * 112 * 112, 300.0);
}

// An island of 12500 m^2 (a 50 m square with a 10 m wide tail 1 km long) is judged after the
// closing: the tail goes, the square's 2500 m^2 remnant is below --min-island (3000) and becomes
// a triangle where it was instead of water.
TEST(Generalise, RemnantBelowMinIslandAfterTheClosingBecomesATriangle) {
  const Rings sea = rect(0, 0, 4000, 4000);
  const Rings isl{{{2000, 2000}, {2050, 2000}, {2050, 2020}, {3050, 2020}, {3050, 2030}, {2050, 2030}, {2050, 2050}, {2000, 2050}}};
  Options o = widen_opts();
  o.min_island_area = 3000;
  o.islet_side = 70;
  const Result r = generalise({{sea[0], isl[0]}}, o);
  ASSERT_EQ(r.polygons.size(), 1u);
  EXPECT_EQ(r.polygons[0].size(), 2u);
  EXPECT_EQ(r.islets_replaced, 1u);
  EXPECT_EQ(r.islands_removed, 0u);
  EXPECT_FALSE(water_at(r, {2025, 2025}));
  EXPECT_TRUE(water_at(r, {2800, 2025}));  // the tail became water
  bool said = false;
  for (const auto& x : r.repairs)
    if (x.kind == "islet_simplified") said = x.reason.find("island remnant of") != std::string::npos;
  EXPECT_TRUE(said);
  // Without islet_side the remnant is removed, as before.
  o.islet_side = 0;
  const Result r0 = generalise({{sea[0], isl[0]}}, o);
  EXPECT_EQ(r0.polygons[0].size(), 1u);
  EXPECT_EQ(r0.islands_removed, 1u);
}

// The same islet 30 m from the big island (its centroid 40 m away, 75 m needed) with
// islet_shift 40: its triangle moves 40 m east, away from the island, instead of being removed.
TEST(Generalise, IsletNearLandMovesItsTriangleAwayFromIt) {
  const Rings sea = rect(0, 0, 4000, 4000);
  const Rings big{{{500, 500}, {500, 1500}, {1500, 1500}, {1500, 500}}};
  const Rings near_islet{{{1530, 1000}, {1530, 1020}, {1550, 1020}, {1550, 1000}}};
  Options o = widen_opts();
  o.min_island_area = 3000;
  o.islet_side = 70;
  o.islet_shift = 40;
  const Result r = generalise({{sea[0], big[0], near_islet[0]}}, o);
  ASSERT_EQ(r.polygons.size(), 1u);
  EXPECT_EQ(r.islets_replaced, 1u);
  EXPECT_EQ(r.islands_removed, 0u);
  EXPECT_FALSE(water_at(r, {1580, 1010}));  // the triangle's centre
  EXPECT_TRUE(water_at(r, {1540, 1010}));   // where the islet was
  bool said = false;
  for (const auto& x : r.repairs)
    if (x.kind == "islet_simplified") {
      EXPECT_NEAR(x.where.x, 1580, 1e-9);
      EXPECT_NEAR(x.where.y, 1010, 1e-9);
      said = x.reason.find("40 m from its centroid") != std::string::npos;
    }
  EXPECT_TRUE(said);
  // Shifts too small for the room it needs: removed, as without islet_shift.
  o.islet_shift = 20;
  const Result r2 = generalise({{sea[0], big[0], near_islet[0]}}, o);
  EXPECT_EQ(r2.islets_replaced, 0u);
  EXPECT_EQ(r2.islands_removed, 1u);
}

// An islet whose triangle (side 70 m, hmin 100) leaves 45 m of water to the next land: room
// enough to place it (35 m beyond its corners), but narrower than --widen-width (60 m). The
// triangle goes in after the widening, so the widening does not eat into it: it keeps its side.
TEST(Generalise, IsletTriangleNextToNarrowWaterKeepsItsSide) {
  const Rings sea = rect(0, 0, 4000, 4000);
  const Rings islet{{{2000, 2000}, {2000, 2020}, {2020, 2020}, {2020, 2000}}};
  const Rings land = rect(2090, 1500, 3000, 2500);
  Options o = widen_opts();
  o.min_island_area = 3000;
  o.islet_side = 70;
  const Result r = generalise({{sea[0], islet[0], land[0]}}, o);
  ASSERT_EQ(r.polygons.size(), 1u);
  ASSERT_EQ(r.islets_replaced, 1u);
  double tri = -1;
  for (std::size_t k = 1; k < r.polygons[0].size(); ++k) {
    const Polygons one{{r.polygons[0][k]}};
    const double a = area(one);
    if (a < 1e4) tri = a;
  }
  EXPECT_NEAR(tri, std::sqrt(3.0) / 4 * 70 * 70, 0.08 * std::sqrt(3.0) / 4 * 70 * 70);  // the closing rounds its corners (-6 %)
  EXPECT_FALSE(water_at(r, {2010, 2010}));
  EXPECT_GE(r.widened, 1u);  // the water beside it was narrow all the same
}

TEST(Generalise, OverlappingPolygonsAreUnited) {
  // Two overlapping squares: one domain (not the symmetric difference), reported.
  const Polygons in{rect(0, 0, 1000, 1000), rect(500, 500, 1500, 1500)};
  const Result r = generalise(in, opts(100));
  EXPECT_EQ(r.output_pieces, 1u);
  EXPECT_EQ(r.united, 1u);
  EXPECT_EQ(count(r, "polygons_united"), 1u);
  EXPECT_NEAR(area(r.polygons), 2e6 - 2.5e5, corner_loss(opts(100), 6));
}

TEST(Generalise, IdenticalPolygonsAreUnited) {
  const Polygons in{rect(0, 0, 1000, 1000), rect(0, 0, 1000, 1000)};
  const Result r = generalise(in, opts(100));
  EXPECT_EQ(r.output_pieces, 1u);
  EXPECT_NEAR(area(r.polygons), 1e6, corner_loss(opts(100), 4));
}

TEST(Generalise, NothingLeftIsAnError) {
  try {
    generalise({rect(0, 0, 1000, 5)}, opts(100));  // 5 m wide everywhere, min_feature 10 m
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidGeometry);
    EXPECT_NE(std::string(e.what()).find("--close-width"), std::string::npos) << e.what();
  }
}

TEST(Generalise, OffKeepsEverything) {
  const Polygons in = basin_with_inlet(10);
  const Result r = generalise(in, Options{});
  EXPECT_NEAR(area(r.polygons), area(in), 1e-6);
  EXPECT_TRUE(r.repairs.empty());
}

// Validity: a valid polygon with many islands is taken as it is (the fast exact test), invalid
// ones (an island inside an island, a self-crossing bow tie) are repaired by GEOS as before.
TEST(Generalise, ValidAndInvalidInputsWithoutFilter) {
  Rings many = rect(0, 0, 1000, 1000);
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j) {
      const double x = 50 + 115 * i, y = 50 + 115 * j;
      many.push_back({{x, y}, {x, y + 40}, {x + 40, y + 40}, {x + 40, y}});
    }
  const Result a = generalise({many}, Options{});
  EXPECT_EQ(a.output_pieces, 1u);
  EXPECT_NEAR(area(a.polygons), 1e6 - 64 * 1600, 1e-6);
  // An island drawn inside another island: GEOS makes the inner ring a separate water body.
  Rings nested = rect(0, 0, 1000, 1000);
  nested.push_back({{100, 100}, {100, 900}, {900, 900}, {900, 100}});
  nested.push_back({{300, 300}, {300, 700}, {700, 700}, {700, 300}});
  const Result b = generalise({nested}, Options{});
  EXPECT_EQ(b.output_pieces, 2u);
  EXPECT_NEAR(area(b.polygons), 1e6 - 640000 + 160000, 1e-6);
  // A bow tie (the outer ring crosses itself) becomes two triangles.
  const Rings bow{{{0, 0}, {1000, 1000}, {1000, 0}, {0, 1000}}};
  const Result c = generalise({bow}, Options{});
  EXPECT_EQ(c.output_pieces, 2u);
  EXPECT_NEAR(area(c.polygons), 5e5, 1e-6);
}

}  // namespace
}  // namespace fdr::coast

namespace fdr::coast {
namespace {

// A 10 km basin whose south coast is a zigzag of 400 vertices 25 m apart turning by 25 degrees
// (the buffers' arcs there start 2.8 m from each vertex, farther than the 1.25 m vertex snap,
// but stay within 0.3 m of the coast), with a 5 m wide dead-end inlet in its north side.
Polygons wavy_basin_with_inlet() {
  Rings r(1);
  for (int i = 0; i <= 400; ++i) r[0].push_back({25.0 * i, (i % 2) * 5.5});
  r[0].push_back({10000, 10000});
  r[0].push_back({5002.5, 10000});
  r[0].push_back({5002.5, 11000});
  r[0].push_back({4997.5, 11000});
  r[0].push_back({4997.5, 10000});
  r[0].push_back({0, 10000});
  return {r};
}

TEST(Generalise, UnchangedCoastComesBackAsTheInputsVertices) {
  // The buffers return an unchanged coast as arc points around every input vertex; the filter
  // gives the input's own vertices back there (CoastRestorer), so only the closed inlet and the
  // rounded corners carry new vertices.
  const Polygons in = wavy_basin_with_inlet();
  const Result r = generalise(in, opts(100));  // close_width 25 m
  ASSERT_EQ(r.polygons.size(), 1u);
  EXPECT_GE(count(r, "narrow_water_closed"), 1u);
  std::set<std::pair<double, double>> input;
  for (const Point2 p : in[0][0]) input.insert({p.x, p.y});
  auto near_change = [](Point2 p) {  // the inlet and the four corners (rounded by the opening)
    const double d = 2 * 25.0;
    if (p.x > 4997.5 - d && p.x < 5002.5 + d && p.y > 10000 - d) return true;
    for (const Point2 c : {Point2{0, 0}, Point2{10000, 0}, Point2{10000, 10000},
                           Point2{0, 10000}})
      if (std::hypot(p.x - c.x, p.y - c.y) < d) return true;
    return false;
  };
  std::size_t kept_input = 0, input_away = 0, new_away = 0;
  std::set<std::pair<double, double>> out;
  for (const Point2 p : r.polygons[0][0]) {
    out.insert({p.x, p.y});
    if (!near_change(p) && !input.count({p.x, p.y})) ++new_away;
  }
  for (const Point2 p : in[0][0]) {
    if (near_change(p)) continue;
    ++input_away;
    kept_input += out.count({p.x, p.y});
  }
  EXPECT_EQ(new_away, 0u);               // no vertex of the buffers' own along unchanged coast
  EXPECT_EQ(kept_input, input_away);     // and every input vertex there, bitwise
  EXPECT_LT(r.polygons[0][0].size(), in[0][0].size() + 40);  // a few arcs at the corners only
}

TEST(Generalise, CoastRestoreIsDeterministic) {
  const Result a = generalise(wavy_basin_with_inlet(), opts(100));
  const Result b = generalise(wavy_basin_with_inlet(), opts(100));
  ASSERT_EQ(a.polygons.size(), b.polygons.size());
  for (std::size_t i = 0; i < a.polygons.size(); ++i) EXPECT_EQ(a.polygons[i], b.polygons[i]);
}

}  // namespace
}  // namespace fdr::coast

namespace fdr::coast {
namespace {

// A coast with everything the openings' difference sees: inlets from 4 to 70 m wide, channels
// between two basins, islands in channels and next to inlets, an island inside a closed inlet.
Polygons messy_coast() {
  Rings outer;
  double x = 0;
  std::uint32_t s = 12345;
  auto rnd = [&s] { s = s * 1664525u + 1013904223u; return (s >> 8) / 16777216.0; };
  outer.emplace_back();
  auto& o = outer[0];
  o.push_back({0, 0});
  while (x < 9000) {  // the south coast: inlets going south
    const double w = 4 + 66 * rnd(), len = 40 + 300 * rnd();
    o.push_back({x + 100, 0});
    o.push_back({x + 100, -len});
    o.push_back({x + 100 + w, -len});
    o.push_back({x + 100 + w, 0});
    x += 100 + w + 80 * rnd();
  }
  o.push_back({10000, 0});
  o.push_back({10000, 4000});
  o.push_back({0, 4000});
  Polygons in{{o}};
  for (int i = 0; i < 40; ++i) {  // islands: squares 10-60 m, some within a few metres of the coast
    const double cx = 150 + 9500 * rnd(), cy = (i % 3 == 0 ? 8 + 30 * rnd() : 50 + 3800 * rnd()), h = 5 + 25 * rnd();
    in[0].push_back({{cx - h, cy - h}, {cx - h, cy + h}, {cx + h, cy + h}, {cx + h, cy - h}});
  }
  return in;
}

TEST(Generalise, DifferenceOfOpeningsByFacesEqualsTheOverlay) {
  // The pieces between the two openings come from the faces of their non-shared segments
  // (difference_by_faces); Options::diff_overlay computes them with GEOS's overlay of the whole.
  for (const Polygons& in : {messy_coast(), wavy_basin_with_inlet(), two_basins(15), two_basins(5)}) {
    const Result a = generalise(in, opts(100));
    Options ob = opts(100);
    ob.diff_overlay = true;
    const Result b = generalise(in, ob);
    EXPECT_EQ(a.polygons, b.polygons);
    // The removed pieces are the same; their order and the last bits of their areas (summed
    // from another first vertex) may differ.
    ASSERT_EQ(a.repairs.size(), b.repairs.size());
    auto sorted = [](std::vector<pslg::Repair> r) {
      std::sort(r.begin(), r.end(), [](const pslg::Repair& x, const pslg::Repair& y) {
        return std::tie(x.kind, x.where.x, x.where.y) < std::tie(y.kind, y.where.x, y.where.y);
      });
      return r;
    };
    const auto ra = sorted(a.repairs), rb = sorted(b.repairs);
    for (std::size_t i = 0; i < ra.size(); ++i) {
      EXPECT_EQ(ra[i].kind, rb[i].kind);
      EXPECT_EQ(ra[i].where, rb[i].where);
      EXPECT_NEAR(ra[i].size, rb[i].size, 1e-9 * ra[i].size);
    }
    EXPECT_EQ(a.channels_kept, b.channels_kept);
  }
}

}  // namespace
}  // namespace fdr::coast
