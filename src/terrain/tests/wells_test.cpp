// Wells: placing a range in a column (elevations, depths, clipping, snapping, refusals), the PLC
// segments through the horizons (checked by plc::check), and the spacing cap along a segment.
#include <gtest/gtest.h>
#include <cmath>
#include <functional>
#include <string>
#include "base/error.hpp"
#include "plc/check.hpp"
#include "sizing/spacing3d.hpp"
#include "terrain/wells.hpp"
#include "terrain_fixture.hpp"

namespace fdr::terrain {
namespace {
using testing::lattice_tin;
using testing::plane;

Well well(WellRangeKind kind, double upper, double lower) {
  Well w;
  w.name = "w1";
  w.where = "wells.gpkg: layer 'wells', feature FID 7 (w1) at (3, 4)";
  w.kind = kind;
  w.upper = upper;
  w.lower = lower;
  return w;
}

ExitCode code_of(const std::function<void()>& f, std::string* what) {
  try {
    f();
  } catch (const Error& e) {
    *what = e.what();
    return e.code();
  }
  return ExitCode::kOk;
}

TEST(PlaceWell, ElevationsInsideTheColumnStay) {
  WellRepairs rep;
  const WellColumn c = place_well(well(WellRangeKind::kElevation, 50, -100), 4, {100, 0, -200}, 1.0, &rep);
  EXPECT_EQ(c.hi, 50);
  EXPECT_EQ(c.lo, -100);
  EXPECT_EQ(c.tin_vertex, 4u);
  EXPECT_FALSE(rep.clipped_top || rep.clipped_base);
  EXPECT_EQ(rep.snapped, 0);
}

TEST(PlaceWell, DepthsAreBelowTheTop) {
  const WellColumn c = place_well(well(WellRangeKind::kDepth, 10, 150), 0, {100, 0, -200}, 1.0);
  EXPECT_EQ(c.hi, 90);
  EXPECT_EQ(c.lo, -50);
}

TEST(PlaceWell, ClippedToTopAndBaseAndListed) {
  WellRepairs rep;
  const WellColumn c = place_well(well(WellRangeKind::kElevation, 300, -900), 0, {100, 0, -200}, 1.0, &rep);
  EXPECT_EQ(c.hi, 100);
  EXPECT_EQ(c.lo, -200);
  EXPECT_TRUE(rep.clipped_top);
  EXPECT_TRUE(rep.clipped_base);
}

TEST(PlaceWell, EndsNearASurfaceMoveOntoIt) {
  WellRepairs rep;
  const WellColumn c = place_well(well(WellRangeKind::kElevation, 99.5, 0.4), 0, {100, 0, -200}, 1.0, &rep);
  EXPECT_EQ(c.hi, 100);
  EXPECT_EQ(c.lo, 0);
  EXPECT_EQ(rep.snapped, 2);
}

TEST(PlaceWell, OutsideTheVolumeIsAnErrorNamingTheFeature) {
  std::string what;
  EXPECT_EQ(code_of([] { place_well(well(WellRangeKind::kElevation, 500, 200), 0, {100, 0, -200}, 1.0); }, &what),
            ExitCode::kInvalidGeometry);
  EXPECT_NE(what.find("FID 7"), std::string::npos) << what;
  EXPECT_NE(what.find("outside the volume"), std::string::npos) << what;
  EXPECT_EQ(code_of([] { place_well(well(WellRangeKind::kDepth, 400, 500), 0, {100, 0, -200}, 1.0); }, &what),
            ExitCode::kInvalidGeometry);
  EXPECT_EQ(code_of([] { place_well(well(WellRangeKind::kElevation, 10, 20), 0, {100, 0, -200}, 1.0); }, &what),
            ExitCode::kInvalidGeometry);
  EXPECT_NE(what.find("empty"), std::string::npos) << what;
}

TEST(WellSegments, SplitAtEveryHorizonVertexAndCheckedByThePlc) {
  const Tin tin = lattice_tin();
  std::vector<Surface> stack{plane(tin, "top", 10, 1, 0.5), plane(tin, "h1", 2), plane(tin, "h2", -1),
                             plane(tin, "base", -5)};
  TerrainPlc tp = build_terrain_plc(tin, stack);
  const std::size_t n0 = tp.plc.points.size();
  // The centre vertex (4, at (1, 1), the lattice's one inside): top 11.5. From the top to -3
  // (inside the last layer).
  const auto chains = add_well_segments(tp, tin, stack, {{"a", 4, 11.5, -3}});
  ASSERT_EQ(chains.size(), 1u);
  EXPECT_EQ(chains[0], (std::vector<VertexId>{tp.ids[0][4], tp.ids[1][4], tp.ids[2][4], static_cast<VertexId>(n0)}));
  EXPECT_EQ(tp.plc.segments.size(), 3u);
  EXPECT_EQ(tp.plc.points[n0].z, -3);
  EXPECT_EQ(tp.plc.points[n0].x, 1);
  EXPECT_NO_THROW(plc::check(tp.plc));
}

TEST(WellSegments, FromInsideALayerDownToTheBase) {
  const Tin tin = lattice_tin();
  std::vector<Surface> stack{plane(tin, "top", 10), plane(tin, "h1", 2), plane(tin, "h2", -1), plane(tin, "base", -5)};
  TerrainPlc tp = build_terrain_plc(tin, stack);
  const std::size_t n0 = tp.plc.points.size();
  const auto chains = add_well_segments(tp, tin, stack, {{"b", 4, 5, -5}});
  EXPECT_EQ(chains[0], (std::vector<VertexId>{static_cast<VertexId>(n0), tp.ids[1][4], tp.ids[2][4], tp.ids[3][4]}));
  EXPECT_NO_THROW(plc::check(tp.plc));
  // A well at a boundary vertex would lie in a side wall: refused.
  TerrainPlc t2 = build_terrain_plc(tin, stack);
  EXPECT_THROW(add_well_segments(t2, tin, stack, {{"c", 0, 5, -5}}), Error);
}

TEST(WellSegments, PinchedSurfacesGiveNoZeroLengthSegment) {
  const Tin tin = lattice_tin();
  std::vector<Surface> stack{plane(tin, "top", 10), plane(tin, "h1", 10), plane(tin, "base", -5)};
  TerrainPlc tp = build_terrain_plc(tin, stack);
  const auto chains = add_well_segments(tp, tin, stack, {{"a", 4, 10, -5}});
  ASSERT_EQ(chains[0].size(), 2u);
  EXPECT_EQ(tp.plc.segments.size(), 1u);
}

// A well whose end lies inside the vertical wall where a layer ends (end_pinch_outs): both walls
// over the well's vertex take the new end vertex as a corner, so facets and segments meet at vertices.
TEST(WellSegments, AnEndInsideAWallSplitsItsVerticalEdge) {
  const Tin tin = lattice_tin(5, 3);
  std::vector<Surface> stack{plane(tin, "top", 10), plane(tin, "h1", 9.5, 0.25), plane(tin, "base", 0)};
  clamp_surfaces(stack, tin, {});
  const PinchOutRepair r = end_pinch_outs(tin, stack);
  TerrainPlc tp = build_terrain_plc(tin, stack, r.layering);
  const std::size_t n0 = tp.plc.points.size();
  // Vertex 6 at (1, 1): the walls over x = 1 stand between h1 (9.75) and the top (10) there.
  const auto chains = add_well_segments(tp, tin, stack, {{"w", 6, 10, 9.8}});
  EXPECT_EQ(chains[0], (std::vector<VertexId>{tp.ids[0][6], static_cast<VertexId>(n0)}));
  std::size_t walls = 0;
  for (const plc::Facet& f : tp.plc.facets)
    for (VertexId v : f.polygons[0]) walls += v == n0;
  EXPECT_EQ(walls, 2u);
  EXPECT_NO_THROW(plc::check(tp.plc));
}

TEST(CapNearSegments, AtMostHOnTheSegmentAndUntouchedFarAway) {
  sizing::Grid3 g;
  g.nx = g.ny = g.nz = 20;
  g.dx = g.dy = g.dz = 10;
  g.v.assign(g.nx * g.ny * g.nz, 100.0);
  const std::array<Point3, 2> seg{Point3{95, 95, 150}, Point3{95, 95, 30}};
  cap_near_segments(g, {seg}, 4.0);
  const sizing::GridField3 f(g);
  for (double z = 30; z <= 150; z += 7.5) EXPECT_LE(f({95, 95, z}), 4.0) << z;
  EXPECT_EQ(g.at(0, 0, 0), 100.0);
  EXPECT_EQ(g.at(19, 19, 19), 100.0);
  EXPECT_THROW(cap_near_segments(g, {seg}, 0.0), Error);
}

}  // namespace
}  // namespace fdr::terrain
