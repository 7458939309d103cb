// Tetrahedron geometry, the B-bad test and the queue of bad tetrahedra.
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include "tet/delaunay3.hpp"
#include "tet/dt_queries.hpp"
#include "tet/refine3d.hpp"
#include "tet/tet_geometry.hpp"

using namespace fdr;
using namespace fdr::tet;

TEST(TetGeometry, CircumsphereOfTheCornerTetrahedron) {
  const Sphere s = circumsphere({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1});
  EXPECT_NEAR(s.centre.x, 0.5, 1e-15);
  EXPECT_NEAR(s.centre.y, 0.5, 1e-15);
  EXPECT_NEAR(s.centre.z, 0.5, 1e-15);
  EXPECT_NEAR(s.radius, std::sqrt(3.0) / 2, 1e-15);
}

TEST(TetGeometry, CentreIsEquidistantFarFromTheOrigin) {
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 1000; ++i) {
    const Point3 o{1e6, -2e6, 3e5};
    const Point3 p[4] = {o + Point3{u(rng), u(rng), u(rng)}, o + Point3{u(rng), u(rng), u(rng)},
                         o + Point3{u(rng), u(rng), u(rng)}, o + Point3{u(rng), u(rng), u(rng)}};
    const Sphere s = circumsphere(p[0], p[1], p[2], p[3]);
    if (s.radius > 100) continue;  // nearly flat: the centre is far and ill-conditioned
    for (const Point3& q : p) EXPECT_NEAR(dist(q, s.centre), s.radius, 1e-7 * (1 + s.radius));
  }
}

TEST(TetGeometry, RadiusEdgeOfTheRegularTetrahedron) {
  const Point3 a{1, 1, 1}, b{1, -1, -1}, c{-1, 1, -1}, d{-1, -1, 1};
  EXPECT_NEAR(radius_edge_ratio(a, b, c, d), std::sqrt(6.0) / 4, 1e-15);
  EXPECT_NEAR(shortest_edge(a, b, c, d), std::sqrt(8.0), 1e-15);
}

TEST(Refine3d, RangesFollowTheRatioOnALogScale) {
  int last = BadTetQueue::bucket(1e-30);
  for (double r = 1e-30; r < 1e30; r *= 1.001) {
    const int k = BadTetQueue::bucket(r);
    EXPECT_GE(k, last) << r;
    last = k;
  }
  // One range spans at most a factor 1 + 1/kBucketsPerOctave.
  const double width = 1.0 + 1.0 / BadTetQueue::kBucketsPerOctave;
  for (double r = 0.01; r < 100; r *= 1.003) EXPECT_LT(BadTetQueue::bucket(r), BadTetQueue::bucket(r * width * 1.0001)) << r;
  EXPECT_EQ(BadTetQueue::bucket(std::nan("")), BadTetQueue::bucket(std::numeric_limits<double>::infinity()));
  EXPECT_GT(BadTetQueue::bucket(std::nan("")), BadTetQueue::bucket(1e300));
  EXPECT_EQ(BadTetQueue::bucket(0.0), 0);
}

TEST(Refine3d, BadTetrahedraComeOutLargestRatioFirst) {
  std::mt19937_64 rng(22);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Point3> pts(400);
  for (auto& p : pts) p = {u(rng), u(rng), u(rng)};
  Delaunay3 dt;
  dt.insert_all(pts);
  const Spacing3 f = [](Point3 p) { return 0.05 + 0.1 * p.x; };
  const double bound = 1.0;
  BadTetQueue q(bound);
  std::size_t bad = 0;
  dt.for_each_finite_tet([&](TetId t) {
    const bool b = is_bad(size_ratio(dt, t, f), bound);
    EXPECT_EQ(q.offer(dt, t, f), b);
    bad += b;
  });
  ASSERT_GT(bad, 10u);
  EXPECT_EQ(q.size(), bad);
  // Splitting the worst one destroys it (and others): those leave the queue unseen.
  BadTet worst;
  ASSERT_TRUE(q.pop(dt, &worst));
  EXPECT_GT(worst.ratio, bound);
  const Insertion ins = dt.insert(worst.centre, worst.tet);
  ASSERT_FALSE(ins.duplicate);
  double last = worst.ratio;
  std::size_t popped = 1;
  BadTet b;
  while (q.pop(dt, &b)) {
    // Largest first; the centre is the tetrahedron's circumcentre again.
    EXPECT_LE(b.ratio, last);
    EXPECT_EQ(b.centre, size_ratio(dt, b.tet, f).centre);
    EXPECT_EQ(b.ratio, size_ratio(dt, b.tet, f).ratio);
    EXPECT_TRUE(dt.alive(b.tet) && !dt.is_ghost(b.tet));
    last = b.ratio;
    ++popped;
  }
  EXPECT_LT(popped, bad);
}

TEST(Refine3d, TiesAreOrderedByVertices) {
  Delaunay3 dt;
  // A cube's corners and its centre: congruent tetrahedra with equal ratios, which must come out
  // in one fixed order.
  std::vector<Point3> pts;
  for (int x = 0; x < 2; ++x)
    for (int y = 0; y < 2; ++y)
      for (int z = 0; z < 2; ++z) pts.push_back({double(x), double(y), double(z)});
  pts.push_back({0.5, 0.5, 0.5});
  dt.insert_all(pts);
  const Spacing3 f = [](Point3) { return 0.01; };
  std::vector<std::array<VertexId, 4>> first, second;
  for (auto* out : {&first, &second}) {
    BadTetQueue q(1.0);
    dt.for_each_finite_tet([&](TetId t) { q.offer(dt, t, f); });
    BadTet b;
    while (q.pop(dt, &b)) out->push_back(b.v);
  }
  EXPECT_EQ(first.size(), dt.num_finite_tets());
  EXPECT_EQ(first, second);
}

// Entries pushed while their range is being emptied (into the sorted range, above it, below it)
// come out in the order one heap would give: largest ratio first, ties by their sorted vertices.
TEST(Refine3d, QueueOrderHoldsForEntriesPushedWhilePopping) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Point3> pts(300);
  for (auto& p : pts) p = {u(rng), u(rng), u(rng)};
  Delaunay3 dt;
  dt.insert_all(pts);
  std::vector<BadTet> all;
  dt.for_each_finite_tet([&](TetId t) {
    // Few distinct ratios, most of them inside one range of the queue, with ties.
    const double ratio = 1.5 + 0.0005 * static_cast<double>(rng() % 12) + (rng() % 9 == 0 ? 0.3 : 0.0) -
                         (rng() % 7 == 0 ? 0.2 : 0.0);
    all.push_back({ratio, t, dt.vertices(t), {}});
  });
  ASSERT_GT(all.size(), 1000u);
  auto key = [](const BadTet& b) {
    auto v = b.v;
    std::sort(v.begin(), v.end());
    return std::make_pair(-b.ratio, v);  // smallest key comes out first
  };
  BadTetQueue q(1.0);
  std::vector<BadTet> pending;  // the reference: what is queued
  std::vector<std::array<VertexId, 4>> got, want;
  auto pop_both = [&](std::size_t n) {
    for (std::size_t i = 0; i < n && !pending.empty(); ++i) {
      const auto it = std::min_element(pending.begin(), pending.end(),
                                       [&](const BadTet& a, const BadTet& b) { return key(a) < key(b); });
      want.push_back(it->v);
      pending.erase(it);
      BadTet b;
      ASSERT_TRUE(q.pop(dt, &b));
      got.push_back(b.v);
    }
  };
  const std::size_t half = all.size() / 2;
  for (std::size_t i = 0; i < half; ++i) q.push(all[i]), pending.push_back(all[i]);
  pop_both(50);
  for (std::size_t i = half; i < all.size(); ++i) {
    q.push(all[i]);
    pending.push_back(all[i]);
    if (i % 17 == 0) pop_both(3);
  }
  pop_both(all.size());
  BadTet b;
  EXPECT_FALSE(q.pop(dt, &b));
  EXPECT_EQ(q.size(), 0u);
  EXPECT_EQ(got, want);
}

namespace fdr::tet {
namespace {

// vertex_edge_ratios against each vertex's edges listed one by one, over all the tetrahedra and
// over half of them (the kept ones), on random points with f varying in space.
TEST(VertexEdgeRatios, MatchesEdgesListedByHand) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Point3> pts(6000);  // tetrahedron slots in several chunks
  for (auto& p : pts) p = {u(rng), u(rng), u(rng)};
  Delaunay3 dt;
  dt.insert_all(pts);
  const auto f = [](Point3 p) { return 0.05 + 0.1 * p.x + 0.02 * p.z; };
  for (int mod : {1, 2}) {
    const auto keep = [&](TetId t) { return t % mod == 0; };
    std::vector<double> lo(dt.num_vertices(), std::numeric_limits<double>::infinity()), hi(dt.num_vertices(), 0);
    dt.for_each_finite_tet([&](TetId t) {
      if (!keep(t)) return;
      const auto& v = dt.vertices(t);
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
          if (i != j) {
            const double l = dist(dt.point(v[i]), dt.point(v[j]));
            lo[v[i]] = std::min(lo[v[i]], l);
            hi[v[i]] = std::max(hi[v[i]], l);
          }
    });
    double nn = std::numeric_limits<double>::infinity(), el = 0;
    for (VertexId w = 0; w < dt.num_vertices(); ++w)
      if (hi[w] > 0) {
        nn = std::min(nn, lo[w] / f(dt.point(w)));
        el = std::max(el, hi[w] / f(dt.point(w)));
      }
    for (unsigned threads : {1u, 2u}) {
      const VertexEdgeRatios r = vertex_edge_ratios(dt, keep, f, threads);
      EXPECT_EQ(r.nn_over_f_min, nn) << mod << " " << threads;
      EXPECT_EQ(r.el_over_f_max, el) << mod << " " << threads;
    }
  }
  const VertexEdgeRatios none = vertex_edge_ratios(dt, [](TetId) { return false; }, f);
  EXPECT_EQ(none.nn_over_f_min, 0);
  EXPECT_EQ(none.el_over_f_max, 0);
}

}  // namespace
}  // namespace fdr::tet
