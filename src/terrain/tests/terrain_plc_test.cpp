// build_terrain_plc: vertices shared at pinch-outs, facets, side walls and regions, checked by
// plc::check (planar facets meeting exactly, closed, region points inside); layer volumes.
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include "plc/check.hpp"
#include "terrain/terrain_plc.hpp"
#include "terrain_fixture.hpp"

namespace fdr::terrain {
namespace {
using testing::lattice_tin;
using testing::plane;

std::size_t count_marker(const plc::Plc& p, std::int32_t m) {
  return static_cast<std::size_t>(std::count_if(p.facets.begin(), p.facets.end(), [&](const plc::Facet& f) { return f.marker == m; }));
}

std::size_t count_material(const plc::Plc& p, double a) {
  return static_cast<std::size_t>(std::count_if(p.regions.begin(), p.regions.end(), [&](const plc::Region& r) { return r.attribute == a; }));
}

TEST(TerrainPlc, BoundaryEdgesOfTheLattice) {
  const auto e = boundary_edges(lattice_tin());
  EXPECT_EQ(e.size(), 8u);
}

TEST(TerrainPlc, OneLayerIsAClosedPrism) {
  const Tin tin = lattice_tin();
  const TerrainPlc t = build_terrain_plc(tin, {plane(tin, "top", 10, 1, 0.5), plane(tin, "base", -5)});
  const plc::Plc& p = t.plc;
  EXPECT_EQ(p.points.size(), 18u);
  EXPECT_EQ(count_marker(p, kTopMarker), 8u);
  EXPECT_EQ(count_marker(p, kBaseMarker), 8u);
  EXPECT_EQ(count_marker(p, kSideMarker), 8u);
  ASSERT_EQ(p.regions.size(), 1u);
  EXPECT_EQ(p.regions[0].attribute, 1.0);
  EXPECT_EQ(p.material_names.at(1), "top-base");
  EXPECT_EQ(p.marker_names.at(kSideMarker), "side");
  EXPECT_NO_THROW(plc::check(p));
}

TEST(TerrainPlc, HorizonAsInternalFacets) {
  const Tin tin = lattice_tin();
  const TerrainPlc t = build_terrain_plc(tin, {plane(tin, "top", 10, 1), plane(tin, "h1", 5, 0, 1), plane(tin, "base", 0)});
  const plc::Plc& p = t.plc;
  EXPECT_EQ(p.points.size(), 27u);
  EXPECT_EQ(count_marker(p, kHorizonMarker0), 8u);
  EXPECT_EQ(count_marker(p, kSideMarker), 16u);
  EXPECT_EQ(p.marker_names.at(kHorizonMarker0), "h1");
  EXPECT_EQ(count_material(p, 1), 1u);
  EXPECT_EQ(count_material(p, 2), 1u);
  EXPECT_EQ(p.material_names.at(2), "h1-base");
  EXPECT_NO_THROW(plc::check(p));
}

TEST(TerrainPlc, PinchOutSharesVerticesAndFacets) {
  const Tin tin = lattice_tin();
  std::vector<Surface> s{plane(tin, "top", 10, 1), plane(tin, "h1", 6, 5), plane(tin, "base", 0)};
  clamp_surfaces(s, tin, {});  // h1 meets the top for x >= 1
  const TerrainPlc t = build_terrain_plc(tin, s);
  const plc::Plc& p = t.plc;
  EXPECT_EQ(p.points.size(), 9u + 3u + 9u);
  for (std::size_t v = 0; v < tin.xy.size(); ++v)
    if (tin.xy[v].x >= 1) {
      EXPECT_EQ(t.ids[1][v], t.ids[0][v]);
    }
  EXPECT_EQ(count_marker(p, kTopMarker), 8u);
  EXPECT_EQ(count_marker(p, kHorizonMarker0), 4u);  // the right half is the top's facets
  EXPECT_EQ(count_marker(p, kSideMarker), 4u + 8u);
  EXPECT_NO_THROW(plc::check(p));
}

TEST(TerrainPlc, LayerCutInTwoGetsTwoRegions) {
  const Tin tin = lattice_tin();
  std::vector<Surface> s{plane(tin, "top", 10), plane(tin, "h1", 0), plane(tin, "base", 0)};
  s[2] = plane(tin, "base", -5);
  for (std::size_t v = 0; v < tin.xy.size(); ++v) s[1].z[v] = 10 - 2 * std::abs(tin.xy[v].x - 1);
  const TerrainPlc t = build_terrain_plc(tin, s);
  EXPECT_EQ(count_material(t.plc, 1), 2u);
  EXPECT_EQ(count_material(t.plc, 2), 1u);
  EXPECT_NO_THROW(plc::check(t.plc));
}

TEST(TerrainPlc, HorizonOnTheBaseKeepsTheBaseMarker) {
  const Tin tin = lattice_tin();
  std::vector<Surface> s{plane(tin, "top", 10), plane(tin, "h1", 4, -4), plane(tin, "base", 0)};
  clamp_surfaces(s, tin, {});  // h1 on the base for x >= 1
  const TerrainPlc t = build_terrain_plc(tin, s);
  EXPECT_EQ(count_marker(t.plc, kBaseMarker), 8u);
  EXPECT_EQ(count_marker(t.plc, kHorizonMarker0), 4u);
  EXPECT_NO_THROW(plc::check(t.plc));
}

TEST(TerrainPlc, LayerVolumesAreExactForLinearSurfaces) {
  const Tin tin = lattice_tin();
  const std::vector<Surface> s{plane(tin, "top", 10, 1), plane(tin, "h1", 5, 0, 1), plane(tin, "base", 0)};
  const auto v = layer_volumes(tin, s);
  ASSERT_EQ(v.size(), 2u);
  EXPECT_DOUBLE_EQ(v[0], 4 * 5 + 2 * 2 - 2 * 2);  // integral of 5 + x - y over [0, 2]^2
  EXPECT_DOUBLE_EQ(v[1], 4 * 5 + 2 * 2);          // integral of 5 + y
}

}  // namespace
}  // namespace fdr::terrain
