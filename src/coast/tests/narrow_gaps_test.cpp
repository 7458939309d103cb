// The listing of water left narrower than the resolution (narrow_gaps.hpp) on small shapes.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>

#include "coast/geometry_ops.hpp"
#include "coast/narrow_gaps.hpp"

namespace fdr::coast {
namespace {

// A sea 1 km square (counter-clockwise) with square islands (clockwise holes).
Rings sea_with(const std::vector<Box2>& islands) {
  Rings r{{{0, 0}, {1000, 0}, {1000, 1000}, {0, 1000}}};
  for (const Box2& b : islands) r.push_back({{b.lo.x, b.lo.y}, {b.lo.x, b.hi.y}, {b.hi.x, b.hi.y}, {b.hi.x, b.lo.y}});
  return r;
}

GeomPtr water(const Polygons& ps) {
  auto m = std::make_unique<OGRMultiPolygon>();
  for (const auto& rings : ps) {
    OGRPolygon p = to_ogr(rings);
    m->addGeometry(&p);
  }
  return GeomPtr(m.release());
}

TEST(CoastNarrowGaps, TwoIsletsThirtyMetresApartAreOneGap) {
  const Polygons ps{sea_with({{{400, 400}, {480, 480}}, {{510, 400}, {590, 480}}})};
  const auto gaps = narrow_gaps(ps, 50, &ps);
  ASSERT_EQ(gaps.size(), 1u);
  EXPECT_NEAR(gaps[0].width, 30, 1e-9);
  EXPECT_NEAR(gaps[0].where.x, 495, 1e-9);
  EXPECT_GE(gaps[0].where.y, 400);
  EXPECT_LE(gaps[0].where.y, 480);
  EXPECT_TRUE(gaps[0].in_input);
  // Not input coast: the gap is one the generalisation made (the input's east islet was 20 m
  // farther east).
  EXPECT_FALSE(narrow_gaps(ps, 50, nullptr)[0].in_input);
  const Polygons before{sea_with({{{400, 400}, {480, 480}}, {{530, 400}, {610, 480}}})};
  EXPECT_FALSE(narrow_gaps(ps, 50, &before)[0].in_input);
  // Wider than the limit: none.
  EXPECT_TRUE(narrow_gaps(ps, 30, &ps).empty());
}

TEST(CoastNarrowGaps, IsletNearTheCoastAndAShallowNotch) {
  // An islet 20 m off the south coast; a notch 40 m wide and 20 m deep in the north coast.
  Rings r = sea_with({{{100, 20}, {160, 80}}});
  r[0] = {{0, 0}, {1000, 0}, {1000, 1000}, {620, 1000}, {620, 980}, {580, 980}, {580, 1000}, {0, 1000}};
  const Polygons ps{r};
  const auto gaps = narrow_gaps(ps, 50, nullptr);
  ASSERT_EQ(gaps.size(), 1u);
  EXPECT_NEAR(gaps[0].width, 20, 1e-9);
  EXPECT_NEAR(gaps[0].where.y, 10, 1e-9);
}

TEST(CoastNarrowGaps, LandBetweenTwoWatersIsNoGap) {
  // Two water polygons 20 m apart: land between them, not water.
  const Polygons ps{{{{0, 0}, {100, 0}, {100, 100}, {0, 100}}}, {{{120, 0}, {220, 0}, {220, 100}, {120, 100}}}};
  EXPECT_TRUE(narrow_gaps(ps, 50, nullptr).empty());
}

TEST(CoastNarrowGaps, LongChannelIsListedAFewTimesNotEverySegment) {
  // A dead-end channel 20 m wide and 800 m long, its banks cut into 10 m segments.
  Rings r{{{0, 0}, {1000, 0}, {1000, 100}}};
  for (double x = 1000; x <= 1800; x += 10) r[0].push_back({x, 100});
  for (double x = 1800; x >= 1000; x -= 10) r[0].push_back({x, 120});
  r[0].push_back({1000, 1000});
  r[0].push_back({0, 1000});
  const auto gaps = narrow_gaps({r}, 50, nullptr);
  EXPECT_GE(gaps.size(), 4u);
  EXPECT_LE(gaps.size(), 10u);
  for (const auto& g : gaps) {
    EXPECT_NEAR(g.width, 20, 1e-9);
    EXPECT_GT(g.where.x, 1000 - 1e-9);
  }
}

TEST(CoastNarrowGaps, ListedAsRepairs) {
  Result res;
  res.polygons = {sea_with({{{400, 400}, {480, 480}}, {{510, 400}, {590, 480}}})};
  Options o;
  o.narrow_gap = 50;
  list_narrow_gaps(o, *water(res.polygons), res);
  EXPECT_EQ(res.narrow_gaps, 1u);
  EXPECT_EQ(res.narrow_gaps_made, 0u);
  ASSERT_EQ(res.repairs.size(), 1u);
  EXPECT_EQ(res.repairs[0].kind, "narrow_gap_kept");
  EXPECT_NEAR(res.repairs[0].size, 30, 1e-9);
  o.narrow_gap = 0;
  Result none;
  none.polygons = res.polygons;
  list_narrow_gaps(o, *water(none.polygons), none);
  EXPECT_TRUE(none.repairs.empty());
}

TEST(CoastNarrowGaps, MadeGapsNameTheStepThatMovedEachCoast) {
  // The input: two islets 200 m apart. The result: the left one replaced by a placed triangle
  // reaching to 30 m of the right one (on the input's coast), and a joined hull 20 m to the
  // right one's right.
  const Polygons input{sea_with({{{300, 400}, {320, 420}}, {{510, 400}, {590, 480}}})};
  Options o;
  o.narrow_gap = 50;
  o.islet_side = 100;
  Result res;
  IsletPlacer placer(o, res);
  placer.add_placed({{380, 400}, {480, 440}, {380, 480}}, 0);
  placer.add_joined({{610, 400}, {700, 400}, {700, 480}, {610, 480}});
  Rings result = sea_with({{{510, 400}, {590, 480}}, {{610, 400}, {700, 480}}});
  result.push_back({{380, 400}, {380, 480}, {480, 440}});  // the triangle, a clockwise hole
  res.polygons = {result};
  EXPECT_STREQ(gap_end_cause({480, 440}, &placer, 2.5), "an islet's triangle");
  EXPECT_STREQ(gap_end_cause({610, 440}, &placer, 2.5), "an islet joined to land");
  EXPECT_STREQ(gap_end_cause({100, 100}, &placer, 2.5), "a widened bank or a cut");
  EXPECT_STREQ(gap_end_cause({480, 440}, nullptr, 2.5), "a widened bank or a cut");
  list_narrow_gaps(o, *water(input), res, &placer);
  ASSERT_EQ(res.narrow_gaps, 2u);
  EXPECT_EQ(res.narrow_gaps_made, 2u);
  std::size_t tri = 0, join = 0;
  for (const auto& r : res.repairs) {
    tri += r.reason.find("an islet's triangle facing the input's coast") != std::string::npos;
    join += r.reason.find("an islet joined to land facing the input's coast") != std::string::npos;
  }
  EXPECT_EQ(tri, 1u);
  EXPECT_EQ(join, 1u);
}

}  // namespace
}  // namespace fdr::coast
