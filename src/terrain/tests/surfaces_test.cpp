// clamp_surfaces: ordering a stack into non-crossing surfaces, and its errors.
#include <gtest/gtest.h>
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

}  // namespace
}  // namespace fdr::terrain
