// clamp_surfaces: ordering a stack into non-crossing surfaces, and its errors.
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <limits>
#include "base/error.hpp"
#include "terrain/surfaces.hpp"
#include "terrain_fixture.hpp"

namespace fdr::terrain {
namespace {
using testing::lattice_tin;
using testing::plane;

ExitCode code_of(std::vector<Surface> stack, const Tin& tin) {
  try {
    clamp_surfaces(stack, tin, {});
  } catch (const Error& e) {
    return e.code();
  }
  return ExitCode::kOk;
}

TEST(ClampSurfaces, HorizonsInsideAreUnchanged) {
  const Tin tin = lattice_tin();
  std::vector<Surface> s{plane(tin, "top", 10, 1), plane(tin, "h1", 5), plane(tin, "base", 0)};
  const auto before = s;
  const ClampCounts c = clamp_surfaces(s, tin, {});
  EXPECT_EQ(s[1].z, before[1].z);
  EXPECT_EQ(c.lowered[1], 0u);
  EXPECT_EQ(c.raised[1], 0u);
}

TEST(ClampSurfaces, HorizonAboveTheTopFollowsIt) {
  const Tin tin = lattice_tin();
  // h1 rises above the top where x > 1 (top 10 + x, h1 = 6 + 4x): pinched out there.
  std::vector<Surface> s{plane(tin, "top", 10, 1), plane(tin, "h1", 6, 4), plane(tin, "base", 0)};
  const ClampCounts c = clamp_surfaces(s, tin, {});
  for (std::size_t v = 0; v < tin.xy.size(); ++v) {
    EXPECT_LE(s[1].z[v], s[0].z[v]);
    if (tin.xy[v].x >= 2) {
      EXPECT_EQ(s[1].z[v], s[0].z[v]);
    }
  }
  EXPECT_EQ(c.lowered[1], 3u);  // x = 2: h1 14 above the top 12
}

TEST(ClampSurfaces, LowerHorizonClampedToTheOneAbove) {
  const Tin tin = lattice_tin();
  std::vector<Surface> s{plane(tin, "top", 10), plane(tin, "h1", 5), plane(tin, "h2", 3, 2), plane(tin, "base", 0)};
  const ClampCounts c = clamp_surfaces(s, tin, {});
  for (std::size_t v = 0; v < tin.xy.size(); ++v) EXPECT_LE(s[2].z[v], s[1].z[v]);
  EXPECT_EQ(c.lowered[2], 6u);  // 3 + 2x >= 5 for x >= 1
}

TEST(ClampSurfaces, HorizonBelowTheBaseIsRaised) {
  const Tin tin = lattice_tin();
  std::vector<Surface> s{plane(tin, "top", 10), plane(tin, "h1", -1, 3), plane(tin, "base", 0)};
  const ClampCounts c = clamp_surfaces(s, tin, {});
  EXPECT_EQ(c.raised[1], 3u);  // x = 0
  for (std::size_t v = 0; v < tin.xy.size(); ++v) EXPECT_GE(s[1].z[v], 0.0);
}

TEST(ClampSurfaces, BaseAboveTheTopIsAnError) {
  const Tin tin = lattice_tin();
  EXPECT_EQ(code_of({plane(tin, "top", 10, 1), plane(tin, "base", 11)}, tin), ExitCode::kInvalidGeometry);
  EXPECT_EQ(code_of({plane(tin, "top", 10), plane(tin, "base", 10)}, tin), ExitCode::kInvalidGeometry);
  try {
    std::vector<Surface> s{plane(tin, "top", 10, 1), plane(tin, "base", 11)};
    clamp_surfaces(s, tin, {100, 200});
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("vertex 0 (100, 200)"), std::string::npos) << e.what();
  }
}

TEST(ClampSurfaces, HorizonOutsideEverywhereIsAnError) {
  const Tin tin = lattice_tin();
  EXPECT_EQ(code_of({plane(tin, "top", 10), plane(tin, "h1", 20), plane(tin, "base", 0)}, tin), ExitCode::kInvalidGeometry);
  EXPECT_EQ(code_of({plane(tin, "top", 10), plane(tin, "h1", -5), plane(tin, "base", 0)}, tin), ExitCode::kInvalidGeometry);
}

TEST(ClampSurfaces, MissingElevationIsAnError) {
  const Tin tin = lattice_tin();
  std::vector<Surface> s{plane(tin, "top", 10), plane(tin, "base", 0)};
  s[0].z[4] = std::nan("");
  EXPECT_EQ(code_of(s, tin), ExitCode::kInvalidGeometry);
  EXPECT_EQ(code_of({plane(tin, "top", 10)}, tin), ExitCode::kInvalidGeometry);
}

TEST(DefaultMinThickness, AFractionOfHminNoLessThanTheVerticalTolerance) {
  EXPECT_EQ(default_min_thickness(160, 0), kMinThicknessPerHmin * 160);
  EXPECT_EQ(default_min_thickness(160, 200), 200.0);  // the TIN resolves no finer vertically
  EXPECT_EQ(default_min_thickness(0, 0), 0.0);
  EXPECT_EQ(default_min_thickness(std::numeric_limits<double>::infinity(), 5), 5.0);  // no spacing known
  EXPECT_GT(kMinThicknessPerHmin, 0.0);
  EXPECT_LE(kMinThicknessPerHmin, 0.25);
}

// With the default, a layer thinner than a fraction of hmin collapses at those vertices and the
// thinnest positive thickness left is at least that fraction.
TEST(DefaultMinThickness, CollapsesLayersBelowTheResolution) {
  const Tin tin = lattice_tin();
  // The layer above h1 is 30 + 30x thick: 30 at x = 0 (below the fraction of hmin 240), 60 and 90 beyond.
  std::vector<Surface> s{plane(tin, "top", 100), plane(tin, "h1", 70, -30), plane(tin, "base", -100)};
  const double m = default_min_thickness(240, 0);
  const ClampCounts c = clamp_surfaces(s, tin, {}, m);
  EXPECT_EQ(c.collapsed[1], 3u);
  for (std::size_t v = 0; v < tin.xy.size(); ++v) {
    const double t = s[0].z[v] - s[1].z[v];
    EXPECT_TRUE(t == 0 || t >= m) << v << " " << t;
  }
}


// Every layer over every triangle is empty or positive at all three corners, and the layering
// runs from the top to the base without decreasing.
void expect_no_wedges(const Tin& tin, const std::vector<Surface>& s, const Layering& l) {
  const std::size_t n = s.size();
  for (std::size_t t = 0; t < tin.triangles.size(); ++t) {
    EXPECT_EQ(l.at(t, 0), 0u);
    EXPECT_EQ(l.at(t, n - 1), n - 1);
    for (std::size_t k = 0; k + 1 < n; ++k) {
      EXPECT_LE(l.at(t, k), l.at(t, k + 1));
      int positive = 0;
      for (int c = 0; c < 3; ++c) positive += corner_z(s, l, tin, t, k, c) > corner_z(s, l, tin, t, k + 1, c);
      EXPECT_TRUE(positive == 0 || positive == 3) << "triangle " << t << " layer " << k;
    }
  }
}

TEST(EndPinchOuts, NothingToDoWithoutPinchOuts) {
  const Tin tin = lattice_tin();
  const std::vector<Surface> s{plane(tin, "top", 10, 1), plane(tin, "h1", 5, 0, 1), plane(tin, "base", 0)};
  const PinchOutRepair r = end_pinch_outs(tin, s);
  EXPECT_TRUE(r.layering.identity());
  EXPECT_EQ(r.triangles, (std::vector<std::size_t>{0, 0}));
  EXPECT_EQ(r.largest_move, 0.0);
}

// h1 meets the top for x >= 2 (after clamping) on [0, 4] x [0, 2]: the column of triangles between
// x = 1 and x = 2 holds the wedge; the layer leaves it and ends over x = 1 at its thickness there.
TEST(EndPinchOuts, LayerLeavesTheTrianglesWhereItThinsToZero) {
  const Tin tin = lattice_tin(5, 3);
  std::vector<Surface> s{plane(tin, "top", 10), plane(tin, "h1", 9.5, 0.25), plane(tin, "base", 0)};
  clamp_surfaces(s, tin, {});
  const PinchOutRepair r = end_pinch_outs(tin, s);
  ASSERT_FALSE(r.layering.identity());
  EXPECT_EQ(r.triangles, (std::vector<std::size_t>{4, 0}));
  EXPECT_EQ(r.largest_move, 0.25);  // h1 at x = 1 moves onto the top over the wedge
  EXPECT_EQ(tin.xy[r.largest_at].x, 1.0);
  EXPECT_DOUBLE_EQ(r.volume[0], 2 * 0.5 * (0.25 + 0.5) / 3);  // per square: corners 0.25, 0, 0 and 0.25, 0, 0.25
  expect_no_wedges(tin, s, r.layering);
  for (std::size_t t = 0; t < tin.triangles.size(); ++t) {
    double xlo = 4, xhi = 0;
    for (VertexId v : tin.triangles[t]) xlo = std::min(xlo, tin.xy[v].x), xhi = std::max(xhi, tin.xy[v].x);
    EXPECT_EQ(r.layering.at(t, 1), xlo == 1 && xhi == 2 ? 0u : 1u) << t;  // on the top over the wedge only
  }
}

// A horizon that comes down onto the base: the layer above the base leaves the wedge's triangles
// by its upper surface going down (the base stays where it is).
TEST(EndPinchOuts, LayerAboveTheBaseLeavesByItsTop) {
  const Tin tin = lattice_tin(5, 3);
  std::vector<Surface> s{plane(tin, "top", 10), plane(tin, "h1", 0.5, -0.25), plane(tin, "base", 0)};
  clamp_surfaces(s, tin, {});
  const PinchOutRepair r = end_pinch_outs(tin, s);
  EXPECT_EQ(r.triangles, (std::vector<std::size_t>{0, 4}));
  expect_no_wedges(tin, s, r.layering);
  for (std::size_t t = 0; t < tin.triangles.size(); ++t) {
    double xlo = 4, xhi = 0;
    for (VertexId v : tin.triangles[t]) xlo = std::min(xlo, tin.xy[v].x), xhi = std::max(xhi, tin.xy[v].x);
    EXPECT_EQ(r.layering.at(t, 1), xlo == 1 && xhi == 2 ? 2u : 1u) << t;  // on the base over the wedge only
  }
}

// h2 meets h1 over the triangles where the layer above the base thins to zero (a layer of zero
// thickness between them there): both go down onto the base, or the layer above them would be
// left as a wedge.
TEST(EndPinchOuts, CoincidentHorizonsGoDownTogether) {
  const Tin tin = lattice_tin(5, 3);
  std::vector<Surface> s{plane(tin, "top", 10), plane(tin, "h1", 0.5, -0.25), plane(tin, "h2", 0), plane(tin, "base", 0)};
  for (std::size_t v = 0; v < tin.xy.size(); ++v) s[2].z[v] = tin.xy[v].x == 0 ? 0.3 : s[1].z[v];
  clamp_surfaces(s, tin, {});
  const PinchOutRepair r = end_pinch_outs(tin, s);
  expect_no_wedges(tin, s, r.layering);
  EXPECT_GT(r.triangles[2], 0u);
}

// Two horizons pinching out across each other and onto the base at places: every layer ends
// without a wedge whatever the order of the removals.
TEST(EndPinchOuts, CrossingPinchOutsOfTwoHorizons) {
  const Tin tin = lattice_tin(7, 5);
  std::vector<Surface> s{plane(tin, "top", 10, 0.1), plane(tin, "h1", 11, -1.5, 0.5), plane(tin, "h2", 3, 1, -1.5),
                         plane(tin, "base", 0)};
  clamp_surfaces(s, tin, {}, 0.5);
  const PinchOutRepair r = end_pinch_outs(tin, s);
  EXPECT_GT(r.triangles[0] + r.triangles[1] + r.triangles[2], 0u);
  expect_no_wedges(tin, s, r.layering);
}

}  // namespace
}  // namespace fdr::terrain
