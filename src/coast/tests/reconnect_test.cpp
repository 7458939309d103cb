// The reconnection of large cut-off water bodies (reconnect.hpp, cut_off.hpp) on a lagoon behind
// a narrow inlet.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "coast/cut_off.hpp"
#include "coast/generalise.hpp"
#include "coast/geometry_ops.hpp"
#include "coast/openings.hpp"
#include "coast/reconnect.hpp"

namespace fdr::coast {
namespace {

// A sea 2 km by 1 km (y 0..1000) and a lagoon 1 km by 800 m north of it (y 1400..2200), one input
// body: an inlet w wide and 400 m long joins them at x = 1000.
Polygons sea_and_lagoon(double w) {
  return {{{{0, 0}, {2000, 0}, {2000, 1000}, {1000 + w / 2, 1000}, {1000 + w / 2, 1400}, {1500, 1400}, {1500, 2200},
            {500, 2200}, {500, 1400}, {1000 - w / 2, 1400}, {1000 - w / 2, 1000}, {0, 1000}}}};
}

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

std::size_t count(const Result& r, const std::string& kind) {
  std::size_t n = 0;
  for (const auto& x : r.repairs) n += x.kind == kind;
  return n;
}

Options opts(double connect_area) {  // hmin 100: close 15 m, connections down to 10 m kept
  Options o;
  o.close_width = 15;
  o.min_feature = 10;
  o.connect_area = connect_area;
  o.connect_width = 90;
  return o;
}

TEST(CoastReconnect, LagoonBehindANarrowInletKeepsItsInletWidened) {
  const GeomPtr W0 = water(sea_and_lagoon(4));
  Result res;
  GeomPtr R = open_water(W0, opts(4e4), res);
  ASSERT_EQ(pieces(*R), 2u);  // the 4 m inlet is closed: the lagoon is cut off
  R = remove_cut_off(std::move(R), *W0, opts(4e4), res);
  EXPECT_EQ(pieces(*R), 1u);
  EXPECT_EQ(res.cut_off, 0u);
  EXPECT_EQ(res.reconnected, 1u);
  EXPECT_EQ(count(res, "water_connection_widened"), 1u);
  EXPECT_TRUE(water_at(*R, {1000, 1800}));  // the lagoon
  EXPECT_TRUE(water_at(*R, {1000, 500}));   // the sea
  // The inlet is at least connect_width wide along its whole length.
  for (double y : {1050.0, 1200.0, 1350.0}) {
    EXPECT_TRUE(water_at(*R, {1000 - 0.44 * 90, y})) << y;
    EXPECT_TRUE(water_at(*R, {1000 + 0.44 * 90, y})) << y;
  }
  // ... and not much wider: the banks moved by about half of it.
  EXPECT_FALSE(water_at(*R, {1000 - 60, 1200}));
  EXPECT_FALSE(water_at(*R, {1000 + 60, 1200}));
  EXPECT_GT(res.reconnected_area, 0.8 * 90 * 400);
  EXPECT_LT(res.reconnected_area, 1.3 * 90 * 400 + 2e4);
}

TEST(CoastReconnect, SmallCutOffBodyIsStillRemoved) {
  const GeomPtr W0 = water(sea_and_lagoon(4));
  Result res;
  GeomPtr R = open_water(W0, opts(1e6), res);  // the lagoon (8e5 m^2) is below connect_area
  R = remove_cut_off(std::move(R), *W0, opts(1e6), res);
  EXPECT_EQ(pieces(*R), 1u);
  EXPECT_EQ(res.cut_off, 1u);
  EXPECT_EQ(res.reconnected, 0u);
  EXPECT_FALSE(water_at(*R, {1000, 1800}));
}

TEST(CoastReconnect, LostConnectionIsTheInletOnly) {
  const GeomPtr W0 = water(sea_and_lagoon(4));
  Result res;
  const GeomPtr R = open_water(W0, opts(0), res);
  OwnedPolygons body, rps;
  polygons_of(W0.get(), body);
  polygons_of(R.get(), rps);
  ASSERT_EQ(rps.size(), 2u);
  const bool first_is_sea = water_at(*rps[0], {1000, 500});
  const OGRPolygon& sea = *rps[first_is_sea ? 0 : 1];
  const OGRPolygon& lagoon = *rps[first_is_sea ? 1 : 0];
  // A small first box: the search grows it until the inlet is whole.
  const GeomPtr c = lost_connection(*body[0], lagoon, sea, 10, 0.01);
  ASSERT_TRUE(c);
  EXPECT_TRUE(water_at(*c, {1000, 1200}));
  EXPECT_LT(area_of(c.get()), 4 * 400 + 2000.0);  // the inlet and its closed mouths' corners
  // Water of another input body beside the inlet: the widened inlet would meet it, so none.
  OGREnvelope box;
  W0->getEnvelope(&box);
  const OGRPolygon other = to_ogr({{{1020, 1100}, {1100, 1100}, {1100, 1300}, {1020, 1300}}});
  EXPECT_FALSE(widened_connection(*c, 90, box, {&other}));
  EXPECT_TRUE(widened_connection(*c, 90, box, {}));
}

}  // namespace
}  // namespace fdr::coast
