// The refinement's bucketed queue: highest bucket first, newest first within a bucket, Morton
// order in a bucket the queue descends to, and chunked storage that keeps every entry.
#include <gtest/gtest.h>
#include <algorithm>
#include <random>
#include <vector>
#include "refine/spatial_buckets.hpp"

using fdr::Point2;
using fdr::refine::MortonFrame;
using fdr::refine::SpatialBuckets;

TEST(SpatialBuckets, HighestBucketFirstNewestFirstWithin) {
  SpatialBuckets q(8);
  q.push(2, {1, 0, 5});
  q.push(5, {2, 0, 9});
  q.push(2, {3, 0, 1});
  EXPECT_EQ(q.size(), 3u);
  SpatialBuckets::Entry e;
  ASSERT_TRUE(q.pop(&e));
  EXPECT_EQ(e.t, 2u);
  // Descending to bucket 2 sorts it by Morton code, smallest first: t 3 (z 1) before t 1 (z 5).
  ASSERT_TRUE(q.pop(&e));
  EXPECT_EQ(e.t, 3u);
  q.push(2, {4, 0, 7});  // pushed after the sort: taken first (newest first)
  ASSERT_TRUE(q.pop(&e));
  EXPECT_EQ(e.t, 4u);
  ASSERT_TRUE(q.pop(&e));
  EXPECT_EQ(e.t, 1u);
  EXPECT_FALSE(q.pop(&e));
  EXPECT_TRUE(q.empty());
}

TEST(SpatialBuckets, NewestFirstWhileNotDescending) {
  SpatialBuckets q(4);
  for (fdr::TriangleId t = 0; t < 5; ++t) q.push(3, {t, 0, 100 - t});
  SpatialBuckets::Entry e;
  for (fdr::TriangleId t = 5; t-- > 0;) {
    ASSERT_TRUE(q.pop(&e));
    EXPECT_EQ(e.t, t);  // the top bucket was never descended to: push order reversed
  }
}

TEST(SpatialBuckets, KeepsEveryEntryAcrossChunksInMortonOrder) {
  std::mt19937 rng(3);
  SpatialBuckets q(3);
  constexpr fdr::TriangleId kN = 5000;  // several chunks
  for (fdr::TriangleId t = 0; t < kN; ++t) q.push(0, {t, t + 1, static_cast<std::uint32_t>(rng())});
  q.push(2, {kN, 0, 0});
  SpatialBuckets::Entry e;
  ASSERT_TRUE(q.pop(&e));
  EXPECT_EQ(e.t, kN);
  std::vector<bool> seen(kN, false);
  std::uint32_t last = 0;
  for (fdr::TriangleId i = 0; i < kN; ++i) {
    ASSERT_TRUE(q.pop(&e));
    ASSERT_LT(e.t, kN);
    EXPECT_FALSE(seen[e.t]);
    seen[e.t] = true;
    EXPECT_EQ(e.c, e.t + 1);
    EXPECT_GE(e.z, last) << i;  // bucket 0 was descended to: ascending Morton codes
    last = e.z;
    if (i + 6 < kN) {
      ASSERT_NE(q.ahead(6), nullptr);
    }
  }
  EXPECT_TRUE(q.empty());
  EXPECT_EQ(q.ahead(1), nullptr);
}

TEST(SpatialBuckets, SortIsDescendingAndDeterministic) {
  std::mt19937 rng(11);
  std::vector<SpatialBuckets::Entry> v;
  for (fdr::TriangleId t = 0; t < 3000; ++t) v.push_back({t, 0, static_cast<std::uint32_t>(rng() % 700)});
  auto w = v;
  fdr::refine::sort_desc_by_z(v);
  fdr::refine::sort_desc_by_z(w);
  for (std::size_t i = 1; i < v.size(); ++i) EXPECT_GE(v[i - 1].z, v[i].z);
  for (std::size_t i = 0; i < v.size(); ++i) EXPECT_EQ(v[i].t, w[i].t);
}

TEST(MortonFrame, CodesInterleaveTheFrameCoordinates) {
  const std::vector<Point2> pts{{10, 20}, {14, 22}};
  const MortonFrame fr = MortonFrame::of(pts);
  EXPECT_EQ(fr.code({10, 20}), 0u);
  EXPECT_EQ(fr.code({14, 24}), 0xffffffffu);             // the far corner of the square frame
  EXPECT_EQ(fr.code({14, 20}), 0x55555555u);             // x in the even bits
  EXPECT_EQ(fr.code({10, 24}), 0xaaaaaaaau);             // y in the odd bits
  EXPECT_EQ(fr.code({-100, -100}), 0u);                  // clamped to the frame
  EXPECT_LT(fr.code({11, 21}), fr.code({13, 23}));
}
