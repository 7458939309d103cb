// The coast generalisation's steps one at a time on small synthetic shapes: what each step does
// to a spit, a needle island, a narrow channel, an islet, a narrow strait, overlapping polygons.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <unordered_set>

#include "coast/cut_off.hpp"
#include "coast/generalise.hpp"
#include "coast/geometry_ops.hpp"
#include "coast/islets.hpp"
#include "coast/meets.hpp"
#include "coast/openings.hpp"
#include "coast/restore.hpp"
#include "coast/tiny_edges.hpp"
#include "coast/tips.hpp"
#include "coast/union.hpp"
#include "coast/widen.hpp"

namespace fdr::coast {
namespace {

Rings rect(double x0, double y0, double x1, double y1) { return {{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}}; }

// The water of polygons (valid as given) as one OGR geometry.
GeomPtr water(const Polygons& ps) {
  auto m = std::make_unique<OGRMultiPolygon>();
  for (const auto& rings : ps) {
    OGRPolygon p = to_ogr(rings);
    m->addGeometry(&p);
  }
  return GeomPtr(m.release());
}

bool water_at(const OGRGeometry& g, Point2 q) {
  OGRPoint pt(q.x, q.y);
  return g.Contains(&pt);
}

std::size_t pieces(const OGRGeometry& g) {
  OwnedPolygons ps;
  polygons_of(&g, ps);
  return ps.size();
}

std::size_t holes(const OGRGeometry& g) {
  OwnedPolygons ps;
  polygons_of(&g, ps);
  std::size_t n = 0;
  for (const auto& p : ps) n += static_cast<std::size_t>(p->getNumInteriorRings());
  return n;
}

std::size_t count(const Result& r, const std::string& kind) {
  std::size_t n = 0;
  for (const auto& x : r.repairs) n += x.kind == kind;
  return n;
}

// Options for the closing: land thinner than 30 m is cut unless it is a tip with no other land
// within 50 m of its end.
Options closing_opts(double tip_clearance) {
  Options o;
  o.close_width = 30;
  o.tip_clearance = tip_clearance;
  return o;
}

TEST(CoastSteps, UnionOfTwoOverlappingPolygons) {
  Result res;
  const GeomPtr w = unite({rect(0, 0, 100, 100), rect(50, 50, 150, 150)}, res);
  EXPECT_EQ(pieces(*w), 1u);
  EXPECT_DOUBLE_EQ(area_of(w.get()), 17500.0);  // the overlap stays water, counted once
  EXPECT_DOUBLE_EQ(res.input_area, 17500.0);
  EXPECT_EQ(res.united, 1u);
  EXPECT_DOUBLE_EQ(res.united_overlap_area, 2500.0);
  ASSERT_EQ(count(res, "polygons_united"), 1u);
  const Point2 at = res.repairs[0].where;
  EXPECT_TRUE(at.x > 50 && at.x < 100 && at.y > 50 && at.y < 100) << "reported inside the overlap";
  EXPECT_EQ(res.input_pieces, 1u);

  Result apart;  // disjoint squares: nothing united, two water bodies
  const GeomPtr w2 = unite({rect(0, 0, 100, 100), rect(200, 0, 300, 100)}, apart);
  EXPECT_EQ(apart.united, 0u);
  EXPECT_EQ(apart.input_pieces, 2u);
  EXPECT_TRUE(apart.repairs.empty());
}

// A 4 km sea whose south coast has a headland 200 m wide reaching 600 m north, ending in a spit
// of land 20 m wide at its base that tapers to a tip 400 m further north at (2000, 1000).
Rings sea_with_spit() {
  return {{{0, 0}, {1900, 0}, {1900, 600}, {1990, 600}, {2000, 1000}, {2010, 600}, {2100, 600}, {2100, 0},
           {4000, 0}, {4000, 4000}, {0, 4000}}};
}

TEST(CoastSteps, SpitKeepsItsTipInOpenWater) {
  Result res;
  const GeomPtr w = close_thin_land(water({sea_with_spit()}), closing_opts(50), res);
  EXPECT_EQ(res.tips_kept, 1u);
  EXPECT_FALSE(water_at(*w, {2000, 900})) << "the spit stays land up to near its tip";
  EXPECT_FALSE(water_at(*w, {2000, 650}));
  EXPECT_LT(res.land_removed_area, 500.0);  // only corner slivers at its base

  Result cut;  // tip_clearance 0: every thin part of the land is cut
  const GeomPtr w0 = close_thin_land(water({sea_with_spit()}), closing_opts(0), cut);
  EXPECT_EQ(cut.tips_kept, 0u);
  EXPECT_TRUE(water_at(*w0, {2000, 900}));
  EXPECT_TRUE(water_at(*w0, {2000, 650}));
  EXPECT_GT(cut.land_removed_area, 3500.0);  // the spit: 4000 m^2
}

TEST(CoastSteps, SpitPointingAtNearLandIsCut) {
  const Rings island{{{1900, 1030}, {1900, 1200}, {2100, 1200}, {2100, 1030}}};  // 30 m beyond the tip
  Result res;
  const GeomPtr w = close_thin_land(water({{sea_with_spit()[0], island[0]}}), closing_opts(50), res);
  EXPECT_EQ(res.tips_kept, 0u);
  EXPECT_TRUE(water_at(*w, {2000, 900}));
  EXPECT_FALSE(water_at(*w, {2000, 1100})) << "the island stays";
}

TEST(CoastSteps, NeedleIslandKeptInOpenWaterCutNearTheCoast) {
  // Islands 300 m long and 10 m wide: one in open water, one 20 m from the coast.
  const Rings sea = rect(0, 0, 4000, 4000);
  const Rings far{{{1000, 2000}, {1000, 2010}, {1300, 2010}, {1300, 2000}}};
  const Rings near{{{1000, 20}, {1000, 30}, {1300, 30}, {1300, 20}}};
  Result res;
  const GeomPtr w = close_thin_land(water({{sea[0], far[0], near[0]}}), closing_opts(50), res);
  EXPECT_EQ(res.tips_kept, 1u);
  EXPECT_EQ(holes(*w), 1u);
  EXPECT_FALSE(water_at(*w, {1150, 2005})) << "the needle in open water stays";
  EXPECT_TRUE(water_at(*w, {1150, 25})) << "the needle near the coast became water";
  EXPECT_DOUBLE_EQ(res.land_removed_area, 3000.0);
}

// Two 1 km basins joined by a channel w wide and 500 m long (one water polygon).
Polygons two_basins(double w) {
  return {{{{0, 0}, {1000, 0}, {1000, 500 - w / 2}, {1500, 500 - w / 2}, {1500, 0}, {2500, 0}, {2500, 1000},
            {1500, 1000}, {1500, 500 + w / 2}, {1000, 500 + w / 2}, {1000, 1000}, {0, 1000}}}};
}

Options opening_opts() {  // close water narrower than 30 m, keep connections down to 5 m
  Options o;
  o.close_width = 30;
  o.min_feature = 5;
  return o;
}

TEST(CoastSteps, NarrowDeadEndIsClosedNarrowConnectionKept) {
  // A dead-end inlet 10 m wide: closed.
  const Polygons inlet{{{{0, 0}, {1000, 0}, {1000, 495}, {1500, 495}, {1500, 505}, {1000, 505}, {1000, 1000}, {0, 1000}}}};
  Result r1;
  const GeomPtr a = open_water(water(inlet), opening_opts(), r1);
  EXPECT_EQ(r1.channels_kept, 0u);
  EXPECT_FALSE(water_at(*a, {1250, 500}));
  EXPECT_TRUE(water_at(*a, {500, 500}));
  EXPECT_EQ(pieces(*a), 1u);
  // The same 10 m channel between two basins: a connection, kept.
  Result r2;
  const GeomPtr b = open_water(water(two_basins(10)), opening_opts(), r2);
  EXPECT_EQ(r2.channels_kept, 1u);
  EXPECT_TRUE(water_at(*b, {1250, 500}));
  EXPECT_EQ(pieces(*b), 1u);
}

TEST(CoastSteps, ConnectionNarrowerThanMinFeatureCutsOffTheSmallerBody) {
  const GeomPtr W0 = water(two_basins(3));
  Result res;
  GeomPtr R = open_water(W0, opening_opts(), res);
  EXPECT_EQ(res.channels_kept, 0u);
  EXPECT_FALSE(water_at(*R, {1250, 500}));
  ASSERT_EQ(pieces(*R), 2u);
  // Both basins came from one input body: one of them (equal up to rounding) is removed and
  // reported; the model could not reach it.
  R = remove_cut_off(std::move(R), *W0, opening_opts(), res);
  EXPECT_EQ(pieces(*R), 1u);
  EXPECT_EQ(res.cut_off, 1u);
  EXPECT_EQ(count(res, "cut_off_water_removed"), 1u);
  EXPECT_GT(res.cut_off_area, 9.9e5);
}

std::string wkt(const OGRGeometry& g) {
  char* w = nullptr;
  g.exportToWkt(&w);
  std::string s(w ? w : "");
  CPLFree(w);
  return s;
}

// The two openings one after the other are bitwise what each opening and restoration of the
// water alone give: neither depends on the other (nor on the restorer having served the other).
TEST(CoastSteps, TwoOpeningsAreEachOpeningAlone) {
  // A basin with a dead-end inlet, a channel to a second basin, and islands far out and near
  // the coast (holes: the opening grows them and gives their coast back).
  Polygons ps = two_basins(10);
  ps[0].push_back({{300, 300}, {300, 340}, {340, 340}, {340, 300}});
  ps[0].push_back({{12, 600}, {12, 630}, {30, 630}, {30, 600}});
  ps[0].push_back({{500, 800}, {500, 803}, {520, 803}, {520, 800}});
  const GeomPtr W = water(ps);
  ASSERT_TRUE(W->IsValid());
  const double r1 = 15, r2 = 2.5, hair = 1.5;
  const TwoOpenings both = two_openings(*W, r1, r2, hair);
  const CoastRestorer alone(W.get(), hair);
  EXPECT_EQ(wkt(*both.O1), wkt(*alone.restore(opening(*W, r1))));
  EXPECT_EQ(wkt(*both.O2), wkt(*CoastRestorer(W.get(), hair).restore(opening(*W, r2))));
  EXPECT_GT(area_of(both.O2.get()), area_of(both.O1.get()));
  // r2 = 0: O2 is W itself.
  EXPECT_EQ(wkt(*two_openings(*W, r1, 0, hair).O2), wkt(*W));
}

Options islet_opts(bool join) {  // hmin 100
  Options o;
  o.min_island_area = 3000;
  o.islet_side = 70;
  o.islet_shift = 40;
  o.join_islets = join;
  o.close_width = 15;
  return o;
}

// A 1 km sea with a cape 200 m wide reaching 300 m north from its south coast.
Rings sea_with_cape() {
  return {{{0, 0}, {400, 0}, {400, 300}, {600, 300}, {600, 0}, {1000, 0}, {1000, 1000}, {0, 1000}}};
}

// The openings' pieces are counted against O1 with shared vertices found first (exact
// coordinates) and GEOS asked only for the rest: the same counts as GEOS alone, for pieces that
// meet two polygons at vertices, one at a vertex and one along an edge, one only, none.
TEST(CoastSteps, MeetsBySharedVerticesCountsAsGeosAlone) {
  std::vector<std::unique_ptr<OGRPolygon>> set;
  for (const Rings& r : {rect(0, 0, 1, 1), rect(2, 0, 3, 1), rect(0, 3, 1, 4)})
    set.push_back(std::make_unique<OGRPolygon>(to_ogr({r})));
  Meets by_geos(set, 1e-6), by_vertices(set, 1e-6, false, true);
  const std::vector<std::pair<Rings, std::size_t>> pieces = {
      {rect(1, 0, 2, 1), 2},          // vertices of both squares beside it
      {rect(1, 0.2, 2, 0.8), 2},      // along both squares' edges, no common vertex
      {rect(1, 0, 1.5, 0.5), 1},      // a vertex of one
      {rect(0.5, 1, 2.5, 3), 3},      // a vertex of none, along the edges of all three (count stops at 2)
      {rect(5, 5, 6, 6), 0},          // far from all
      {{{{1, 1}, {2, 1}, {1.5, 2}}}, 2},  // a corner of each of the two lower squares
  };
  for (const auto& [rings, expect] : pieces) {
    const OGRPolygon piece = to_ogr(rings);
    EXPECT_EQ(by_geos.count(piece), std::min<std::size_t>(expect, 2));
    EXPECT_EQ(by_vertices.count(piece), by_geos.count(piece));
  }
}

TEST(CoastSteps, IsletInOpenWaterBecomesATriangle) {
  const Rings islet{{{490, 690}, {490, 710}, {510, 710}, {510, 690}}};  // 400 m^2, far from land
  const Options o = islet_opts(true);
  Result res;
  IsletPlacer placer(o, res);
  GeomPtr w = replace_islets(water({{sea_with_cape()[0], islet[0]}}), placer, o, res);
  EXPECT_EQ(res.islets_replaced, 1u);
  EXPECT_EQ(count(res, "islet_simplified"), 1u);
  EXPECT_EQ(holes(*w), 0u) << "the triangle goes in after the widening";
  ASSERT_EQ(placer.tris->getNumGeometries(), 1);
  const double side = 70, tri_area = std::sqrt(3.0) / 4 * side * side;
  EXPECT_NEAR(placer.tris->getGeometryRef(0)->get_Area(), tri_area, 1e-6 * tri_area);
  w = add_islet_triangles(std::move(w), placer);
  EXPECT_EQ(holes(*w), 1u);
  EXPECT_FALSE(water_at(*w, {500, 700})) << "the triangle stands where the islet was";
}

TEST(CoastSteps, IsletBesideACapeIsJoinedToIt) {
  const Rings islet{{{490, 315}, {490, 335}, {510, 335}, {510, 315}}};  // 15 m north of the cape
  const Polygons in{{sea_with_cape()[0], islet[0]}};
  const Options o = islet_opts(true);
  Result res;
  IsletPlacer placer(o, res);
  const GeomPtr w = add_islet_triangles(replace_islets(water(in), placer, o, res), placer);
  EXPECT_EQ(res.islets_replaced, 0u) << "no room for a triangle";
  EXPECT_EQ(res.islets_joined, 1u);
  EXPECT_GT(res.islets_joined_area, 250.0);  // at least the 15 m x 20 m gap
  EXPECT_EQ(holes(*w), 0u) << "the islet is part of the cape";
  EXPECT_FALSE(water_at(*w, {500, 308})) << "the gap became land";
  EXPECT_FALSE(water_at(*w, {500, 325}));

  const Options no_join = islet_opts(false);  // not joined: removed, it became water
  Result res2;
  IsletPlacer placer2(no_join, res2);
  const GeomPtr w2 = add_islet_triangles(replace_islets(water(in), placer2, no_join, res2), placer2);
  EXPECT_EQ(res2.islets_joined, 0u);
  EXPECT_EQ(res2.islands_removed, 1u);
  EXPECT_TRUE(water_at(*w2, {500, 325}));
}

TEST(CoastSteps, NarrowStraitIsWidened) {
  Options o;
  o.close_width = 30;  // water 30 m to 65 m wide is widened to about 65 m
  o.widen_width = 65;
  Result res;
  const GeomPtr w = widen(water(two_basins(40)), o, res);
  EXPECT_EQ(res.widened, 1u);
  EXPECT_GT(res.widened_area, 0.0);
  // The banks (y = 480 and 520) moved about (65 - 40) / 2 m into the land each.
  EXPECT_TRUE(water_at(*w, {1250, 522}));
  EXPECT_TRUE(water_at(*w, {1250, 478}));
  EXPECT_FALSE(water_at(*w, {1250, 530}));
  EXPECT_FALSE(water_at(*w, {1250, 470}));

  Result wide;  // a strait already 80 m wide stays as it is
  const GeomPtr w2 = widen(water(two_basins(80)), o, wide);
  EXPECT_EQ(wide.widened, 0u);
  EXPECT_DOUBLE_EQ(area_of(w2.get()), area_of(water(two_basins(80)).get()));
}

TEST(CoastSteps, RestorationGivesTheUnchangedCoastItsInputVertices) {
  // A basin with vertices every 100 m along its south side and a 10 m inlet: the opening closes
  // the inlet and rounds the corners; the rest of the coast comes back as the input's vertices.
  Rings basin{{{0, 0}}};
  for (int x = 100; x <= 900; x += 100) basin[0].push_back({static_cast<double>(x), 0});
  for (const Point2 p : {Point2{1000, 0}, Point2{1000, 495}, Point2{1500, 495}, Point2{1500, 505}, Point2{1000, 505},
                         Point2{1000, 1000}, Point2{0, 1000}})
    basin[0].push_back(p);
  const GeomPtr W = water({basin});
  const GeomPtr opened = opening(*W, 15);  // none of the south side's vertices are left in it
  const GeomPtr restored = CoastRestorer(W.get(), 1.5).restore(GeomPtr(opened->clone()));
  std::unordered_set<std::uint64_t> in_vertices;
  for (const Point2 p : basin[0]) in_vertices.insert(point_key(p.x, p.y));
  OwnedPolygons ps;
  polygons_of(restored.get(), ps);
  ASSERT_EQ(ps.size(), 1u);
  const std::vector<Point2> ring = ring_points(ps[0]->getExteriorRing(), true);
  std::size_t from_input = 0;
  for (const Point2 p : ring) from_input += in_vertices.count(point_key(p.x, p.y));
  EXPECT_GE(from_input, 9u) << "the south side's vertices (100 .. 900, 0) are the input's, bit for bit";
  for (int x = 100; x <= 900; x += 100)
    EXPECT_TRUE(std::find(ring.begin(), ring.end(), Point2{static_cast<double>(x), 0}) != ring.end()) << x;
  EXPECT_FALSE(water_at(*restored, {1250, 500})) << "the inlet stays closed";
}

TEST(CoastSteps, TinyEdgeAtANewCornerIsDropped) {
  // (99, 0) is a corner 1.4 m from its neighbour (100, 1): dropped unless it is an input vertex.
  const Rings ring{{{0, 0}, {99, 0}, {100, 1}, {100, 100}, {0, 100}}};
  const Rings a = drop_tiny_edges(ring, {}, 7.5);
  EXPECT_EQ(a, (Rings{{{0, 0}, {100, 1}, {100, 100}, {0, 100}}}));
  const std::unordered_set<std::uint64_t> input{point_key(99, 0)};
  const Rings b = drop_tiny_edges(ring, input, 7.5);
  EXPECT_EQ(b, (Rings{{{0, 0}, {99, 0}, {100, 100}, {0, 100}}})) << "the input corner stays, its new neighbour goes";
  EXPECT_EQ(drop_tiny_edges(ring, {}, 1.0), ring) << "nothing nearer than 1 m";
}

}  // namespace
}  // namespace fdr::coast
