// Delaunay3 against CGAL's Delaunay_triangulation_3: the same tetrahedra on points in general
// position; on degenerate sets (lattices, cospherical points) a valid tetrahedralization with
// empty circumspheres, CGAL's volume and CGAL's hull.
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <vector>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include "base/error.hpp"
#include "predicates/predicates3d.hpp"
#include "tet/delaunay3.hpp"
#include "tet/spatial_sort.hpp"

using namespace fdr;
using namespace fdr::tet;

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_3<std::size_t, K>;
using Tds = CGAL::Triangulation_data_structure_3<Vb>;
using Dt = CGAL::Delaunay_triangulation_3<K, Tds>;
using Quad = std::array<std::size_t, 4>;

Dt cgal_of(const std::vector<Point3>& pts) {
  std::vector<std::pair<K::Point_3, std::size_t>> in;
  for (std::size_t i = 0; i < pts.size(); ++i) in.push_back({{pts[i].x, pts[i].y, pts[i].z}, i});
  return Dt(in.begin(), in.end());
}

std::set<Quad> cgal_tets(const Dt& dt) {
  std::set<Quad> s;
  for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c) {
    Quad q{c->vertex(0)->info(), c->vertex(1)->info(), c->vertex(2)->info(), c->vertex(3)->info()};
    std::sort(q.begin(), q.end());
    s.insert(q);
  }
  return s;
}

std::set<std::size_t> cgal_hull(const Dt& dt) {
  std::vector<Dt::Vertex_handle> vs;
  dt.adjacent_vertices(dt.infinite_vertex(), std::back_inserter(vs));
  std::set<std::size_t> s;
  for (auto v : vs) s.insert(v->info());
  return s;
}

double cgal_volume(const Dt& dt) {
  double v = 0;
  for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c) v += dt.tetrahedron(c).volume();
  return v;
}

// Input index of each vertex id.
std::vector<std::size_t> input_of(const BulkInsertion& b, std::size_t nverts) {
  std::vector<std::size_t> in(nverts, ~std::size_t{0});
  for (std::size_t i = 0; i < b.vertex_of.size(); ++i)
    if (!std::binary_search(b.duplicates.begin(), b.duplicates.end(), i)) in[b.vertex_of[i]] = i;
  return in;
}

std::set<Quad> our_tets(const Delaunay3& d, const std::vector<std::size_t>& in) {
  std::set<Quad> s;
  d.for_each_finite_tet([&](TetId t) {
    const auto& v = d.vertices(t);
    Quad q{in[v[0]], in[v[1]], in[v[2]], in[v[3]]};
    std::sort(q.begin(), q.end());
    s.insert(q);
  });
  return s;
}

std::set<std::size_t> our_hull(const Delaunay3& d, const std::vector<std::size_t>& in) {
  std::set<std::size_t> s;
  for (TetId t = 0; t < d.tet_slots(); ++t)
    if (d.alive(t) && d.is_ghost(t))
      for (int k = 0; k < 3; ++k) s.insert(in[d.vertices(t)[k]]);
  return s;
}

double our_volume(const Delaunay3& d) {
  double v = 0;
  d.for_each_finite_tet([&](TetId t) {
    const auto& w = d.vertices(t);
    const Point3 a = d.point(w[0]);
    v += dot(d.point(w[1]) - a, cross(d.point(w[2]) - a, d.point(w[3]) - a)) / 6;
  });
  return v;
}

void expect_valid_delaunay(const Delaunay3& d) {
  std::string why;
  EXPECT_TRUE(d.check_valid(&why)) << why;
  EXPECT_TRUE(d.is_delaunay(&why)) << why;
}

// Degenerate sets: the tetrahedra may differ from CGAL's, the rest may not.
void expect_like_cgal_degenerate(const std::vector<Point3>& pts) {
  Delaunay3 d;
  const auto b = d.insert_all(pts);
  expect_valid_delaunay(d);
  const Dt dt = cgal_of(pts);
  ASSERT_EQ(d.num_vertices(), dt.number_of_vertices());
  const auto in = input_of(b, d.num_vertices());
  const std::set<std::size_t> cg_hull = cgal_hull(dt);
  // CGAL keeps the first of duplicate points; ours may keep another one of the same position.
  std::set<Point3, bool (*)(const Point3&, const Point3&)> hp([](const Point3& a, const Point3& b) {
    return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
  });
  std::set<Point3, bool (*)(const Point3&, const Point3&)> cp(hp.key_comp());
  for (const auto i : our_hull(d, in)) hp.insert(pts[i]);
  for (const auto i : cg_hull) cp.insert(pts[i]);
  EXPECT_TRUE(hp == cp);
  EXPECT_NEAR(our_volume(d), cgal_volume(dt), 1e-9 * std::abs(cgal_volume(dt)));
}

std::vector<Point3> random_cube(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Point3> pts(n);
  for (auto& p : pts) p = {u(rng), u(rng), u(rng)};
  return pts;
}
}  // namespace

TEST(Delaunay3, RandomPointsSameTetrahedraAsCgal) {
  for (const std::size_t n : {5u, 50u, 2000u, 30000u}) {
    const auto pts = random_cube(n, n);
    Delaunay3 d;
    const auto b = d.insert_all(pts);
    EXPECT_TRUE(b.duplicates.empty());
    expect_valid_delaunay(d);
    const Dt dt = cgal_of(pts);
    const auto in = input_of(b, d.num_vertices());
    EXPECT_EQ(d.num_finite_tets(), dt.number_of_finite_cells());
    EXPECT_TRUE(our_tets(d, in) == cgal_tets(dt)) << n;
    EXPECT_TRUE(our_hull(d, in) == cgal_hull(dt)) << n;
  }
}

TEST(Delaunay3, LatticeIsValidDelaunayWithCgalVolumeAndHull) {
  std::vector<Point3> pts;
  for (int x = 0; x < 7; ++x)
    for (int y = 0; y < 6; ++y)
      for (int z = 0; z < 5; ++z) pts.push_back({x * 0.1, y * 0.25, z * 1.0});
  expect_like_cgal_degenerate(pts);
  // The same lattice in reverse order (another insertion order through BRIO's hash).
  std::reverse(pts.begin(), pts.end());
  expect_like_cgal_degenerate(pts);
}

TEST(Delaunay3, CosphericalPointsAreValid) {
  // Every integer point on the spheres x^2 + y^2 + z^2 = 50 and = 2 (exactly cospherical sets,
  // many coplanar subsets), then with the centre.
  std::vector<Point3> pts;
  for (int r2 : {50, 2})
    for (int x = -8; x <= 8; ++x)
      for (int y = -8; y <= 8; ++y)
        for (int z = -8; z <= 8; ++z)
          if (x * x + y * y + z * z == r2) pts.push_back({double(x), double(y), double(z)});
  expect_like_cgal_degenerate(pts);
  pts.push_back({0, 0, 0});
  expect_like_cgal_degenerate(pts);
}

TEST(Delaunay3, DuplicatesAreReportedNotInserted) {
  auto pts = random_cube(500, 3);
  pts.push_back(pts[10]);
  pts.push_back(pts[20]);
  pts.push_back({-0.0, 0.5, 0.5});
  pts.push_back({0.0, 0.5, 0.5});
  Delaunay3 d;
  const auto b = d.insert_all(pts);
  EXPECT_EQ(b.duplicates.size(), 3u);
  EXPECT_EQ(d.num_vertices(), 501u);
  EXPECT_EQ(b.vertex_of[500], b.vertex_of[10]);
  EXPECT_EQ(b.vertex_of[501], b.vertex_of[20]);
  EXPECT_EQ(b.vertex_of[502], b.vertex_of[503]);
  const Insertion again = d.insert(pts[7]);
  EXPECT_TRUE(again.duplicate);
  EXPECT_EQ(again.vertex, b.vertex_of[7]);
  expect_valid_delaunay(d);
}

TEST(Delaunay3, SmallCases) {
  Delaunay3 d;
  EXPECT_EQ(d.dimension(), -1);
  EXPECT_EQ(d.locate({0, 0, 0}), kNoId);
  d.insert({0, 0, 0});
  d.insert({1, 0, 0});
  d.insert({2, 0, 0});  // collinear
  EXPECT_EQ(d.dimension(), 1);
  d.insert({0, 1, 0});
  d.insert({1, 1, 0});
  EXPECT_TRUE(d.insert({1, 1, 0}).duplicate);
  EXPECT_EQ(d.dimension(), 2);
  EXPECT_EQ(d.num_finite_tets(), 0u);
  EXPECT_TRUE(d.to_mesh().tets.empty());
  EXPECT_TRUE(d.check_valid());
  std::vector<TetId> created;
  d.insert({0.5, 0.5, 1}, kNoId, &created);
  EXPECT_EQ(d.dimension(), 3);
  expect_valid_delaunay(d);
  // A pyramid of height 1 over the base polygon (0,0) (2,0) (1,1) (0,1) of area 1.5.
  EXPECT_NEAR(our_volume(d), 0.5, 1e-12);
  EXPECT_EQ(d.num_vertices(), 6u);
  EXPECT_FALSE(created.empty());
  const TetMesh m = d.to_mesh();
  for (const auto& t : m.tets)
    EXPECT_GT(predicates::orient3d(m.points[t[0]], m.points[t[1]], m.points[t[2]], m.points[t[3]]), 0);

  Delaunay3 one;
  one.insert_all(std::vector<Point3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
  EXPECT_EQ(one.num_finite_tets(), 1u);
  expect_valid_delaunay(one);

  Delaunay3 flat;
  const auto pts = random_cube(300, 5);
  std::vector<Point3> plane;
  for (const auto& p : pts) plane.push_back({p.x, p.y, 2.0});
  flat.insert_all(plane);
  EXPECT_EQ(flat.dimension(), 2);
  EXPECT_EQ(flat.num_finite_tets(), 0u);
  flat.insert({0.5, 0.5, 3.0});  // the first point off the plane: a cone over the plane's points
  expect_valid_delaunay(flat);
  EXPECT_EQ(flat.num_vertices(), 301u);
}

TEST(Delaunay3, CoplanarThenCgalEqualOnFivePoints) {
  const std::vector<Point3> five{{0, 0, 0}, {1, 0.1, 0}, {0.2, 1, 0.05}, {0.1, 0.3, 1}, {0.9, 0.8, 0.7}};
  Delaunay3 d;
  const auto b = d.insert_all(five);
  expect_valid_delaunay(d);
  const Dt dt = cgal_of(five);
  EXPECT_TRUE(our_tets(d, input_of(b, 5)) == cgal_tets(dt));
}

TEST(Delaunay3, DeterministicAndEqualToOneByOneInsertion) {
  const auto pts = random_cube(5000, 8);
  Delaunay3 a, b;
  a.insert_all(pts);
  b.insert_all(pts);
  EXPECT_EQ(a.to_mesh().tets, b.to_mesh().tets);
  // One point at a time in the same order, each with the tetrahedra it made checked.
  Delaunay3 c;
  std::vector<TetId> created;
  for (const Index i : brio_order(pts)) {
    created.clear();
    const bool spanned = c.dimension() == 3;  // the insertion that spans 3D reports every tetrahedron
    const Insertion r = c.insert(pts[i], kNoId, &created);
    if (!spanned) continue;
    // The new tetrahedra are the live ones around the new vertex.
    for (const TetId t : created) {
      ASSERT_TRUE(c.alive(t));
      const auto& v = c.vertices(t);
      ASSERT_TRUE(std::find(v.begin(), v.end(), r.vertex) != v.end());
    }
    if (r.vertex % 97 == 0) {  // and all of them (a scan of every slot, so only now and then)
      std::size_t around = 0;
      for (TetId t = 0; t < c.tet_slots(); ++t) {
        const auto& v = c.vertices(t);
        around += c.alive(t) && std::find(v.begin(), v.end(), r.vertex) != v.end();
      }
      ASSERT_EQ(around, created.size());
    }
  }
  EXPECT_EQ(a.to_mesh().tets, c.to_mesh().tets);
  EXPECT_EQ(a.to_mesh().points, c.to_mesh().points);
}

TEST(Delaunay3, LocateFindsTheContainingTetrahedron) {
  const auto pts = random_cube(3000, 12);
  Delaunay3 d;
  d.insert_all(pts);
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(-0.2, 1.2);
  for (int k = 0; k < 2000; ++k) {
    const Point3 p{u(rng), u(rng), u(rng)};
    const TetId t = d.locate(p, static_cast<TetId>(k % d.tet_slots()));
    ASSERT_NE(t, kNoId);
    const auto& v = d.vertices(t);
    if (d.is_ghost(t)) {
      EXPECT_GT(predicates::orient3d(d.point(v[0]), d.point(v[1]), d.point(v[2]), p), 0);
      continue;
    }
    for (int i = 0; i < 4; ++i) {
      Point3 r[4] = {d.point(v[0]), d.point(v[1]), d.point(v[2]), d.point(v[3])};
      r[i] = p;
      EXPECT_GE(predicates::orient3d(r[0], r[1], r[2], r[3]), 0);
    }
  }
}

TEST(Delaunay3, NearDegenerateSetsAreValid) {
  // Points on a sphere rounded to doubles (nearly cospherical), and a lattice moved by single
  // ulps (nearly coplanar and cospherical everywhere): the filter's uncertain cases.
  std::mt19937_64 rng(31);
  std::normal_distribution<double> g(0, 1);
  std::vector<Point3> sphere;
  for (int i = 0; i < 3000; ++i) {
    Point3 v{g(rng), g(rng), g(rng)};
    sphere.push_back(Point3{5, 5, 5} + (1 / std::sqrt(norm2(v))) * v);
  }
  expect_like_cgal_degenerate(sphere);
  std::uniform_int_distribution<int> pick(0, 5);
  std::vector<Point3> lattice;
  for (int x = 0; x < 8; ++x)
    for (int y = 0; y < 8; ++y)
      for (int z = 0; z < 8; ++z) {
        Point3 p{1 + x * 0.1, 1 + y * 0.1, 1 + z * 0.1};
        const int k = pick(rng);
        double* c = k % 3 == 0 ? &p.x : (k % 3 == 1 ? &p.y : &p.z);
        *c = std::nextafter(*c, k < 3 ? 10.0 : -10.0);
        lattice.push_back(p);
      }
  predicates::reset_counters();
  expect_like_cgal_degenerate(lattice);
  EXPECT_GT(predicates::counters().exact, 0u);
}

TEST(Delaunay3, NonFinitePointsAreRefusedBeforeAnyChange) {
  auto pts = random_cube(100, 41);
  pts[50].y = std::nan("");
  Delaunay3 d;
  EXPECT_THROW(d.insert_all(pts), Error);
  EXPECT_EQ(d.num_vertices(), 0u);
  pts[50].y = 0.5;
  d.insert_all(pts);
  const std::size_t before = d.num_finite_tets();
  try {
    d.insert({0.5, HUGE_VAL, 0.5});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidGeometry);
    EXPECT_NE(std::string(e.what()).find("non-finite"), std::string::npos);
  }
  EXPECT_EQ(d.num_finite_tets(), before);
  expect_valid_delaunay(d);
}

TEST(Delaunay3, DigThenInsertEqualsInsertAndAbandonChangesNothing) {
  const auto pts = random_cube(3000, 9);
  Delaunay3 a, b;
  a.insert_all(pts);
  b.insert_all(pts);
  const auto probes = random_cube(120, 10);
  std::vector<TetId> ca, cb;
  for (std::size_t k = 0; k < probes.size(); ++k) {
    const Point3 p = probes[k];
    const TetId h = b.locate(p);
    ASSERT_FALSE(b.dig(p, h).duplicate);
    // The cavity is every tetrahedron whose circumsphere strictly holds p (p lies inside the cube).
    std::set<TetId> dug(b.cavity().begin(), b.cavity().end());
    std::size_t conflicting = 0;
    b.for_each_finite_tet([&](TetId t) {
      const auto& v = b.vertices(t);
      const bool in = predicates::insphere(b.point(v[0]), b.point(v[1]), b.point(v[2]), b.point(v[3]), p) > 0;
      conflicting += in;
      if (in) {
        EXPECT_TRUE(dug.count(t)) << "probe " << k << " tet " << t;
      }
    });
    EXPECT_GE(dug.size(), conflicting);
    if (k % 2 == 0) {  // abandoned: nothing changed, and the next dig or insert works as usual
      b.abandon();
      ASSERT_EQ(a.to_mesh().tets, b.to_mesh().tets);
      continue;
    }
    ca.clear();
    cb.clear();
    const Insertion ra = a.insert(p, kNoId, &ca);
    const Insertion rb = b.insert_dug(&cb);
    EXPECT_EQ(ra.vertex, rb.vertex);
    EXPECT_EQ(ca, cb);
  }
  std::string why;
  EXPECT_TRUE(b.check_valid(&why)) << why;
  EXPECT_TRUE(b.is_delaunay(&why)) << why;
  EXPECT_EQ(a.to_mesh().tets, b.to_mesh().tets);
  // A point that repeats a vertex is reported, nothing dug; insert() refuses while a cavity waits.
  const Point3 q = b.point(7);
  EXPECT_EQ(b.dig(q, b.locate(q)).vertex, 7u);
  const Point3 r = probes[0];
  ASSERT_FALSE(b.dig(r, b.locate(r)).duplicate);
  EXPECT_THROW(b.insert(r), Error);
  b.abandon();
  EXPECT_FALSE(b.insert(r).duplicate);
}
