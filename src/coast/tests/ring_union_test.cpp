// The union of a water polygon with overlapping pieces ring by ring (ring_union.hpp), against
// GEOS's overlay of the whole, and the box index it finds the pieces near each hole with.
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "coast/box_index.hpp"
#include "coast/ring_union.hpp"

namespace fdr::coast {
namespace {

std::unique_ptr<OGRPolygon> square(double x0, double y0, double x1, double y1) {
  auto p = std::make_unique<OGRPolygon>();
  OGRLinearRing r = closed_ring({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}});
  p->addRing(&r);
  return p;
}

// A square of water [0, 100]^2 with square islands (holes) of side 10 at the given corners.
OGRPolygon sea_with_islands(const std::vector<Point2>& corners) {
  OGRPolygon p = *square(0, 0, 100, 100);
  for (const Point2& c : corners) {
    OGRLinearRing h = closed_ring({{c.x, c.y}, {c.x, c.y + 10}, {c.x + 10, c.y + 10}, {c.x + 10, c.y}});
    p.addRing(&h);
  }
  return p;
}

// union_by_rings(p, pieces) covers the same area as GEOS's union and is valid.
void expect_same_as_overlay(const OGRPolygon& p, const OwnedPolygons& pieces) {
  GeomPtr mine = union_by_rings(p, pieces, "test");
  ASSERT_TRUE(mine);
  EXPECT_TRUE(mine->IsValid());
  OGRMultiPolygon m;
  for (const auto& d : pieces) m.addGeometry(d.get());
  GeomPtr theirs(p.Union(&m));
  ASSERT_TRUE(theirs);
  EXPECT_NEAR(area_of(mine.get()), area_of(theirs.get()), 1e-9);
  GeomPtr sym(mine->SymDifference(theirs.get()));
  ASSERT_TRUE(sym);
  EXPECT_LT(area_of(sym.get()), 1e-9);
}

TEST(CoastRingUnion, BoxIndexFindsTheBoxesAQueryMeets) {
  std::vector<OGREnvelope> boxes(4);
  auto set = [](OGREnvelope& e, double x0, double y0, double x1, double y1) {
    e.MinX = x0; e.MinY = y0; e.MaxX = x1; e.MaxY = y1;
  };
  set(boxes[0], 0, 0, 1, 1);
  set(boxes[1], 50, 50, 51, 51);
  set(boxes[2], 0, 0, 100, 2);  // long and thin: in many cells
  set(boxes[3], 99, 99, 100, 100);
  const BoxIndex index(boxes);
  OGREnvelope q;
  set(q, 0.5, 0.5, 3, 3);
  std::vector<std::size_t> near;
  index.near(q, &near);
  EXPECT_EQ(near, (std::vector<std::size_t>{0, 2}));
  set(q, 49, 49, 50, 50);  // touching counts (closed boxes)
  index.near(q, &near);
  EXPECT_EQ(near, (std::vector<std::size_t>{1}));
  set(q, 200, 200, 300, 300);
  index.near(q, &near);
  EXPECT_TRUE(near.empty());
}

TEST(CoastRingUnion, PiecesCrossingTheCoastAndIslandsGiveTheOverlaysUnion) {
  const OGRPolygon p = sea_with_islands({{20, 20}, {60, 20}, {20, 60}, {75, 75}});
  OwnedPolygons pieces;
  pieces.push_back(square(-5, 40, 5, 50));     // crosses the outer ring
  pieces.push_back(square(15, 22, 25, 26));    // reaches into the first island
  pieces.push_back(square(25, 55, 28, 75));    // cuts the third island in two
  pieces.push_back(square(45, 45, 50, 50));    // in open water: adds nothing
  pieces.push_back(square(95, 95, 105, 105));  // crosses the outer ring at a corner
  expect_same_as_overlay(p, pieces);
  GeomPtr mine = union_by_rings(p, pieces, "test");
  OwnedPolygons ps;
  polygons_of(mine.get(), ps);
  ASSERT_EQ(ps.size(), 1u);
  EXPECT_EQ(ps[0]->getNumInteriorRings(), 5);  // the third island in two pieces
}

TEST(CoastRingUnion, APieceJoiningTwoIslandsShrinksBoth) {
  const OGRPolygon p = sea_with_islands({{20, 20}, {32, 20}});
  OwnedPolygons pieces;
  pieces.push_back(square(28, 24, 34, 26));  // across the channel between them
  expect_same_as_overlay(p, pieces);
}

TEST(CoastRingUnion, AnIslandEatenWholeLeavesNoHole) {
  const OGRPolygon p = sea_with_islands({{20, 20}, {60, 60}});
  OwnedPolygons pieces;
  pieces.push_back(square(18, 18, 32, 32));
  expect_same_as_overlay(p, pieces);
  GeomPtr mine = union_by_rings(p, pieces, "test");
  OwnedPolygons ps;
  polygons_of(mine.get(), ps);
  ASSERT_EQ(ps.size(), 1u);
  EXPECT_EQ(ps[0]->getNumInteriorRings(), 1);
}

TEST(CoastRingUnion, ManyIslandsOnlySomeReachedAsTheOverlay) {
  std::vector<Point2> corners;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) corners.push_back({2.0 + 16 * i, 2.0 + 16 * j});
  const OGRPolygon p = sea_with_islands(corners);
  OwnedPolygons pieces;
  for (int i = 0; i < 6; i += 2) pieces.push_back(square(9.0 + 16 * i, 9.0 + 16 * i, 14.0 + 16 * i, 14.0 + 16 * i));
  expect_same_as_overlay(p, pieces);
}

TEST(CoastRingUnion, AHoleLeftWithAHoleOfItsOwnIsRefused) {
  const OGRPolygon p = sea_with_islands({{20, 20}});
  OwnedPolygons pieces;
  pieces.push_back(square(24, 24, 26, 26));  // strictly inside the island
  EXPECT_FALSE(union_by_rings(p, pieces, "test"));
}

}  // namespace
}  // namespace fdr::coast
