// Islets in clusters and beside other land (islet_clusters.hpp, islet_placer.hpp, islets.hpp) on
// small synthetic shapes at hmin 1 km: clusters become one island, one triangle or one join, and
// nothing a step places or joins comes nearer than hmin/2 to other land.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "coast/convex.hpp"
#include "coast/generalise.hpp"
#include "coast/geometry_ops.hpp"
#include "coast/islet_clusters.hpp"
#include "coast/islets.hpp"
#include "coast/narrow_gaps.hpp"

namespace fdr::coast {
namespace {

std::vector<Point2> square(double x, double y, double side) {  // counter-clockwise, lower left corner at x, y
  return {{x, y}, {x + side, y}, {x + side, y + side}, {x, y + side}};
}
std::vector<Point2> box(double x0, double y0, double x1, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}
std::vector<Point2> reversed(std::vector<Point2> r) {  // a hole: clockwise
  std::reverse(r.begin(), r.end());
  return r;
}

// The CLI's defaults at hmin 1 km.
Options defaults() { return resolution_options(1000); }

// A sea 20 km square with the given islands.
Polygons sea_with(const std::vector<std::vector<Point2>>& islands) {
  Rings r{box(0, 0, 20000, 20000)};
  for (const auto& i : islands) r.push_back(reversed(i));
  return {r};
}

std::size_t count(const Result& r, const std::string& kind) {
  std::size_t n = 0;
  for (const auto& x : r.repairs) n += x.kind == kind;
  return n;
}

std::size_t holes(const Result& r) {
  std::size_t n = 0;
  for (const auto& p : r.polygons) n += p.size() - 1;
  return n;
}

// Nearest distance between two rings of the result that are not the same ring.
double nearest_other_land(const Result& r) {
  std::vector<std::vector<Point2>> rings;
  for (const auto& p : r.polygons)
    for (const auto& ring : p) rings.push_back(ring);
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < rings.size(); ++i)
    for (std::size_t j = i + 1; j < rings.size(); ++j) d = std::min(d, ring_gap(rings[i], rings[j]));
  return d;
}

TEST(CoastIsletClusters, SingleLinkGroupsInInputOrder) {
  // Five islets 30 m apart in a row, one far away between them in the input's order, and a
  // pair 600 m apart (no cluster at a gap of 500 m).
  std::vector<std::vector<Point2>> rings;
  for (int k = 0; k < 5; ++k) {
    rings.push_back(square(1000 + 90 * k, 1000, 60));
    if (k == 2) rings.push_back(square(8000, 8000, 60));
  }
  rings.push_back(square(5000, 5000, 60));
  rings.push_back(square(5660, 5000, 60));
  const auto g = islet_clusters(rings, 500);
  ASSERT_EQ(g.size(), 4u);
  EXPECT_EQ(g[0], (std::vector<std::size_t>{0, 1, 2, 4, 5}));
  EXPECT_EQ(g[1], (std::vector<std::size_t>{3}));
  EXPECT_EQ(g[2], (std::vector<std::size_t>{6}));
  EXPECT_EQ(g[3], (std::vector<std::size_t>{7}));
  // A gap of 29 m splits the row into single islets.
  EXPECT_EQ(islet_clusters(rings, 29).size(), rings.size());
}

TEST(CoastIsletClusters, RingGapAndConvexGap) {
  EXPECT_NEAR(ring_gap(square(0, 0, 10), square(13, 4, 10)), 3, 1e-12);
  EXPECT_EQ(ring_gap(square(0, 0, 10), square(5, 5, 10)), 0);
  EXPECT_NEAR(convex_gap(square(0, 0, 10), square(10, 14, 10)), 4, 1e-12);
  EXPECT_EQ(convex_gap(square(0, 0, 10), square(2, 2, 3)), 0) << "one inside the other";
}

TEST(CoastIsletClusters, FiveIsletsThirtyMetresApartBecomeOneTriangle) {
  std::vector<std::vector<Point2>> islets;
  for (int k = 0; k < 5; ++k) islets.push_back(square(9000 + 90 * k, 10000, 60));
  const Result r = generalise(sea_with(islets), defaults());
  EXPECT_EQ(r.islets_replaced, 1u) << "one triangle for the cluster";
  EXPECT_EQ(count(r, "islet_simplified"), 1u);
  EXPECT_EQ(count(r, "island_removed"), 0u);
  EXPECT_EQ(r.islands_removed, 0u);
  EXPECT_EQ(holes(r), 1u);
  EXPECT_EQ(r.narrow_gaps, 0u);
}

TEST(CoastIsletClusters, LargeClusterIsKeptAsItsHull) {
  // Two rows of five islets 250 m square, 100 m apart: each below --min-island, their hull
  // (1.45 km x 0.6 km) above it.
  std::vector<std::vector<Point2>> islets;
  for (int k = 0; k < 5; ++k)
    for (int row = 0; row < 2; ++row) islets.push_back(square(9000 + 350 * k, 10000 + 350 * row, 250));
  const Result r = generalise(sea_with(islets), defaults());
  EXPECT_EQ(r.islets_joined, 1u);
  EXPECT_EQ(count(r, "islet_joined"), 1u);
  EXPECT_EQ(r.islets_replaced, 0u);
  EXPECT_EQ(r.islands_removed, 0u);
  ASSERT_EQ(holes(r), 1u);
  // The cluster's convex hull (the later steps round its corners a little).
  EXPECT_NEAR(std::fabs(signed_area(r.polygons[0][1])), 1600.0 * 600.0, 0.05 * 1600.0 * 600.0);
  EXPECT_EQ(r.narrow_gaps, 0u);
}

TEST(CoastIsletClusters, ChainOfCaysBecomesOneTriangleAlongIt) {
  // Six cays 80 m x 40 m, 200 m apart along a line 1.48 km long.
  std::vector<std::vector<Point2>> cays;
  for (int k = 0; k < 6; ++k) cays.push_back(box(9000 + 280 * k, 10000, 9080 + 280 * k, 10040));
  const Result r = generalise(sea_with(cays), defaults());
  EXPECT_EQ(r.islets_replaced, 1u);
  EXPECT_EQ(r.islands_removed, 0u);
  ASSERT_EQ(holes(r), 1u);
  // The triangle, larger than islet_side for a long cluster, lies along the chain.
  const Box2 b = box_of(r.polygons[0][1]);
  EXPECT_GT(b.width(), b.height());
  EXPECT_GT(b.width(), 800);
  EXPECT_EQ(r.narrow_gaps, 0u);
}

TEST(CoastIsletClusters, IsletFiftyMetresOffATipIsJoinedToIt) {
  // A cape 2 km wide narrowing to a tip at (10000, 8000), and an islet 50 m north of its tip.
  Rings sea{{{0, 0}, {9000, 0}, {9000, 6000}, {10000, 8000}, {11000, 6000}, {11000, 0}, {20000, 0}, {20000, 20000},
             {0, 20000}}};
  sea.push_back(reversed(square(9950, 8050, 100)));
  const Result r = generalise({sea}, defaults());
  EXPECT_EQ(r.islets_joined, 1u);
  EXPECT_EQ(r.islands_removed, 0u);
  EXPECT_EQ(holes(r), 0u) << "the islet is part of the cape";
  EXPECT_EQ(r.narrow_gaps, 0u);
}

TEST(CoastIsletClusters, TriangleKeepsHalfHminFromTheCoast) {
  // An islet 300 m off the straight coast of a large island: its triangle (circumradius 404 m)
  // has no room around the centroid; wherever it goes it keeps islet_clearance from the coast,
  // or it is joined.
  Rings sea{box(0, 0, 20000, 20000), reversed(box(2000, 2000, 18000, 10000))};
  sea.push_back(reversed(square(9970, 10300, 60)));
  const Options o = defaults();
  Result res;
  IsletPlacer placer(o, res);
  const GeomPtr w = replace_islets(GeomPtr(new OGRPolygon(to_ogr(sea))), placer, o, res);
  EXPECT_EQ(res.islets_replaced + res.islets_joined, 1u);
  EXPECT_EQ(res.islands_removed, 0u);
  for (int k = 0; k < placer.tris->getNumGeometries(); ++k) {
    const OGRLinearRing* t = placer.tris->getGeometryRef(k)->getExteriorRing();
    for (int i = 0; i < t->getNumPoints(); ++i) EXPECT_GE(t->getY(i), 10500.0 - 1e-9);
  }
  const Result r = generalise({sea}, o);
  EXPECT_EQ(r.narrow_gaps, 0u);
  EXPECT_GE(nearest_other_land(r), 500.0 - 1e-6);
}

TEST(CoastIsletClusters, PlacementsKeepTheirClearanceFromEachOther) {
  // A field of islets 40 m square on a 450 m lattice: a triangle per islet has no room next to
  // its neighbours; whatever the step makes of them keeps hmin/2 between all land.
  std::vector<std::vector<Point2>> islets;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) islets.push_back(square(8000 + 450 * i, 8000 + 450 * j, 40));
  const Result r = generalise(sea_with(islets), defaults());
  EXPECT_EQ(r.narrow_gaps, 0u);
  EXPECT_GE(nearest_other_land(r), 500.0 - 1e-6);
  EXPECT_EQ(r.islands_removed, 0u) << "the field is one cluster";
}

// The joins of replace_islets and the nearest distance from each to the coast of `land` (a
// counter-clockwise ring) outside the box `run` (the part of the coast the join may take).
double join_gap_outside(const IsletPlacer& placer, const std::vector<Point2>& land, const Box2& run) {
  double d = std::numeric_limits<double>::infinity();
  for (const auto& h : placer.joined)
    for (std::size_t i = 0; i < land.size(); ++i) {
      const Point2 a = land[i], b = land[(i + 1) % land.size()];
      // The coast's points outside `run`, sampled every metre.
      const double len = dist(a, b);
      for (double t = 0; t <= len; t += 1) {
        const Point2 q = a + (t / len) * (b - a);
        if (q.x >= run.lo.x && q.x <= run.hi.x && q.y >= run.lo.y && q.y <= run.hi.y) continue;
        d = std::min(d, convex_distance(q, q, h));
      }
    }
  return d;
}

TEST(CoastIsletJoins, IsletInTheCornerOfABayFillsTheCorner) {
  // Land (a hole of the sea) with a wall rising at x = 10400 from its north coast at y = 10000:
  // the water's corner there is square. An islet 100 m square lies 100 m off the north coast
  // and 400 m from the wall. A hull with the north coast alone would leave a notch under 400 m
  // wide against the wall; the join takes the corner of water in instead, or keeps hmin/2 from
  // the wall.
  const std::vector<Point2> land{{2000, 2000}, {18000, 2000}, {18000, 14000}, {10400, 14000}, {10400, 10000}, {2000, 10000}};
  Rings sea{box(0, 0, 20000, 20000), reversed(land)};
  sea.push_back(reversed(square(9900, 10100, 100)));
  const Options o = defaults();
  Result res;
  IsletPlacer placer(o, res);
  replace_islets(GeomPtr(new OGRPolygon(to_ogr(sea))), placer, o, res);
  ASSERT_EQ(res.islets_joined, 1u);
  EXPECT_EQ(res.islands_removed, 0u);
  // Away from the corner's run (the coast within 1.5 km of the islet), the hull keeps hmin/2.
  EXPECT_GE(join_gap_outside(placer, land, Box2{{9000, 9990}, {10410, 11500}}), 500.0 - 1e-6);
  // The hull takes the corner: it reaches the wall.
  const Box2 hb = box_of(placer.joined.front());
  EXPECT_GE(hb.hi.x, 10400.0 - 1e-6);
  const Result r = generalise({sea}, o);
  EXPECT_EQ(r.islets_joined, 1u);
  EXPECT_EQ(r.narrow_gaps, 0u);
}

TEST(CoastIsletJoins, IsletOffAStraightCoastJoinsWithTheShortRun) {
  // An islet 100 m square, 80 m off a straight coast 16 km long: joined along the coast near it
  // (the run of rho, about 0.32 km each side), the coast beyond leaving the hull at its ends.
  const std::vector<Point2> land = box(2000, 2000, 18000, 10000);
  Rings sea{box(0, 0, 20000, 20000), reversed(land)};
  sea.push_back(reversed(square(9950, 10080, 100)));
  const Options o = defaults();
  Result res;
  IsletPlacer placer(o, res);
  replace_islets(GeomPtr(new OGRPolygon(to_ogr(sea))), placer, o, res);
  ASSERT_EQ(res.islets_joined, 1u);
  ASSERT_EQ(placer.joined.size(), 1u);
  const Box2 hb = box_of(placer.joined.front());
  EXPECT_LT(hb.width(), 700.0) << "the first run, not a longer one";
  EXPECT_NEAR(hb.lo.y, 10000.0, 1e-6);
  EXPECT_NEAR(hb.hi.y, 10180.0, 1e-6);
}

}  // namespace
}  // namespace fdr::coast
