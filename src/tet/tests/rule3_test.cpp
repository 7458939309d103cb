// Rule 3's steps on a layered box: the walk that finds the subfacet a circumcentre lies beyond,
// checked against the conflict region dug in full, and the regions flooded again after a
// boundary split (relabel_regions), checked against a fresh flood.
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <set>
#include "plc/check.hpp"
#include "predicates/predicates3d.hpp"
#include "sizing/spacing3d.hpp"
#include "tet/dt_queries.hpp"
#include "tet/refiner3.hpp"

using namespace fdr;
using namespace fdr::tet;

namespace {

void add_quad(plc::Plc& plc, std::vector<VertexId> poly, int marker) {
  plc::Facet f;
  f.polygons.push_back(std::move(poly));
  f.marker = marker;
  plc.facets.push_back(f);
}

// [0, 4]^2 x [0, 1] cut at z = 0.125 into a thin bottom layer (material 1) and the rest (2): the
// flat tetrahedra next to the interface have circumcentres beyond it.
plc::Plc thin_layer_box() {
  plc::Plc plc;
  const double zs[3] = {0, 0.125, 1};
  for (double z : zs)
    for (int k = 0; k < 4; ++k) plc.points.push_back({(k & 1) ? 4.0 : 0.0, (k & 2) ? 4.0 : 0.0, z});
  auto id = [](int level, int k) { return static_cast<VertexId>(4 * level + k); };
  int marker = 1;
  for (int level = 0; level < 3; ++level) add_quad(plc, {id(level, 0), id(level, 1), id(level, 3), id(level, 2)}, marker++);
  const int sides[4][2] = {{0, 1}, {1, 3}, {3, 2}, {2, 0}};
  for (int layer = 0; layer < 2; ++layer)
    for (const auto& s : sides) add_quad(plc, {id(layer, s[0]), id(layer, s[1]), id(layer + 1, s[1]), id(layer + 1, s[0])}, marker++);
  plc.regions.push_back({{2, 2, 0.0625}, 1, -1});
  plc.regions.push_back({{2, 2, 0.5}, 2, -1});
  return plc;
}

// Whether the insertion of p with conflict region `cavity` destroys subfacet s (both its
// tetrahedra are in the region), or p encroaches s.
bool encroached_or_destroyed(const Refiner3& r, const std::vector<TetId>& cavity, std::uint32_t s, Point3 p) {
  const auto& v = r.boundary().tri(s).v;
  const Delaunay3& dt = r.dt();
  if (predicates::equatorial_side(dt.point(v[0]), dt.point(v[1]), dt.point(v[2]), p) >= 0) return true;
  int holders = 0;
  for (TetId t : cavity) {
    const auto& tv = dt.vertices(t);
    const auto has = [&](VertexId x) { return std::find(tv.begin(), tv.end(), x) != tv.end(); };
    holders += has(v[0]) && has(v[1]) && has(v[2]);
  }
  return holders == 2;
}

// A wedge along y whose bottom (z = 0) and tilted facet meet at 10 degrees: the small angle's
// vertices stay in the other facet's equatorial spheres (the acute pair's exemption), so flat
// tetrahedra in the wedge have circumcentres beyond the bottom.
plc::Plc wedge10() {
  plc::Plc plc;
  const double c = std::cos(10 * M_PI / 180), s = std::sin(10 * M_PI / 180);
  plc.points = {{0, 0, 0}, {1, 0, 0}, {c, 0, s}, {0, 1, 0}, {1, 1, 0}, {c, 1, s}};
  const std::vector<std::vector<VertexId>> polys = {{0, 1, 4, 3}, {0, 2, 5, 3}, {1, 2, 5, 4}, {0, 1, 2}, {3, 4, 5}};
  for (std::size_t i = 0; i < polys.size(); ++i) add_quad(plc, polys[i], static_cast<int>(i + 1));
  return plc;
}

}  // namespace

TEST(TetRule3, WalkFindsTheSubfacetTheCircumcentreDestroys) {
  const plc::Plc plc = wedge10();
  const plc::FacetTriangulation ft = plc::check_and_triangulate(plc);
  const sizing::ConstantField3 f(0.2);
  Refiner3 r(plc, ft, f, {});
  r.conform();
  r.refine();  // what is left near the small angle
  std::size_t found = 0;
  std::vector<TetId> cavity;
  r.dt().for_each_finite_tet([&](TetId t) {
    if (r.region(t) == kOutsideRegion) return;
    BadTet b;
    r.tet_bad(t, &b);
    if (!std::isfinite(b.centre.x)) return;
    const std::uint32_t s = r.subfacet_toward(t, b.centre);
    if (s == UINT32_MAX) return;
    ++found;
    ASSERT_TRUE(r.boundary().tri(s).alive);
    conflict_region(r.dt(), b.centre, t, cavity);
    EXPECT_TRUE(encroached_or_destroyed(r, cavity, s, b.centre)) << "tet " << t << " subfacet " << s;
  });
  // A circumcentre inside its own tetrahedron crosses nothing.
  r.dt().for_each_finite_tet([&](TetId t) {
    if (r.region(t) == kOutsideRegion) return;
    BadTet b;
    r.tet_bad(t, &b);
    if (!std::isfinite(b.centre.x) || r.dt().locate(b.centre, t) != t) return;
    EXPECT_EQ(r.subfacet_toward(t, b.centre), UINT32_MAX) << t;
  });
  EXPECT_GT(found, 0u);  // flat tetrahedra in the wedge reach across its bottom
}

TEST(TetRule3, RelabelRegionsRestoresTheFlood) {
  const plc::Plc plc = thin_layer_box();
  const plc::FacetTriangulation ft = plc::check_and_triangulate(plc);
  const sizing::ConstantField3 f(0.5);
  Refiner3 r(plc, ft, f, {});
  r.conform();
  r.refine();
  EXPECT_EQ(r.stale_regions(), "");
  std::vector<std::int32_t> flooded;
  std::vector<TetId> all;
  for (TetId t = 0; t < r.dt().tet_slots(); ++t) {
    flooded.push_back(r.region(t));
    if (r.dt().alive(t)) all.push_back(t);
  }
  std::set<std::int32_t> codes(flooded.begin(), flooded.end());
  EXPECT_TRUE(codes.count(0) && codes.count(1) && codes.count(kOutsideRegion));
  // The interface vertex nearest the middle, and the tetrahedra within two rings of it, on both
  // sides of the interface: as an insertion there would have remade them.
  VertexId mid = kNoId;
  double best = 1e300;
  for (VertexId v = 0; v < r.dt().num_vertices(); ++v) {
    const Point3 p = r.dt().point(v);
    if (p.z == 0.125 && norm2(p - Point3{2, 2, 0.125}) < best) best = norm2(p - Point3{2, 2, 0.125}), mid = v;
  }
  ASSERT_NE(mid, kNoId);
  std::vector<TetId> ring, rings;
  vertex_star(r.dt(), mid, ring);
  std::set<VertexId> near;
  for (TetId t : ring)
    for (VertexId v : r.dt().vertices(t)) near.insert(v);
  for (TetId t : all) {
    const auto& v = r.dt().vertices(t);
    if (std::any_of(v.begin(), v.end(), [&](VertexId x) { return near.count(x) != 0; })) rings.push_back(t);
  }
  std::set<std::int32_t> relabelled;
  for (TetId t : rings) relabelled.insert(r.region(t));
  EXPECT_TRUE(relabelled.count(0) && relabelled.count(1));
  rings.push_back(rings.front());  // a repeated slot is relabelled once
  r.relabel_regions(rings);
  for (TetId t = 0; t < r.dt().tet_slots(); ++t)
    if (r.dt().alive(t)) EXPECT_EQ(r.region(t), flooded[t]) << t;
  EXPECT_EQ(r.stale_regions(), "");
  // With every tetrahedron to relabel nothing is left to flood from: all but the ghosts fall to
  // the default region, which a fresh flood then corrects.
  r.relabel_regions(all);
  for (TetId t : all) EXPECT_EQ(r.region(t), r.dt().is_ghost(t) ? kOutsideRegion : kDefaultRegion) << t;
  EXPECT_NE(r.stale_regions(), "");
}
