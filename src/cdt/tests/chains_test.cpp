// Degenerate inputs (collinear chains, lattices, cocircular rings) give valid constrained Delaunay
// triangulations with every constraint, in work linear in the input: counts, not times.
#include <gtest/gtest.h>
#include <algorithm>
#include <numeric>
#include "cdt/cdt.hpp"
#include "cdt/steps.hpp"
#include "cdt/tests/chain_inputs.hpp"
#include "mesh/check.hpp"
#include "predicates/predicates.hpp"
#include "pslg/resolve.hpp"

using namespace fdr;

namespace {

struct Work {
  double per_point;    // walk steps plus new triangles per input point
  double per_segment;  // segment recovery steps per input segment
  bool random_rounds;
};

// Builds the CDT, checks it, and returns its work per point and per segment.
Work build_and_check(const pslg::Pslg& p, const char* what) {
  cdt::CdtStats st;
  const mesh::Triangulation T = cdt::build_cdt(p, {cdt::CdtOptions::Regions::kAuto, what}, &st);
  const mesh::CheckResult r = mesh::check_all(T);
  EXPECT_TRUE(r.ok()) << what << ": " << r.count << " problems, first: " << (r.problems.empty() ? "" : r.problems[0]);
  EXPECT_GE(T.num_live_triangles() + 2, p.points.size());
  return {static_cast<double>(st.walk_steps + st.new_triangles) / static_cast<double>(p.points.size()),
          static_cast<double>(st.recovery_steps) / static_cast<double>(std::max<std::size_t>(1, p.segments.size())),
          st.random_rounds};
}

// Random points of the same size take about 10 units of work per point and a segment a few steps;
// a quadratic insertion order takes hundreds per point at these sizes.
constexpr double kMaxWorkPerPoint = 40;
constexpr double kMaxStepsPerSegment = 16;

}  // namespace

TEST(CdtChains, RandomPointsReference) {
  const Work w = build_and_check(fdr::testing::random_points(8000), "random");
  EXPECT_LT(w.per_point, 16);
  EXPECT_FALSE(w.random_rounds);
}

TEST(CdtChains, CollinearSquareTakesLinearWork) {
  const Work w = build_and_check(fdr::testing::collinear_square(2000), "collinear square");
  EXPECT_LT(w.per_point, kMaxWorkPerPoint);
  EXPECT_LT(w.per_segment, kMaxStepsPerSegment);
  EXPECT_TRUE(w.random_rounds);  // the Hilbert order alone is quadratic here
}

TEST(CdtChains, LatticeTakesLinearWork) {
  const Work w = build_and_check(fdr::testing::lattice_square(90), "lattice");
  EXPECT_LT(w.per_point, kMaxWorkPerPoint);
  EXPECT_LT(w.per_segment, kMaxStepsPerSegment);
}

TEST(CdtChains, ConcentricCocircularRingsTakeLinearWork) {
  const pslg::Pslg p = fdr::testing::concentric_rings(40, 200);
  ASSERT_EQ(p.points.size(), 1u + 40u * 200u);
  // The rings are exactly cocircular: the first ring's points all at distance R from the centre.
  const Point2 a = p.points[1], b = p.points[50], c = p.points[120], d = p.points[190];
  EXPECT_EQ(predicates::incircle(a, b, c, d), 0);
  const Work w = build_and_check(p, "rings");
  EXPECT_LT(w.per_point, kMaxWorkPerPoint);
  EXPECT_LT(w.per_segment, kMaxStepsPerSegment);
}

TEST(CdtChains, CollinearBreaklinesTakeLinearWork) {
  const Work w = build_and_check(fdr::testing::breaklines(20, 400), "breaklines");
  EXPECT_LT(w.per_point, kMaxWorkPerPoint);
  EXPECT_LT(w.per_segment, kMaxStepsPerSegment);
}

TEST(CdtChains, InsertionOrderIsAPermutationInRoundsForLargeInputs) {
  const pslg::Pslg small = fdr::testing::random_points(100);
  const Box2 sb = small.bbox();
  // Under two first rounds of points: one round, the Hilbert order itself.
  EXPECT_EQ(cdt::insertion_order(small.points, sb, true), cdt::insertion_order(small.points, sb, false));
  const pslg::Pslg big = fdr::testing::random_points(5000);
  const Box2 bb = big.bbox();
  const std::vector<Index> rounds = cdt::insertion_order(big.points, bb, true);
  const std::vector<Index> hilbert = cdt::insertion_order(big.points, bb, false);
  EXPECT_NE(rounds, hilbert);
  std::vector<Index> sorted = rounds;
  std::sort(sorted.begin(), sorted.end());
  std::vector<Index> ids(big.points.size());
  std::iota(ids.begin(), ids.end(), Index{0});
  EXPECT_EQ(sorted, ids);
  EXPECT_EQ(rounds, cdt::insertion_order(big.points, bb, true));  // deterministic
  // The last round holds about half the points: the first half of the order is not the
  // Hilbert order's first half.
  std::vector<Index> first_half(rounds.begin(), rounds.begin() + 2500), hilbert_half(hilbert.begin(), hilbert.begin() + 2500);
  std::sort(first_half.begin(), first_half.end());
  std::sort(hilbert_half.begin(), hilbert_half.end());
  EXPECT_NE(first_half, hilbert_half);
}

TEST(CdtChains, ResolvingACollinearSquareTakesFewPredicatesPerSegment) {
  const pslg::Pslg p = fdr::testing::collinear_square(5000);
  predicates::reset_counters();
  const pslg::Pslg r = pslg::resolve(p, {}, nullptr);
  const auto calls = predicates::counters().filtered + predicates::counters().exact;
  EXPECT_EQ(r.points.size(), p.points.size());
  EXPECT_EQ(r.segments.size(), p.segments.size());
  EXPECT_LT(static_cast<double>(calls) / static_cast<double>(p.segments.size()), 8.0);
}
