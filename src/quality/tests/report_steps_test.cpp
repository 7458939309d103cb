// Steps of the quality report on their own: percentiles from the top of a stream (TopK,
// quantile_from_top), the nearest neighbours from a k-d tree bounded by the mesh edges
// (nearest_from) and the conformity figures (conformity_figures), each against a brute force.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "quality/top_k.hpp"
#include "quality/vertex_metrics.hpp"

namespace fdr::quality {
namespace {

double nearest_rank(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  const std::size_t rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size())));
  return v[rank == 0 ? 0 : rank - 1];
}

TEST(ReportSteps, QuantileFromTheTopOfSplitStreamsIsTheSortedOne) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  for (std::size_t n : {1u, 7u, 100u, 5000u}) {
    std::vector<double> all(n);
    for (double& x : all) x = std::floor(u(rng) * 50) / 50;  // many ties
    const std::size_t keep = n / 50 + 4;
    // Three parts of the stream, each with its own TopK, joined as the report's workers are.
    TopK parts[3] = {TopK(keep), TopK(keep), TopK(keep)};
    for (std::size_t i = 0; i < n; ++i) parts[i % 3].add(all[i]);
    parts[0].absorb(parts[1]);
    parts[0].absorb(parts[2]);
    const std::optional<double> q = quantile_from_top(parts[0].values(), keep, n, 0.99);
    ASSERT_TRUE(q) << n;
    EXPECT_EQ(*q, nearest_rank(all, 0.99)) << n;
  }
}

TEST(ReportSteps, QuantileBelowWhatWasKeptIsUnknown) {
  TopK top(2);
  for (int i = 0; i < 100; ++i) top.add(i);
  EXPECT_FALSE(quantile_from_top(top.values(), 2, 100, 0.5));
  EXPECT_EQ(quantile_from_top(top.values(), 2, 100, 0.99), 98.0);
}

TEST(ReportSteps, NearestFromTheTreeAndFromTheWalkAgree) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 10);
  std::vector<Point2> pts(300);
  for (Point2& p : pts) p = {u(rng), u(rng)};
  pts[7] = pts[3];  // a duplicate: distance 0
  std::vector<double> brute(pts.size(), kInf);
  for (std::size_t i = 0; i < pts.size(); ++i)
    for (std::size_t j = 0; j < pts.size(); ++j)
      if (i != j) brute[i] = std::min(brute[i], dist(pts[i], pts[j]));
  // An upper bound per vertex (as the mesh edges give): the tree search must go below it.
  std::vector<double> bound(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) bound[i] = norm2(pts[i] - pts[(i + 1) % pts.size()]);
  EXPECT_EQ(nearest_from({}, std::move(bound), pts), brute);
  std::vector<double> walk_sq(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) walk_sq[i] = brute[i] * brute[i];
  const std::vector<double> from_walk = nearest_from(std::move(walk_sq), {}, pts);
  for (std::size_t i = 0; i < pts.size(); ++i) EXPECT_DOUBLE_EQ(from_walk[i], brute[i]);
}

TEST(ReportSteps, ConformityFiguresAgainstBruteForce) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(0.1, 2);
  const std::size_t n = 1000;
  std::vector<Point2> pts(n);
  std::vector<double> nn(n), fv(n);
  for (std::size_t i = 0; i < n; ++i) {
    pts[i] = {static_cast<double>(i), 0};
    nn[i] = u(rng);
    fv[i] = i % 97 == 0 ? -1.0 : u(rng);  // some unusable values
  }
  QualityReport r;
  conformity_figures(r, nn, fv.data(), nullptr, pts);
  std::vector<double> conf;
  double nn_over_f_min = kInf;
  for (std::size_t i = 0; i < n; ++i) {
    if (!(fv[i] > 0)) continue;
    conf.push_back(std::min(nn[i] / fv[i], fv[i] / nn[i]));
    nn_over_f_min = std::min(nn_over_f_min, nn[i] / fv[i]);
  }
  EXPECT_EQ(r.spacing_invalid, n - conf.size());
  ASSERT_TRUE(r.conformity_min && r.conformity_p05 && r.conformity_mean && r.nn_over_f_min);
  EXPECT_EQ(*r.conformity_min, *std::min_element(conf.begin(), conf.end()));
  EXPECT_EQ(*r.conformity_p05, nearest_rank(conf, 0.05));
  EXPECT_EQ(*r.nn_over_f_min, nn_over_f_min);
  double mean = 0;
  for (double c : conf) mean += c;
  EXPECT_NEAR(*r.conformity_mean, mean / static_cast<double>(conf.size()), 1e-12);
  std::uint64_t counted = 0;
  for (auto c : r.conformity_histogram.counts) counted += c;
  EXPECT_EQ(counted, conf.size());
}

}  // namespace
}  // namespace fdr::quality
