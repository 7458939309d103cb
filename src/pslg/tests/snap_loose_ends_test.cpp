// pslg::snap_loose_ends (issue 8: moved from the pipeline into pslg).
#include <gtest/gtest.h>
#include "pslg/snap_loose_ends.hpp"

namespace fdr::pslg {
namespace {

// A unit square boundary (marker 1) and a breakline from the centre ending `gap` short of the
// bottom edge.
Pslg square_with_breakline(double gap) {
  Pslg g;
  g.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.5, 0.5}, {0.5, gap}};
  for (Index i = 0; i < 4; ++i) g.segments.push_back({i, static_cast<Index>((i + 1) % 4), 1, 0});
  g.segments.push_back({4, 5, kBreaklineMarker, 1});
  return g;
}

TEST(SnapLooseEnds, EndWithinToleranceSplitsTheBoundarySegment) {
  Pslg g = square_with_breakline(1e-11);
  const auto reps = snap_loose_ends(g, 1e-9);
  ASSERT_EQ(reps.size(), 1u);
  EXPECT_EQ(reps[0].kind, "snap_to_segment");
  EXPECT_EQ(reps[0].part, 0);
  ASSERT_EQ(g.segments.size(), 6u);  // bottom edge split in two at the breakline end
  EXPECT_EQ(g.segments[0].a, 0u);
  EXPECT_EQ(g.segments[0].b, 5u);
  EXPECT_EQ(g.segments[5].a, 5u);
  EXPECT_EQ(g.segments[5].b, 1u);
  EXPECT_EQ(g.segments[5].marker, 1);
}

TEST(SnapLooseEnds, EndsFartherThanToleranceAndZeroToleranceAreLeftAlone) {
  Pslg g = square_with_breakline(1e-6);
  EXPECT_TRUE(snap_loose_ends(g, 1e-9).empty());
  EXPECT_EQ(g.segments.size(), 5u);
  Pslg h = square_with_breakline(1e-11);
  EXPECT_TRUE(snap_loose_ends(h, 0).empty());
  EXPECT_EQ(h.segments.size(), 5u);
}

}  // namespace
}  // namespace fdr::pslg
