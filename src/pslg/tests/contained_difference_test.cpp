// contained_difference: a - b for polygon sets whose boundaries run together, checked against
// point classification (exact point-in-ring) on a lattice, ring validity and areas.
#include "pslg/contained_difference.hpp"
#include "pslg/contained_difference_steps.hpp"
#include <gtest/gtest.h>
#include <numbers>
#include <algorithm>
#include <cmath>
#include <random>
#include "predicates/predicates.hpp"
#include "pslg/segment_grid.hpp"

namespace fdr::pslg {
namespace {

using Ring = std::vector<Point2>;

// +1 inside, -1 outside, 0 on the boundary (exact).
int where(Point2 h, const Ring& r) {
  int wn = 0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Point2 p = r[i], q = r[(i + 1) % r.size()];
    if (p == h || in_interior(p, q, h)) return 0;
    if (p.y <= h.y) {
      if (q.y > h.y && predicates::orient2d(p, q, h) > 0) ++wn;
    } else if (q.y <= h.y && predicates::orient2d(p, q, h) < 0) {
      --wn;
    }
  }
  return wn != 0 ? 1 : -1;
}

// Inside a polygon set (shells minus holes); 0 when on any ring.
int where(Point2 h, const PolygonSet& s) {
  int in = -1;
  for (const auto& poly : s) {
    const int o = where(h, poly[0]);
    if (o == 0) return 0;
    if (o < 0) continue;
    bool hole = false;
    for (std::size_t k = 1; k < poly.size(); ++k) {
      const int w = where(h, poly[k]);
      if (w == 0) return 0;
      hole = hole || w > 0;
    }
    if (!hole) in = 1;
  }
  return in;
}

double dist_to_rings(Point2 h, const PolygonSet& s) {
  double d = INFINITY;
  for (const auto& poly : s)
    for (const auto& r : poly)
      for (std::size_t i = 0; i < r.size(); ++i) d = std::min(d, dist_to_segment(h, r[i], r[(i + 1) % r.size()]));
  return d;
}

double signed_area(const Ring& r) {
  double a = 0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Point2 p = r[i], q = r[(i + 1) % r.size()];
    a += p.x * q.y - q.x * p.y;
  }
  return 0.5 * a;
}

// Every ring simple, no two rings crossing or overlapping (they may share vertices); shells
// clockwise, holes counter-clockwise.
void expect_valid(const PolygonSet& s) {
  std::vector<std::pair<Point2, Point2>> segs;
  for (const auto& poly : s)
    for (std::size_t k = 0; k < poly.size(); ++k) {
      ASSERT_GE(poly[k].size(), 3u);
      EXPECT_EQ(signed_area(poly[k]) < 0, k == 0) << "ring " << k << " orientation";
      for (std::size_t i = 0; i < poly[k].size(); ++i) segs.push_back({poly[k][i], poly[k][(i + 1) % poly[k].size()]});
    }
  for (std::size_t i = 0; i < segs.size(); ++i)
    for (std::size_t j = i + 1; j < segs.size(); ++j) {
      const Contact c = classify(segs[i].first, segs[i].second, segs[j].first, segs[j].second);
      ASSERT_TRUE(c == Contact::kNone || c == Contact::kEndpoint) << "segments " << i << " and " << j;
    }
}

// On a lattice, away from every boundary: inside the result exactly where inside a and not b.
void expect_difference(const PolygonSet& a, const PolygonSet& b, const PolygonSet& r, double lo, double hi,
                       double margin, int n = 120) {
  int tested = 0;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const Point2 p{lo + (hi - lo) * (i + 0.37) / n, lo + (hi - lo) * (j + 0.61) / n};
      if (dist_to_rings(p, a) < margin || dist_to_rings(p, b) < margin) continue;
      const bool want = where(p, a) > 0 && where(p, b) < 0;
      ASSERT_EQ(where(p, r) > 0, want) << "at " << p.x << " " << p.y;
      ++tested;
    }
  EXPECT_GT(tested, n * n / 4);
}

PolygonSet square(double x0, double y0, double x1, double y1) {
  return {{{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}}};
}

TEST(ContainedDifference, InnerSquareTouchingOneSide) {
  const PolygonSet a = square(0, 0, 10, 10), b = square(0, 2, 5, 8);
  ContainedDifferenceStats st;
  const auto r = contained_difference(a, b, 1e-9, &st);
  ASSERT_TRUE(r) << st.refused;
  expect_valid(*r);
  ASSERT_EQ(r->size(), 1u);
  EXPECT_EQ((*r)[0].size(), 1u);  // a notch, not a hole
  EXPECT_NEAR(-signed_area((*r)[0][0]), 70.0, 1e-9);
  expect_difference(a, b, *r, -1, 11, 1e-6);
}

TEST(ContainedDifference, StrictlyInsideBecomesAHole) {
  const PolygonSet a = square(0, 0, 10, 10), b = square(3, 3, 6, 7);
  const auto r = contained_difference(a, b, 1e-9);
  ASSERT_TRUE(r);
  expect_valid(*r);
  ASSERT_EQ(r->size(), 1u);
  ASSERT_EQ((*r)[0].size(), 2u);
  EXPECT_NEAR(signed_area((*r)[0][1]), 12.0, 1e-9);
  expect_difference(a, b, *r, -1, 11, 1e-6);
}

TEST(ContainedDifference, EqualSetsLeaveNothing) {
  const PolygonSet a = square(0, 0, 10, 10);
  const auto r = contained_difference(a, a, 1e-9);
  ASSERT_TRUE(r);
  EXPECT_TRUE(r->empty());
}

TEST(ContainedDifference, BInsideAHoleOfALeavesAUnchanged) {
  PolygonSet a = square(0, 0, 10, 10);
  a[0].push_back({{2, 2}, {2, 8}, {8, 8}, {8, 2}});
  const PolygonSet b = square(3, 3, 6, 6);
  const auto r = contained_difference(a, b, 1e-9);
  ASSERT_TRUE(r);
  expect_valid(*r);
  ASSERT_EQ(r->size(), 1u);
  EXPECT_EQ((*r)[0].size(), 2u);
  expect_difference(a, b, *r, -1, 11, 1e-6);
}

// The closing's case: b runs along a's sides within rounding (its vertices a few ulps off a's
// segments, at other places than a's vertices), leaves a in arcs, and cuts a reflex corner of
// a with a chord that sticks out of a (by a hair and by a finite triangle): the result is the
// pieces between, and nothing where b sticks out.
TEST(ContainedDifference, NearCoincidentBoundariesAndChordsAcrossReflexCorners) {
  // a: a comb-like polygon with reflex corners at (4,4) and (6,4).
  const PolygonSet a = {{{{0, 0}, {10, 0}, {10, 10}, {6, 10}, {6, 4}, {4, 4}, {4, 10}, {0, 10}}}};
  auto off = [](Point2 p, Point2 q, double t, double e) {  // a point near segment pq, e off it
    const Point2 d = q - p;
    const double l = std::sqrt(norm2(d));
    return Point2{p.x + t * d.x - e * d.y / l, p.y + t * d.y + e * d.x / l};
  };
  // b: follows a's bottom and outer sides a few ulps inside (points on the segments, rounded),
  // cuts the reflex corner (4,4) with a chord by a hair outside a, and (6,4) with a chord
  // crossing a's sides a finite way (0.01) outside, rounds the convex corners (10,10), (0,10).
  Ring bb;
  bb.push_back(off({0, 0}, {10, 0}, 0.3, 0));
  bb.push_back(off({0, 0}, {10, 0}, 0.7, 1e-15));
  bb.push_back({10, 0.2});
  bb.push_back(off({10, 0}, {10, 10}, 0.5, 3e-16));
  bb.push_back({10, 9});
  bb.push_back({9.5, 9.9});
  bb.push_back({6.6, 9.9});
  bb.push_back(off({6, 10}, {6, 4}, 0.3, 0));  // on a's side x = 6
  bb.push_back({6.0 - 0.01, 4.3});             // outside a (x < 6, y > 4): crossing
  bb.push_back({5.6, 4.0 - 0.01});             // back inside: crossing y = 4
  bb.push_back({4.3, 4.0 + 1e-14});            // a hair outside a (y > 4 between x 4..6 is outside)
  bb.push_back({4.0 - 1e-14, 4.4});            // a hair outside (x < 4 ... inside); chord cuts corner
  bb.push_back(off({4, 4}, {4, 10}, 0.8, 1e-15));
  bb.push_back({3.5, 9.9});
  bb.push_back({0.4, 9.8});
  bb.push_back(off({0, 10}, {0, 0}, 0.4, -2e-16));
  const PolygonSet b = {{bb}};
  ContainedDifferenceStats st;
  const auto r = contained_difference(a, b, 1e-12, &st);
  ASSERT_TRUE(r) << st.refused;
  expect_valid(*r);
  EXPECT_GT(st.inserted, 0u);
  EXPECT_GT(st.cut, 0u);
  expect_difference(a, b, *r, -1, 11, 1e-6, 200);
}

// Star-shaped a and b on the same angles: b's radius equal to a's (shared vertices), a few
// ulps off it, inside it or outside it (b sticking out, crossing a's boundary), at random.
TEST(ContainedDifference, RandomStarsAgainstPointClassification) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> u(0, 1);
  for (int iter = 0; iter < 60; ++iter) {
    const int n = 8 + static_cast<int>(u(rng) * 40);
    Ring ra, rb;
    for (int i = 0; i < n; ++i) {
      const double th = 2 * std::numbers::pi * (i + 0.8 * u(rng)) / n;
      const double r = 4 + 4 * u(rng);
      const Point2 dir{std::cos(th), std::sin(th)};
      ra.push_back(r * dir);
      const double k = u(rng);
      double s = 1;
      if (k < 0.3) s = 1;
      else if (k < 0.45) s = 1 + (u(rng) - 0.5) * 1e-14;
      else if (k < 0.85) s = 0.5 + 0.5 * u(rng);
      else s = 1 + 0.15 * u(rng);
      rb.push_back(s == 1 ? ra.back() : (r * s) * dir);
    }
    const PolygonSet a = {{ra}}, b = {{rb}};
    ContainedDifferenceStats st;
    const auto r = contained_difference(a, b, 1e-12, &st);
    if (!r) {
      // Refusing is allowed (the caller overlays), but should be rare here.
      ADD_FAILURE() << "refused: " << st.refused << " (iteration " << iter << ")";
      continue;
    }
    SCOPED_TRACE(iter);
    expect_valid(*r);
    expect_difference(a, b, *r, -9, 9, 1e-6, 80);
  }
}

TEST(ContainedDifference, RefusesBBesideA) {
  // b shares a's right side from outside: not a difference this can trace.
  const PolygonSet a = square(0, 0, 10, 10), b = square(10, 0, 12, 10);
  ContainedDifferenceStats st;
  EXPECT_FALSE(contained_difference(a, b, 1e-9, &st));
  EXPECT_NE(st.refused, nullptr);
}

TEST(ContainedDifference, SameResultForEitherRingStart) {
  const PolygonSet a = square(0, 0, 10, 10), b = square(0, 2, 5, 8);
  PolygonSet b2 = b;
  std::rotate(b2[0][0].begin(), b2[0][0].begin() + 2, b2[0][0].end());
  const auto r1 = contained_difference(a, b, 1e-9), r2 = contained_difference(a, b2, 1e-9);
  ASSERT_TRUE(r1 && r2);
  EXPECT_NEAR(signed_area((*r1)[0][0]), signed_area((*r2)[0][0]), 1e-12);
}

// The steps on their own.

TEST(ContainedDifferenceSteps, CancelSharedDropsOppositeSegmentsOnly) {
  using cd_steps::Ring;
  // a's square counter-clockwise, b's square sharing a's bottom side, clockwise (b's interior
  // on the left of a - b's boundary): the shared side cancels, the other six remain.
  std::vector<Ring> rings{{{{0, 0}, {10, 0}, {10, 10}, {0, 10}}, true, 1},
                          {{{0, 0}, {0, 4}, {10, 4}, {10, 0}}, false, -1}};
  std::vector<cd_steps::Edge> rest;
  std::size_t cancelled = 9;
  ASSERT_EQ(cd_steps::cancel_shared(rings, rest, cancelled), nullptr);
  EXPECT_EQ(cancelled, 1u);
  ASSERT_EQ(rest.size(), 6u);
  for (const auto& e : rest) EXPECT_FALSE(std::min(e.u.y, e.v.y) == 0 && std::max(e.u.y, e.v.y) == 0);
  // The same direction in both sets: b beside a.
  std::reverse(rings[1].p.begin(), rings[1].p.end());
  EXPECT_NE(cd_steps::cancel_shared(rings, rest, cancelled), nullptr);
  // A segment twice in one set.
  rings[1].from_a = true;
  std::reverse(rings[1].p.begin(), rings[1].p.end());
  EXPECT_NE(cd_steps::cancel_shared(rings, rest, cancelled), nullptr);
}

TEST(ContainedDifferenceSteps, SplitClosedWalkAtARepeatedVertex) {
  // A figure eight through (0, 0): two triangles.
  const std::vector<Point2> p{{0, 0}, {1, 1}, {1, -1}, {0, 0}, {-1, -1}, {-1, 1}};
  std::vector<cd_steps::Edge> rest;
  std::vector<std::uint32_t> walk;
  for (std::uint32_t i = 0; i < p.size(); ++i) {
    rest.push_back({p[i], p[(i + 1) % p.size()], 0, i});
    walk.push_back(i);
  }
  const auto parts = cd_steps::split_closed_walk(walk, rest);
  ASSERT_EQ(parts.size(), 2u);
  EXPECT_EQ(parts[0], (std::vector<std::uint32_t>{0, 1, 2}));
  EXPECT_EQ(parts[1], (std::vector<std::uint32_t>{3, 4, 5}));
  // Distinct vertices: the walk stays whole.
  const std::vector<std::uint32_t> tri{0, 1, 2};
  ASSERT_EQ(cd_steps::split_closed_walk(tri, rest).size(), 1u);
}

TEST(ContainedDifferenceSteps, ClockwiseOrderAroundAVertex) {
  const Point2 v{0, 0}, r{1, 0};
  // Turning clockwise from +x: -y first, then -x, then +y; the ray's own direction last.
  EXPECT_TRUE(cd_steps::cw_before(v, r, {0, -1}, {-1, 0}));
  EXPECT_TRUE(cd_steps::cw_before(v, r, {-1, 0}, {0, 1}));
  EXPECT_FALSE(cd_steps::cw_before(v, r, {0, 1}, {0, -1}));
  EXPECT_TRUE(cd_steps::cw_before(v, r, {0, 1}, {2, 0}));
}

TEST(ContainedDifferenceSteps, LocateIsExactOnTheBoundary) {
  const std::vector<Point2> sq{{0, 0}, {4, 0}, {4, 4}, {0, 4}};
  EXPECT_EQ(cd_steps::locate({1, 1}, sq), 1);
  EXPECT_EQ(cd_steps::locate({5, 1}, sq), -1);
  EXPECT_EQ(cd_steps::locate({4, 2}, sq), 0);
  EXPECT_EQ(cd_steps::locate({2, 0}, sq), 0);
  EXPECT_EQ(cd_steps::locate({0, 4}, sq), 0);
}

}  // namespace
}  // namespace fdr::pslg
