// Sliver removal: its measurements (smallest dihedral cosine, the candidates, the angles an
// insertion would make), its queue, and whole runs on a PLC with a known sliver: after the step no
// tetrahedron is under the threshold and the refiner's invariants hold.
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include "plc/check.hpp"
#include "predicates/predicates3d.hpp"
#include "sizing/spacing3d.hpp"
#include "tet/dt_queries.hpp"
#include "tet/refiner3.hpp"
#include "tet/slivers.hpp"
#include "tet/tet_geometry.hpp"
#include "tet/tet_output.hpp"
#include "tet/tetrahedralize.hpp"

using namespace fdr;
using namespace fdr::tet;

namespace {

constexpr double kPi = 3.14159265358979323846;

// The unit cube's six facets and four interior points that form a sliver: the corners of a
// square of side 2 h centred in the plane z = 0.5, two of them raised and two lowered by `lift`.
plc::Plc cube_with_sliver(double h, double lift) {
  plc::Plc plc;
  for (int k = 0; k < 8; ++k) plc.points.push_back({(k & 1) ? 1.0 : 0.0, (k & 2) ? 1.0 : 0.0, (k & 4) ? 1.0 : 0.0});
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (int q = 0; q < 6; ++q) {
    plc::Facet f;
    f.polygons.push_back({static_cast<VertexId>(quads[q][0]), static_cast<VertexId>(quads[q][1]),
                          static_cast<VertexId>(quads[q][2]), static_cast<VertexId>(quads[q][3])});
    f.marker = q + 1;
    plc.facets.push_back(f);
  }
  plc.points.push_back({0.5 - h, 0.5 - h, 0.5 + lift});
  plc.points.push_back({0.5 + h, 0.5 + h, 0.5 + lift});
  plc.points.push_back({0.5 + h, 0.5 - h, 0.5 - lift});
  plc.points.push_back({0.5 - h, 0.5 + h, 0.5 - lift});
  return plc;
}

// The smallest dihedral angle over the refiner's domain, in degrees.
double domain_min_dihedral(const Refiner3& r) {
  double lo = 180;
  r.dt().for_each_finite_tet([&](TetId t) {
    if (r.region(t) == kOutsideRegion) return;
    const auto& v = r.dt().vertices(t);
    lo = std::min(lo, min_dihedral_deg(r.dt().point(v[0]), r.dt().point(v[1]), r.dt().point(v[2]), r.dt().point(v[3])));
  });
  return lo;
}

// Every tetrahedron of the domain with R/f(c) <= B and radius-edge <= 2, the tetrahedralization
// valid and Delaunay, and the boundary recovered.
void expect_invariants(const Refiner3& r) {
  std::string why;
  EXPECT_TRUE(r.dt().check_valid(&why)) << why;
  EXPECT_TRUE(r.dt().is_delaunay(&why)) << why;
  EXPECT_TRUE(r.conforming());
  EXPECT_FALSE(r.stats().capped);
  r.dt().for_each_finite_tet([&](TetId t) {
    if (r.region(t) == kOutsideRegion) return;
    const auto& v = r.dt().vertices(t);
    const Point3 a = r.dt().point(v[0]), b = r.dt().point(v[1]), c = r.dt().point(v[2]), d = r.dt().point(v[3]);
    const Sphere s = circumsphere(a, b, c, d);
    EXPECT_LE(s.radius / r.spacing()(s.centre), r.bound() * (1 + 1e-12)) << t;
    EXPECT_LE(s.radius / shortest_edge(a, b, c, d), 2 * (1 + 1e-12)) << t;
  });
}

}  // namespace

TEST(Slivers, SmallestDihedralCosineMatchesTheAngle) {
  const double s = 1 / std::sqrt(2.0);
  EXPECT_NEAR(smallest_dihedral_cos({1, 0, -s}, {-1, 0, -s}, {0, 1, s}, {0, -1, s}), 1.0 / 3, 1e-12);
  EXPECT_EQ(smallest_dihedral_cos({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}), 1.0);  // flat
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 200; ++i) {
    const Point3 a{u(rng), u(rng), u(rng)}, b{u(rng), u(rng), u(rng)}, c{u(rng), u(rng), u(rng)}, d{u(rng), u(rng), u(rng)};
    const double want = min_dihedral_deg(a, b, c, d);
    EXPECT_NEAR(std::acos(smallest_dihedral_cos(a, b, c, d)) * 180 / kPi, want, 1e-6) << i;
    EXPECT_NEAR(smallest_dihedral_cos(a, b, c, d), smallest_dihedral_cos(b, a, c, d), 1e-12);  // orientation-free
  }
}

TEST(Slivers, BallCentreIsInsideTheCircumsphereEvenWhenFlat) {
  // Four points near the unit circle (one off it by `off`), two lifted by a tiny amount: the
  // sphere through them is ill conditioned, yet the ball's centre must lie strictly inside it.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 2 * kPi);
  for (int i = 0; i < 300; ++i) {
    const double lift = std::pow(10.0, -3 - (i % 12)), off = std::pow(10.0, -4 - (i / 12) % 12);
    std::array<double, 4> ang{u(rng), u(rng), u(rng), u(rng)};
    std::sort(ang.begin(), ang.end());
    Point3 p[4];
    for (int k = 0; k < 4; ++k) {
      const double r = k == 3 ? 1 + off : 1;
      p[k] = {r * std::cos(ang[k]), r * std::sin(ang[k]), (k & 1) ? lift : -lift};
    }
    if (predicates::orient3d(p[0], p[1], p[2], p[3]) == 0) continue;
    if (predicates::orient3d(p[0], p[1], p[2], p[3]) < 0) std::swap(p[0], p[1]);
    const Sphere s = sliver_ball(p[0], p[1], p[2], p[3]);
    EXPECT_GT(predicates::insphere(p[0], p[1], p[2], p[3], s.centre), 0) << i;
    EXPECT_GT(s.radius, 0) << i;
  }
  // A flat tetrahedron that rule 3 left in a box at spacing 0.15 (four nearly cocircular points on
  // two facets): the double formula's circumcentre lies outside its exact circumsphere, so
  // circumsphere() constructs this one exactly, and the centre lies inside.
  Point3 p[4] = {{0x1.6p-1, 0x1.8p+1, 0x1.004fec04fec05p-3},
                 {0x1.6p-1, 0x1.6ffb013fb014p+1, 0x0p+0},
                 {0x1.1c1472ce58b03p-1, 0x1.8p+1, 0x1.ef1000f4a4a6cp-4},
                 {0x1.1c1472ce58b03p-1, 0x1.70877ff85adadp+1, 0x0p+0}};
  if (predicates::orient3d(p[0], p[1], p[2], p[3]) < 0) std::swap(p[0], p[1]);
  ASSERT_GT(predicates::orient3d(p[0], p[1], p[2], p[3]), 0);
  EXPECT_GT(predicates::insphere(p[0], p[1], p[2], p[3], circumsphere(p[0], p[1], p[2], p[3]).centre), 0);
  EXPECT_GT(predicates::insphere(p[0], p[1], p[2], p[3], sliver_ball(p[0], p[1], p[2], p[3]).centre), 0);
}

TEST(Slivers, CandidatesFillTheBallDeterministically) {
  const Point3 c{1, 2, 3};
  const auto p = sliver_candidates(c, 2.0, 0.4, 24);
  ASSERT_EQ(p.size(), 24u);
  EXPECT_EQ(p[0], c);
  EXPECT_EQ(p, sliver_candidates(c, 2.0, 0.4, 24));
  double far = 0;
  int upper = 0;
  for (std::size_t i = 1; i < p.size(); ++i) {
    EXPECT_LE(dist(p[i], c), 0.8 * (1 + 1e-12)) << i;
    EXPECT_GT(dist(p[i], c), 0) << i;
    far = std::max(far, dist(p[i], c));
    upper += p[i].z > c.z;
    for (std::size_t j = 1; j < i; ++j) EXPECT_GT(dist(p[i], p[j]), 0.05) << i << " " << j;
  }
  EXPECT_GT(far, 0.6);  // they reach out into the ball, not only near its centre
  EXPECT_GE(upper, 10);  // and spread over both halves
  EXPECT_LE(upper, 13);
}

TEST(Slivers, InsertionAnglesPredictTheNewTetrahedra) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Point3> pts;
  for (int i = 0; i < 60; ++i) pts.push_back({u(rng), u(rng), u(rng)});
  for (int trial = 0; trial < 20; ++trial) {
    Delaunay3 dt;
    dt.insert_all(pts);
    const Point3 p{0.2 + 0.6 * u(rng), 0.2 + 0.6 * u(rng), 0.2 + 0.6 * u(rng)};
    const TetId h = dt.locate(p);
    ASSERT_FALSE(dt.is_ghost(h));
    std::vector<TetId> cavity;
    conflict_region(dt, p, h, cavity);
    std::vector<TetId> scratch;
    const InsertionAngles ang = insertion_angles(dt, p, cavity, scratch);
    double destroyed = -1;
    for (TetId t : cavity) {
      const auto& v = dt.vertices(t);
      destroyed = std::max(destroyed, smallest_dihedral_cos(dt.point(v[0]), dt.point(v[1]), dt.point(v[2]), dt.point(v[3])));
    }
    std::vector<TetId> created;
    dt.insert(p, h, &created);
    double made = -1;
    for (TetId t : created) {
      if (dt.is_ghost(t)) continue;
      const auto& v = dt.vertices(t);
      made = std::max(made, smallest_dihedral_cos(dt.point(v[0]), dt.point(v[1]), dt.point(v[2]), dt.point(v[3])));
    }
    EXPECT_DOUBLE_EQ(ang.destroyed_cos, destroyed) << trial;
    EXPECT_DOUBLE_EQ(ang.created_cos, made) << trial;
  }
}

TEST(Slivers, InsertionAnglesStopOnlyOnceTheCandidateIsUseless) {
  // With a threshold and a rival, the created tetrahedra are measured until the candidate is
  // neither good nor better than both: a candidate that could be chosen gets its exact figure.
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Point3> pts;
  for (int i = 0; i < 60; ++i) pts.push_back({u(rng), u(rng), u(rng)});
  Delaunay3 dt;
  dt.insert_all(pts);
  std::vector<TetId> cavity, scratch;
  int stopped = 0, exact = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const Point3 p{0.2 + 0.6 * u(rng), 0.2 + 0.6 * u(rng), 0.2 + 0.6 * u(rng)};
    const TetId h = dt.locate(p);
    ASSERT_FALSE(dt.is_ghost(h));
    conflict_region(dt, p, h, cavity);
    const InsertionAngles all = insertion_angles(dt, p, cavity, scratch);
    for (const double good : {-1.0, 0.5, 0.9})
      for (const double rival : {-1.0, 0.95, 2.0}) {
        const InsertionAngles r = insertion_angles(dt, p, cavity, scratch, good, rival);
        EXPECT_EQ(r.destroyed_cos, all.destroyed_cos);
        const bool useless = all.created_cos > good && all.created_cos >= std::min(all.destroyed_cos, rival);
        if (!useless) {
          EXPECT_EQ(r.created_cos, all.created_cos) << trial;
          ++exact;
        } else {
          EXPECT_LE(r.created_cos, all.created_cos) << trial;
          EXPECT_TRUE(r.created_cos > good && r.created_cos >= std::min(r.destroyed_cos, rival)) << trial;
          stopped += r.created_cos < all.created_cos;
        }
      }
  }
  EXPECT_GT(exact, 0);
  EXPECT_GT(stopped, 0);  // some measurements did stop early
}

TEST(Slivers, CappedConflictRegionIsTheConflictRegionOrGivesUp) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Point3> pts;
  for (int i = 0; i < 200; ++i) pts.push_back({u(rng), u(rng), u(rng)});
  Delaunay3 dt;
  dt.insert_all(pts);
  for (int trial = 0; trial < 30; ++trial) {
    const Point3 p{u(rng), u(rng), 1.5 * u(rng) - 0.25};  // some beyond the hull
    const TetId h = dt.locate(p);
    TetId start = h;
    if (dt.is_ghost(h)) continue;
    std::vector<TetId> want, got;
    conflict_region(dt, p, start, want);
    ASSERT_TRUE(conflict_region(dt, p, start, got, want.size())) << trial;
    std::sort(want.begin(), want.end());
    std::sort(got.begin(), got.end());
    EXPECT_EQ(got, want) << trial;
    if (want.size() > 1) EXPECT_FALSE(conflict_region(dt, p, start, got, want.size() - 1));
  }
}

TEST(Slivers, QueueGivesTheWorstFirstAndDropsStaleEntries) {
  Delaunay3 dt;
  dt.insert_all(std::vector<Point3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}});
  std::vector<TetId> finite;
  dt.for_each_finite_tet([&](TetId t) { finite.push_back(t); });
  ASSERT_GE(finite.size(), 2u);
  SliverQueue q;
  q.push({0.5, finite[0], dt.vertices(finite[0])});
  q.push({0.9, finite[1], dt.vertices(finite[1])});
  std::array<VertexId, 4> gone = dt.vertices(finite[0]);
  gone[0] = 99;  // no longer the slot's vertices: dropped
  q.push({0.99, finite[0], gone});
  SliverTet s;
  ASSERT_TRUE(q.pop(dt, &s));
  EXPECT_EQ(s.cos, 0.9);
  ASSERT_TRUE(q.pop(dt, &s));
  EXPECT_EQ(s.cos, 0.5);
  EXPECT_FALSE(q.pop(dt, &s));
}

TEST(Slivers, KnownSliverIsRemovedAndInvariantsHold) {
  const plc::Plc plc = cube_with_sliver(0.3, 0.01);
  const plc::FacetTriangulation ft = plc::check_and_triangulate(plc);
  const sizing::ConstantField3 f(10);
  TetOptions off;
  off.remove_slivers = false;
  Refiner3 before(plc, ft, f, off);
  before.conform();
  before.refine();
  EXPECT_LT(domain_min_dihedral(before), 5.0);  // the sliver survives rule 3 (its radius-edge is ~0.7)
  EXPECT_EQ(before.stats().sliver_splits, 0u);
  EXPECT_EQ(before.stats().sliver_angle_deg, 0.0);
  expect_invariants(before);

  Refiner3 r(plc, ft, f, {});
  r.conform();
  r.refine();
  const TetStats& s = r.stats();
  EXPECT_EQ(s.sliver_angle_deg, TetOptions{}.sliver_angle_deg);
  EXPECT_GE(s.slivers_before, 1u);
  EXPECT_LT(s.min_dihedral_before_deg, 5.0);
  EXPECT_GT(s.sliver_splits, 0u);
  EXPECT_EQ(s.slivers_left, 0u);
  EXPECT_TRUE(s.slivers_listed.empty());
  ASSERT_EQ(s.dihedral_hist_before.size(), 18u);
  EXPECT_GE(s.dihedral_hist_before[0], 1u);
  EXPECT_GE(domain_min_dihedral(r), TetOptions{}.sliver_angle_deg);
  expect_invariants(r);
}

TEST(Slivers, ThresholdIsAnOptionAndRunsRepeat) {
  plc::Plc plc = cube_with_sliver(0.3, 0.02);
  const sizing::ConstantField3 f(0.3);
  TetOptions o;
  o.sliver_angle_deg = 20;
  const TetResult a = tetrahedralize(plc, f, o);
  const TetResult b = tetrahedralize(plc, f, o);
  EXPECT_EQ(a.mesh.tets, b.mesh.tets);
  EXPECT_EQ(a.mesh.points, b.mesh.points);
  EXPECT_EQ(a.stats.sliver_angle_deg, 20.0);
  double lo = 180;
  for (const auto& t : a.mesh.tets)
    lo = std::min(lo, min_dihedral_deg(a.mesh.points[t[0]], a.mesh.points[t[1]], a.mesh.points[t[2]], a.mesh.points[t[3]]));
  // What is left under the threshold is counted and listed.
  if (lo < 20) {
    EXPECT_GT(a.stats.slivers_left, 0u);
    EXPECT_FALSE(a.stats.slivers_listed.empty());
  } else {
    EXPECT_EQ(a.stats.slivers_left, 0u);
  }
  TetOptions none = o;
  none.remove_slivers = false;
  const TetResult c = tetrahedralize(plc, f, none);
  EXPECT_EQ(c.stats.sliver_splits, 0u);
  EXPECT_TRUE(c.stats.dihedral_hist_before.empty());
}
