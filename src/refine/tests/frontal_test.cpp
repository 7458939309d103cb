// Frontal refinement: the placement (on the front edge's bisector, inside the bad triangle's
// circumcircle), the front bookkeeping, and whole runs (R/f(c) <= B, a valid constrained Delaunay
// mesh, termination at the Steiner cap, the same mesh every time).
#include <gtest/gtest.h>
#include <cmath>
#include <limits>
#include <random>
#include "base/error.hpp"
#include "base/triangle_geometry.hpp"
#include "cdt/cdt.hpp"
#include "cdt/tests/test_inputs.hpp"
#include "mesh/check.hpp"
#include "predicates/predicates.hpp"
#include "refine/front.hpp"
#include "refine/frontal.hpp"
#include "refine/refine.hpp"
#include "refine/tests/fn_field.hpp"

using namespace fdr;
using fdr::testing::FnField;
using fdr::testing::max_r_over_f;

TEST(FrontalPoint, EquilateralWhenTheCircleAllows) {
  // A tall bad triangle over the edge (0,0)-(1,0): its circumcentre is far up the bisector.
  const Point2 p{0, 0}, q{1, 0}, apex{0.5, 20};
  double r2;
  const Point2 cc = geom::circumcentre(p, q, apex, &r2);
  const auto fp = refine::frontal_point(p, q, cc, std::sqrt(r2), 1 / std::sqrt(3.0));
  EXPECT_FALSE(fp.clamped);
  EXPECT_NEAR(fp.x.x, 0.5, 1e-15);
  EXPECT_NEAR(fp.x.y, std::sqrt(3.0) / 2, 1e-15);
  EXPECT_NEAR(dist(fp.x, p), 1, 1e-15);
  EXPECT_NEAR(fp.centre.y, 0.5 / std::sqrt(3.0), 1e-15);
  // A smaller radius than half the edge gives the right triangle (apex on the diametral circle).
  const auto rt = refine::frontal_point(p, q, cc, std::sqrt(r2), 0.1);
  EXPECT_NEAR(rt.x.y, 0.5, 1e-15);
}

TEST(FrontalPoint, ClampedToTheCircumcentre) {
  const Point2 p{0, 0}, q{1, 0}, apex{0.5, 0.9};
  double r2;
  const Point2 cc = geom::circumcentre(p, q, apex, &r2);
  const auto fp = refine::frontal_point(p, q, cc, std::sqrt(r2), 5.0);
  EXPECT_TRUE(fp.clamped);
  EXPECT_NEAR(fp.x.x, cc.x, 1e-15);
  EXPECT_NEAR(fp.x.y, cc.y, 1e-15);
}

TEST(FrontalPoint, AlwaysInsideTheBadCircumcircle) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1), s(0.01, 3);
  int tested = 0;
  for (int i = 0; i < 20000; ++i) {
    Point2 a{u(rng), u(rng)}, b{u(rng), u(rng)}, c{u(rng), u(rng)};
    const int o = predicates::orient2d(a, b, c);
    if (o == 0) continue;
    if (o < 0) std::swap(b, c);
    double r2;
    const Point2 cc = geom::circumcentre(a, b, c, &r2);
    const Point2 pts[3] = {a, b, c};
    for (int k = 0; k < 3; ++k) {  // each edge as the front edge; the triangle is on its left
      const auto fp = refine::frontal_point(pts[k], pts[(k + 1) % 3], cc, std::sqrt(r2), s(rng));
      EXPECT_GT(predicates::incircle(a, b, c, fp.x), 0) << i << " " << k;
      EXPECT_GT(predicates::orient2d(pts[k], pts[(k + 1) % 3], fp.x), 0) << i << " " << k;
      ++tested;
    }
  }
  EXPECT_GT(tested, 50000);
}

namespace {
// A unit square split by its diagonal (0,0)-(1,1): two triangles, the four sides constrained.
mesh::Triangulation two_triangles() {
  pslg::Pslg p;
  p.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (Index i = 0; i < 4; ++i) p.segments.push_back({i, (i + 1) % 4, 1, 0});
  return cdt::build_cdt(p, {cdt::CdtOptions::Regions::kSeeds, "test"});
}

HalfEdge interior_edge(const mesh::Triangulation& T, TriangleId t) {
  for (Index k = 0; k < 3; ++k)
    if (!T.constrained(3 * t + k)) return 3 * t + k;
  return kNoId;
}
}  // namespace

TEST(Front, EdgesOnConstraintsOrAcceptedTrianglesAreFront) {
  auto T = two_triangles();
  std::vector<TriangleId> live;
  for (TriangleId t = 0; t < T.num_slots(); ++t)
    if (!T.dead(t)) live.push_back(t);
  ASSERT_EQ(live.size(), 2u);
  refine::Front F;
  F.set_key(live[0], 3.0);
  F.set_key(live[1], 2.0);
  const HalfEdge h0 = interior_edge(T, live[0]);
  ASSERT_NE(h0, kNoId);
  EXPECT_FALSE(F.front_edge(T, h0));  // the neighbour is bad
  F.set_key(live[1], 0.0);            // accepted
  EXPECT_TRUE(F.front_edge(T, h0));
  EXPECT_TRUE(F.bad(live[0]));
  EXPECT_FALSE(F.bad(live[1]));
  for (Index k = 0; k < 3; ++k)
    if (3 * live[0] + k != h0) EXPECT_TRUE(F.front_edge(T, 3 * live[0] + k));  // constrained sides
}

TEST(Front, OffersOnlyBadTrianglesLargestFirst) {
  auto T = two_triangles();
  std::vector<TriangleId> live;
  for (TriangleId t = 0; t < T.num_slots(); ++t)
    if (!T.dead(t)) live.push_back(t);
  refine::Front F;
  F.set_key(live[0], 2.0);
  F.set_key(live[1], 5.0);
  F.offer(T, live[0]);
  F.offer(T, live[1]);
  F.offer(T, live[0]);  // twice: both entries kept
  EXPECT_EQ(F.size(), 3u);
  refine::Front::Entry e;
  ASSERT_TRUE(F.pop(&e));
  EXPECT_EQ(e.t, live[1]);
  EXPECT_EQ(e.c, T.corner(live[1], 2));
  ASSERT_TRUE(F.pop(&e));
  EXPECT_EQ(e.t, live[0]);
  ASSERT_TRUE(F.pop(&e));
  EXPECT_EQ(e.t, live[0]);
  EXPECT_FALSE(F.pop(&e));
  F.set_key(live[1], 0.0);
  F.offer(T, live[1]);  // accepted: not queued
  EXPECT_TRUE(F.empty());
}

TEST(Front, BucketsRiseWithTheKey) {
  int last = refine::Front::bucket_of(1.0);
  EXPECT_EQ(last, 0);
  for (double k = 1.01; k < 1e25; k *= 1.07) {
    const int b = refine::Front::bucket_of(k);
    EXPECT_GE(b, last) << k;
    last = b;
  }
  EXPECT_EQ(refine::Front::bucket_of(std::numeric_limits<double>::infinity()),
            refine::Front::kSub * refine::Front::kDoublings - 1);
  EXPECT_LT(refine::Front::bucket_of(1.5), refine::Front::bucket_of(1.7));  // finer than a doubling
}

TEST(Front, NoteNewQueuesOldBadNeighboursOfAcceptedTriangles) {
  auto T = two_triangles();
  std::vector<TriangleId> live;
  for (TriangleId t = 0; t < T.num_slots(); ++t)
    if (!T.dead(t)) live.push_back(t);
  refine::Front F;
  F.set_key(live[0], 2.0);
  F.set_key(live[1], 0.0);
  // live[1] plays a new accepted triangle (new vertex: a vertex live[0]'s third corner is not).
  Index v = kNoId;
  for (Index k = 0; k < 3; ++k)
    if (T.corner(live[1], static_cast<int>(k)) != T.corner(live[0], 2)) v = T.corner(live[1], static_cast<int>(k));
  std::vector<TriangleId> off;
  F.note_new(T, {live[1]}, v, &off);
  refine::Front::Entry e;
  ASSERT_TRUE(F.pop(&e));
  EXPECT_EQ(e.t, live[0]);
  EXPECT_TRUE(F.empty());
  EXPECT_TRUE(off.empty());
}

namespace {
mesh::Triangulation run(const pslg::Pslg& p, const sizing::SizingField& f, refine::RefineOptions o,
                        refine::RefineStats* st = nullptr) {
  auto T = cdt::build_cdt(p, {cdt::CdtOptions::Regions::kSeeds, "test"});
  refine::Refiner r(T, f, o);
  r.init();
  r.run();
  if (st) *st = r.stats();
  return T;
}
}  // namespace

TEST(FrontalRefine, PaperSquaresKeepTheBound) {
  const FnField f1([](Point2 p) { return (std::fabs(p.x - 5) + std::fabs(p.y - 5)) * 0.1 + 0.1; });
  const FnField c([](Point2) { return 0.25; });
  auto p = fdr::testing::random_pslg(0, 0, 0);
  for (const sizing::SizingField* f : {static_cast<const sizing::SizingField*>(&f1), static_cast<const sizing::SizingField*>(&c)})
    for (double B : {1.0, 0.7}) {
      refine::RefineOptions o;
      o.bound = B;
      o.frontal = true;
      refine::RefineStats st;
      auto T = run(p, *f, o, &st);
      const auto r = mesh::check_all(T);
      ASSERT_TRUE(r.ok()) << (r.problems.empty() ? "" : r.problems[0]);
      EXPECT_LE(max_r_over_f(T, *f), B * (1 + 1e-12));
      EXPECT_NEAR(T.area(), 100, 1e-9);
      EXPECT_GT(st.frontal_points, st.circumcenters / 2) << "most interior points frontal";
    }
}

TEST(FrontalRefine, RandomPslgsAndSmallAnglesHoldInvariants) {
  for (unsigned seed = 0; seed < 40; ++seed) {
    auto p = fdr::testing::random_pslg(seed, 5 + seed % 40, static_cast<int>(seed % 12));
    const double h = 0.3 + 0.1 * (seed % 7);
    FnField f([h](Point2 q) { return h * (1 + 0.05 * q.x); });
    refine::RefineOptions o;
    o.frontal = true;
    o.min_angle_deg = seed % 2 ? 30 : 0;
    auto T = run(p, f, o);
    const auto r = mesh::check_all(T);
    ASSERT_TRUE(r.ok()) << seed << ": " << (r.problems.empty() ? "" : r.problems[0]);
    EXPECT_LE(max_r_over_f(T, f), 1 + 1e-12) << seed;
  }
  for (double deg : {1.0, 5.0}) {
    FnField f([](Point2) { return 0.5; });
    refine::RefineOptions o;
    o.frontal = true;
    auto T = run(fdr::testing::wedge(deg), f, o);
    EXPECT_LE(max_r_over_f(T, f), 1 + 1e-12) << deg;
  }
}

// Triangles refinement gives up on (an exempt angle) make no front edges; the bad triangles behind
// them must still be reached: every run ends with R/f(c) <= B.
TEST(FrontalRefine, BadTrianglesBehindExemptOnesAreRefined) {
  std::uint64_t exempt = 0;
  for (unsigned seed = 0; seed < 30; ++seed) {
    auto p = fdr::testing::random_pslg(seed, 10 + seed % 30, static_cast<int>(4 + seed % 9));
    const double h = 0.25 + 0.1 * (seed % 5);
    FnField f([h](Point2 q) { return h * (1 + 0.04 * q.y); });
    refine::RefineOptions o;
    o.frontal = true;
    o.min_angle_deg = 30;
    o.angle_split_min_f = 0.5;  // the GIS setting: angle-only splits near the boundary give up
    refine::RefineStats st;
    auto T = run(p, f, o, &st);
    exempt += st.exempt_small_angle;
    const auto r = mesh::check_all(T);
    ASSERT_TRUE(r.ok()) << seed << ": " << (r.problems.empty() ? "" : r.problems[0]);
    EXPECT_LE(max_r_over_f(T, f), 1 + 1e-12) << seed;
  }
  EXPECT_GT(exempt, 0u) << "no run gave up on a triangle: the test does not reach the case";
}

TEST(Front, DroppedTrianglesStayBad) {
  auto T = two_triangles();
  std::vector<TriangleId> live;
  for (TriangleId t = 0; t < T.num_slots(); ++t)
    if (!T.dead(t)) live.push_back(t);
  refine::Front F;
  F.set_key(live[0], 3.0);
  F.set_key(live[1], 0.0);
  EXPECT_FALSE(F.dropped(live[0]));
  F.drop(live[0]);
  EXPECT_TRUE(F.dropped(live[0]));
  EXPECT_TRUE(F.bad(live[0]));
  EXPECT_FLOAT_EQ(F.key(live[0]), 3.0f);
  EXPECT_FALSE(F.front_edge(T, interior_edge(T, live[1])));  // a dropped neighbour makes no front
  EXPECT_TRUE(F.offer(T, live[0]));  // offered again (it borders an accepted triangle): retried
  F.set_key(live[0], 2.0);           // a new triangle in the slot
  EXPECT_FALSE(F.dropped(live[0]));
}

TEST(FrontalRefine, StopsAtTheSteinerCap) {
  FnField f([](Point2) { return 0.05; });
  refine::RefineOptions o;
  o.frontal = true;
  o.max_steiner = 500;
  try {
    run(fdr::testing::random_pslg(0, 0, 0), f, o);
    FAIL() << "no error at the cap";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kWorkLimit);
  }
}

TEST(FrontalRefine, SameMeshEveryTime) {
  FnField f([](Point2 q) { return 0.2 + 0.03 * q.y; });
  auto p = fdr::testing::random_pslg(3, 20, 5);
  refine::RefineOptions o;
  o.frontal = true;
  auto A = run(p, f, o), B = run(p, f, o);
  ASSERT_EQ(A.num_vertices(), B.num_vertices());
  for (Index v = 0; v < A.num_vertices(); ++v) EXPECT_EQ(A.point(v), B.point(v));
}

TEST(FrontalRefine, RejectsARadiusOutsideTheUnitInterval) {
  auto T = two_triangles();
  FnField f([](Point2) { return 0.1; });
  for (double k : {0.0, 1.0, -0.5}) {
    refine::RefineOptions o;
    o.frontal = true;
    o.frontal_radius = k;
    EXPECT_THROW(refine::Refiner(T, f, o), Error) << k;
  }
}
