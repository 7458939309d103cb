// The Hilbert key and the BRIO order.
#include <gtest/gtest.h>
#include <algorithm>
#include <cstdlib>
#include <random>
#include <vector>
#include "tet/spatial_sort.hpp"

using namespace fdr;
using namespace fdr::tet;

TEST(SpatialSort, HilbertKeysWalkThroughFaceNeighbours) {
  for (int bits : {1, 2, 3, 4}) {
    const std::uint32_t n = 1u << bits;
    std::vector<std::array<std::uint32_t, 3>> at(std::size_t(n) * n * n, {~0u, ~0u, ~0u});
    for (std::uint32_t x = 0; x < n; ++x)
      for (std::uint32_t y = 0; y < n; ++y)
        for (std::uint32_t z = 0; z < n; ++z) {
          const auto k = hilbert_key(x, y, z, bits);
          ASSERT_LT(k, at.size());
          ASSERT_EQ(at[k][0], ~0u) << "key taken twice";
          at[k] = {x, y, z};
        }
    for (std::size_t k = 1; k < at.size(); ++k) {
      int d = 0;
      for (int c = 0; c < 3; ++c) d += std::abs(int(at[k][c]) - int(at[k - 1][c]));
      ASSERT_EQ(d, 1) << "bits " << bits << " key " << k;
    }
  }
}

TEST(SpatialSort, BrioRoundsAreGeometric) {
  const int rounds = 6;
  std::vector<int> count(rounds);
  for (std::uint64_t i = 0; i < 64000; ++i) ++count[brio_round(i, rounds)];
  EXPECT_NEAR(count[5], 32000, 1000);
  EXPECT_NEAR(count[4], 16000, 800);
  EXPECT_NEAR(count[3], 8000, 600);
  EXPECT_EQ(brio_rounds(10), 1);
  EXPECT_EQ(brio_rounds(1000000), 10);
}

TEST(SpatialSort, BrioOrderIsADeterministicPermutationAlongTheCurve) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Point3> pts(20000);
  for (auto& p : pts) p = {u(rng), u(rng), u(rng)};
  pts[7] = pts[3];  // duplicates are ordered too
  const auto order = brio_order(pts);
  EXPECT_EQ(order, brio_order(pts));
  auto sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t i = 0; i < sorted.size(); ++i) ASSERT_EQ(sorted[i], i);
  // Within the last round, consecutive points are close: the mean step is far below the mean
  // distance of two random points in the unit cube (about 0.66).
  const int rounds = brio_rounds(pts.size());
  double sum = 0;
  int steps = 0;
  for (std::size_t k = 1; k < order.size(); ++k) {
    if (brio_round(order[k], rounds) != rounds - 1 || brio_round(order[k - 1], rounds) != rounds - 1) continue;
    sum += dist(pts[order[k]], pts[order[k - 1]]);
    ++steps;
  }
  ASSERT_GT(steps, 9000);
  EXPECT_LT(sum / steps, 0.05);
}

TEST(SpatialSort, EmptyAndFlatInputs) {
  EXPECT_TRUE(brio_order({}).empty());
  std::vector<Point3> same(5, Point3{1, 2, 3});
  EXPECT_EQ(brio_order(same).size(), 5u);
}
