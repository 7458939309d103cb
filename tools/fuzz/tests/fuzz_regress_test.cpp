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

// Every regression file replays clean (covers files added without a named case yet).
TEST(FuzzRegress, AllPslgMeshFiles) {
  for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(FDR_TESTDATA_DIR) / "regress"))
    if (e.path().filename().string().rfind("fuzz_pslg_mesh_", 0) == 0) replay(e.path().filename().string());
}

}  // namespace
