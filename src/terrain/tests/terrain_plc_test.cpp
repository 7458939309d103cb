// build_terrain_plc: vertices shared at pinch-outs, facets, side walls and regions, checked by
// plc::check (planar facets meeting exactly, closed, region points inside); layer volumes.
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <vector>
#include "base/error.hpp"
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


// The smallest angle between two facets sharing an edge, measured between their half-planes
// (each facet's vertex mean off the edge; the polygons here are convex): 180 for coplanar
// neighbours, the wedge's opening where two surfaces meet at a pinch-out.
double smallest_facet_angle_deg(const plc::Plc& p) {
  std::map<std::pair<VertexId, VertexId>, std::vector<std::size_t>> by_edge;
  std::vector<Point3> centre(p.facets.size(), Point3{0, 0, 0});
  for (std::size_t f = 0; f < p.facets.size(); ++f) {
    const auto& poly = p.facets[f].polygons.at(0);
    for (VertexId v : poly) centre[f] = centre[f] + (1.0 / static_cast<double>(poly.size())) * p.points[v];
    for (std::size_t k = 0; k < poly.size(); ++k) {
      const VertexId a = poly[k], b = poly[(k + 1) % poly.size()];
      by_edge[{std::min(a, b), std::max(a, b)}].push_back(f);
    }
  }
  double smallest = 180;
  for (const auto& [e, fs] : by_edge) {
    const Point3 u = p.points[e.first], d = p.points[e.second] - u;
    const Point3 t = (1.0 / std::sqrt(dot(d, d))) * d;
    for (std::size_t i = 0; i < fs.size(); ++i)
      for (std::size_t j = i + 1; j < fs.size(); ++j) {
        Point3 w1 = centre[fs[i]] - u, w2 = centre[fs[j]] - u;
        w1 = w1 - dot(w1, t) * t;
        w2 = w2 - dot(w2, t) * t;
        const double c = dot(w1, w2) / std::sqrt(dot(w1, w1) * dot(w2, w2));
        smallest = std::min(smallest, std::acos(std::clamp(c, -1.0, 1.0)) * 180 / M_PI);
      }
  }
  return smallest;
}

// h1 pinches out against the top between x = 1 and x = 2 on [0, 4] x [0, 2], 0.125 thick at x = 1:
// as triangulated its facets meet the top's in a wedge of about 7 degrees; with the pinch-out
// ended (end_pinch_outs) the layer stops at a vertical wall over x = 1, and every pair of facets
// meets at about a right angle or more.
TEST(TerrainPlc, PinchOutEndsAtAWallWithoutWedges) {
  const Tin tin = lattice_tin(5, 3);
  std::vector<Surface> s{plane(tin, "top", 10), plane(tin, "h1", 9.75, 0.125), plane(tin, "base", 0)};
  clamp_surfaces(s, tin, {});
  const TerrainPlc wedge = build_terrain_plc(tin, s);
  EXPECT_LT(smallest_facet_angle_deg(wedge.plc), 8.0);

  const PinchOutRepair r = end_pinch_outs(tin, s);
  const TerrainPlc t = build_terrain_plc(tin, s, r.layering);
  const plc::Plc& p = t.plc;
  EXPECT_NO_THROW(plc::check(p));
  EXPECT_GT(smallest_facet_angle_deg(p), 80.0);
  // Two vertical walls over x = 1 carry h1's marker beside its 4 facets over [0, 1] x [0, 2].
  EXPECT_EQ(count_marker(p, kHorizonMarker0), 4u + 2u);
  EXPECT_EQ(count_material(p, 1), 1u);
  EXPECT_EQ(count_material(p, 2), 1u);
  // h1's vertices right of x = 1 are used by no facet.
  for (std::size_t v = 0; v < tin.xy.size(); ++v)
    if (tin.xy[v].x == 2 || tin.xy[v].x == 3) {
      EXPECT_EQ(t.ids[1][v], t.ids[0][v]);  // on the top
    }
  EXPECT_EQ(p.points.size(), 15u + 6u + 15u);  // top, h1 over x <= 1, base
  // The volumes of the repaired layers: the wedge (0.1875 per unit of y) moves to the layer below.
  const auto before = layer_volumes(tin, s), after = layer_volumes(tin, s, r.layering);
  EXPECT_NEAR(after[0], before[0] - r.volume[0], 1e-12);
  EXPECT_NEAR(after[1], before[1] + r.volume[0], 1e-12);
  EXPECT_NEAR(r.volume[0], 2 * 0.5 * (0.125 + 0.25) / 3, 1e-15);
}

// Two horizons pinching out across each other, against the top and onto the base: the PLC is
// closed and valid, every facet pair meets at more than a thin wedge, every material is present.
TEST(TerrainPlc, CrossingPinchOutsGiveAValidPlc) {
  const Tin tin = lattice_tin(7, 5);
  std::vector<Surface> s{plane(tin, "top", 10, 0.1), plane(tin, "h1", 11, -1.5, 0.5), plane(tin, "h2", 3, 1, -1.5),
                         plane(tin, "base", 0)};
  clamp_surfaces(s, tin, {}, 0.5);
  const PinchOutRepair r = end_pinch_outs(tin, s);
  const TerrainPlc t = build_terrain_plc(tin, s, r.layering);
  EXPECT_NO_THROW(plc::check(t.plc));
  EXPECT_GT(smallest_facet_angle_deg(t.plc), 20.0);
  for (double m : {1.0, 2.0, 3.0}) EXPECT_GE(count_material(t.plc, m), 1u) << m;
  double total = 0;
  for (double v : layer_volumes(tin, s, r.layering)) total += v;
  double column = 0;
  for (double v : layer_volumes(tin, {s.front(), s.back()})) column += v;
  EXPECT_NEAR(total, column, 1e-9 * column);  // the layers still fill the column
}


// Random stacks of planes and bumps (fixed seed): after clamping and ending the pinch-outs, every
// layer over every triangle is empty or positive at all corners, the PLC passes plc::check, and
// the layers still fill the column.
TEST(TerrainPlc, RandomStacksGiveValidPlcsWithoutWedges) {
  const Tin tin = lattice_tin(6, 5);
  std::mt19937 rng(49);
  std::uniform_real_distribution<double> u(-1, 1);
  int checked = 0, repaired = 0;
  for (int round = 0; round < 200; ++round) {
    const std::size_t horizons = 1 + round % 3;
    std::vector<Surface> s{plane(tin, "top", 10, 0.3 * u(rng), 0.3 * u(rng))};
    for (std::size_t h = 0; h < horizons; ++h) {
      Surface z = plane(tin, "h" + std::to_string(h + 1), 5 + 4 * u(rng), 2 * u(rng), 2 * u(rng));
      for (double& e : z.z) e += u(rng);
      s.push_back(std::move(z));
    }
    s.push_back(plane(tin, "base", 0, 0.2 * u(rng), 0));
    try {
      clamp_surfaces(s, tin, {}, round % 2 ? 0.5 : 0.0);
    } catch (const Error&) {
      continue;  // a horizon outside the column everywhere
    }
    const PinchOutRepair r = end_pinch_outs(tin, s);
    repaired += !r.layering.identity();
    for (std::size_t t = 0; t < tin.triangles.size(); ++t)
      for (std::size_t k = 0; k + 1 < s.size(); ++k) {
        int positive = 0;
        for (int c = 0; c < 3; ++c)
          positive += corner_z(s, r.layering, tin, t, k, c) > corner_z(s, r.layering, tin, t, k + 1, c);
        ASSERT_TRUE(positive == 0 || positive == 3) << "round " << round << " triangle " << t << " layer " << k;
      }
    const TerrainPlc p = build_terrain_plc(tin, s, r.layering);
    ASSERT_NO_THROW(plc::check(p.plc)) << "round " << round;
    double total = 0, column = 0;
    for (double v : layer_volumes(tin, s, r.layering)) total += v;
    for (double v : layer_volumes(tin, {s.front(), s.back()})) column += v;
    EXPECT_NEAR(total, column, 1e-9 * column) << "round " << round;
    ++checked;
  }
  EXPECT_GT(checked, 100);
  EXPECT_GT(repaired, checked / 2);
}

}  // namespace
}  // namespace fdr::terrain
