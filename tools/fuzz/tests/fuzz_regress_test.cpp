// Replays testdata/regress/fuzz_pslg_mesh_* through the fuzz_pslg_mesh oracle: each file is a
// named regression case of a crash or checker failure found by fuzzing (tools/fuzz/run.sh).
#include <gtest/gtest.h>
#include <filesystem>
#include <fstream>
#include <iterator>
#include "pslg_mesh_oracle.hpp"

namespace {

std::vector<std::uint8_t> slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void replay(const std::string& name) {
  const auto p = std::filesystem::path(FDR_TESTDATA_DIR) / "regress" / name;
  ASSERT_TRUE(std::filesystem::exists(p)) << p;
  const auto bytes = slurp(p);
  EXPECT_EQ(fdr_fuzz::pslg_mesh_case(bytes.data(), bytes.size()), "") << name;
}

// Binary lattice PSLG whose refinement met a triangle with R/f(c) = inf: the bad-triangle queue
// converted inf to int (UBSan), fixed in refine's bucket_of.
TEST(FuzzRegress, PslgMesh1InfinitePriority) { replay("fuzz_pslg_mesh_1.bin"); }

// Binary lattice PSLGs at offsets 1e7, -3.5e5, 12345.678 found by the first hour of fuzzing:
// "could not split subsegment" (internal error, exit 1) where resolved crossing points left
// features of a few ulps. Fixed by the resolver's snap rounding (pslg::resolve) and by refine
// stopping with exit 7 when a rounded split point falls behind a neighbouring constraint.
TEST(FuzzRegress, PslgMesh2to20UlpFeatures) {
  for (int k = 2; k <= 20; ++k) replay("fuzz_pslg_mesh_" + std::to_string(k) + ".bin");
}

// FDR refinement left a non-locally-Delaunay edge after a subsegment split: the rounded split
// point lay a hair off the edge, outside the circumcircle of the triangle across it, which the
// cavity destroys anyway. Fixed by Lawson flips after such insertions (cdt::Inserter).
TEST(FuzzRegress, PslgMesh21to34SplitOffEdgeDelaunay) {
  for (int k = 21; k <= 34; ++k) replay("fuzz_pslg_mesh_" + std::to_string(k) + ".bin");
}

// Every regression file replays clean (covers files added without a named case yet).
TEST(FuzzRegress, AllPslgMeshFiles) {
  for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(FDR_TESTDATA_DIR) / "regress"))
    if (e.path().filename().string().rfind("fuzz_pslg_mesh_", 0) == 0) replay(e.path().filename().string());
}

}  // namespace
