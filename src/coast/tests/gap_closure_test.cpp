// Water narrower than the minimum feature width closed or widened (gap_closure.hpp) on synthetic
// channels, islets and tips.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "coast/convex.hpp"
#include "coast/gap_closure.hpp"
#include "coast/narrow_gaps.hpp"

namespace fdr::coast {
namespace {

Options gap_options() {
  Options o;
  o.close_width = 75;
  o.min_feature = 50;
  o.connect_width = 150;
  o.gap_body_area = 40000;
  return o;
}

// A clockwise hole of the box.
std::vector<Point2> island(Box2 b) { return {{b.lo.x, b.lo.y}, {b.lo.x, b.hi.y}, {b.hi.x, b.hi.y}, {b.hi.x, b.lo.y}}; }

double area_of(const Polygons& ps) {
  double a = 0;
  for (const auto& rings : ps)
    for (const auto& r : rings) a += signed_area(r);
  return a;
}

std::size_t count(const Result& res, const std::string& kind) {
  std::size_t n = 0;
  for (const auto& r : res.repairs) n += r.kind == kind;
  return n;
}

Result run(Polygons ps, const Options& o = gap_options()) {
  Result res;
  res.polygons = std::move(ps);
  res.output_area = area_of(res.polygons);
  OGREnvelope box;
  box.MinX = box.MinY = -1e9;
  box.MaxX = box.MaxY = 1e9;
  close_narrow_gaps(o, box, res);
  return res;
}

TEST(CoastGapClosure, BridgeIsTheHullOfTheCoastNearTheGap) {
  // Two squares 20 m apart; the bridge of radius 50 around the gap's middle spans both.
  const Rings rings{{{0, 0}, {1000, 0}, {1000, 1000}, {0, 1000}}, island({{400, 400}, {490, 500}}),
                    island({{510, 400}, {600, 500}})};
  const std::vector<Point2> h = gap_bridge(rings, {500, 450}, 50, 0);
  ASSERT_GE(h.size(), 4u);
  for (const Point2& p : h) EXPECT_LE(std::hypot(p.x - 500, p.y - 450), 50 + 1e-9);
  EXPECT_TRUE(inside_convex({500, 450}, h));
  EXPECT_TRUE(inside_convex({491, 450}, h));
  EXPECT_TRUE(inside_convex({509, 450}, h));
  // The crossing 6 m from the corner (490, 500) snaps to it.
  const std::vector<Point2> snapped = gap_bridge(rings, {500, 445}, 50, 10);
  EXPECT_TRUE(std::find(snapped.begin(), snapped.end(), Point2{490, 500}) != snapped.end());
  // Nothing near: no bridge.
  EXPECT_TRUE(gap_bridge(rings, {200, 200}, 50, 0).empty());
}

TEST(CoastGapClosure, TwoIsletsTwentyMetresApartAreJoined) {
  const Result res = run({{{{0, 0}, {1000, 0}, {1000, 1000}, {0, 1000}}, island({{300, 400}, {490, 500}}),
                           island({{510, 400}, {700, 500}})}});
  ASSERT_EQ(res.polygons.size(), 1u);
  EXPECT_EQ(res.polygons[0].size(), 2u);  // the two islands are one
  EXPECT_TRUE(narrow_gaps(res.polygons, 50, nullptr).empty());
  EXPECT_GE(count(res, "narrow_gap_closed"), 1u);
  EXPECT_EQ(res.closed, count(res, "narrow_gap_closed"));
  EXPECT_GT(res.closed_area, 0);
  // The water removed lies near the gap: at most the bridges' disks.
  EXPECT_LT(1e6 - 2 * 190 * 100 - area_of(res.polygons), 2 * M_PI * 50 * 50);
  EXPECT_NEAR(res.output_area, area_of(res.polygons), 1e-6);
}

TEST(CoastGapClosure, TwoTipsFacingEachOtherAreJoined) {
  // Land spikes from the north and the south coast of a bay, their tips 20 m apart.
  const Rings sea{{{0, 0}, {1000, 0}, {1000, 1000}, {0, 1000}}};
  Rings r{{{0, 0}, {1000, 0}, {1000, 1000}, {520, 1000}, {500, 510}, {480, 1000}, {0, 1000}}};
  r[0] = {{0, 0}, {480, 0}, {500, 490}, {520, 0}, {1000, 0}, {1000, 1000}, {520, 1000}, {500, 510}, {480, 1000},
          {0, 1000}};
  ASSERT_EQ(narrow_gaps({r}, 50, nullptr).size(), 1u);
  const Result res = run({r});
  // The bay's two halves are apart now, each larger than gap_body_area: the closing would cut
  // one off, so the tips are widened apart instead.
  ASSERT_EQ(res.polygons.size(), 1u);
  EXPECT_EQ(count(res, "narrow_gap_widened"), 1u);
  EXPECT_TRUE(narrow_gaps(res.polygons, 50, nullptr).empty());
  EXPECT_GT(area_of(res.polygons), area_of({r}));
  // With small halves (below gap_body_area) the tips are joined and one half removed.
  Options o = gap_options();
  o.gap_body_area = 1e6;
  const Result closed = run({r}, o);
  ASSERT_EQ(closed.polygons.size(), 1u);
  EXPECT_EQ(count(closed, "narrow_gap_closed"), 1u);
  EXPECT_EQ(count(closed, "cut_off_water_removed"), 1u);
  EXPECT_EQ(closed.cut_off, 1u);
  EXPECT_LT(area_of(closed.polygons), 0.55e6);
}

TEST(CoastGapClosure, DeadEndChannelIsClosedWhole) {
  // A channel 20 m wide and 400 m long off the sea, its banks cut into 10 m segments.
  Rings r{{{0, 0}, {1000, 0}, {1000, 500}}};
  for (double x = 1000; x <= 1400; x += 10) r[0].push_back({x, 500});
  for (double x = 1400; x >= 1000; x -= 10) r[0].push_back({x, 520});
  r[0].push_back({1000, 1000});
  r[0].push_back({0, 1000});
  const Result res = run({r});
  ASSERT_EQ(res.polygons.size(), 1u);
  EXPECT_TRUE(narrow_gaps(res.polygons, 50, nullptr).empty());
  EXPECT_GE(res.closed, 1u);
  // The channel's 8000 m^2 are gone (with at most the bridges' bits of the sea at its mouth).
  EXPECT_LT(area_of(res.polygons), 1e6 + 50);
  EXPECT_GT(area_of(res.polygons), 1e6 - 2 * M_PI * 50 * 50);
}

TEST(CoastGapClosure, ChannelToALargeLagoonIsWidened) {
  // The sea and a lagoon 400 m square joined by a channel 20 m wide and 60 m long.
  Rings r{{{0, 0}, {1000, 0}, {1000, 490}, {1060, 490}, {1060, 300}, {1460, 300}, {1460, 700}, {1060, 700},
           {1060, 510}, {1000, 510}, {1000, 1000}, {0, 1000}}};
  const Result res = run({r});
  ASSERT_EQ(res.polygons.size(), 1u);
  EXPECT_EQ(count(res, "narrow_gap_widened"), 1u);
  EXPECT_EQ(res.reconnected, 1u);
  EXPECT_EQ(count(res, "narrow_gap_closed"), 0u);
  EXPECT_TRUE(narrow_gaps(res.polygons, 50, nullptr).empty());
  EXPECT_GT(area_of(res.polygons), area_of({r}));
  // A lagoon below gap_body_area: closed and removed.
  Options o = gap_options();
  o.gap_body_area = 2e5;
  const Result closed = run({r}, o);
  ASSERT_EQ(closed.polygons.size(), 1u);
  EXPECT_EQ(count(closed, "cut_off_water_removed"), 1u);
  EXPECT_LT(area_of(closed.polygons), 1e6 + 1);
}

TEST(CoastGapClosure, WiderGapsAndZeroOptionsAreLeftAlone) {
  const Polygons ps{{{{0, 0}, {1000, 0}, {1000, 1000}, {0, 1000}}, island({{300, 400}, {470, 500}}),
                     island({{530, 400}, {700, 500}})}};
  const Result res = run(ps);
  EXPECT_EQ(res.polygons, ps);
  EXPECT_TRUE(res.repairs.empty());
  Options o = gap_options();
  o.gap_body_area = 0;
  const Polygons near{{{{0, 0}, {1000, 0}, {1000, 1000}, {0, 1000}}, island({{300, 400}, {490, 500}}),
                       island({{510, 400}, {700, 500}})}};
  EXPECT_EQ(run(near, o).polygons, near);
}

}  // namespace
}  // namespace fdr::coast
