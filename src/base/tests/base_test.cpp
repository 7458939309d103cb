// Tests for base: boxes, error codes, GDAL-style progress text.
#include <gtest/gtest.h>
#include <cstdio>
#include <string>
#include "base/error.hpp"
#include "base/progress.hpp"
#include "base/types.hpp"

using namespace fdr;

TEST(Base, BoxGrowsAndContains) {
  Box2 b;
  EXPECT_TRUE(b.empty());
  b.add({1, 2});
  b.add({-1, 5});
  EXPECT_FALSE(b.empty());
  EXPECT_DOUBLE_EQ(b.width(), 2);
  EXPECT_DOUBLE_EQ(b.height(), 3);
  EXPECT_TRUE(b.contains({0, 3}));
  EXPECT_FALSE(b.contains({0, 6}));
}

TEST(Base, ErrorCarriesExitCode) {
  Error e(ExitCode::kInvalidGeometry, "x");
  EXPECT_EQ(e.exit_code(), 5);
  EXPECT_STREQ(exit_code_name(ExitCode::kWorkLimit), "work limit exceeded");
}

TEST(Base, TermProgressPrintsGdalPattern) {
  char buf[256] = {};
  std::FILE* f = fmemopen(buf, sizeof buf, "w");
  TermProgress p(f);
  for (int i = 0; i <= 100; ++i) p(i / 100.0);
  p.finish();
  std::fclose(f);
  EXPECT_EQ(std::string(buf),
            "0...10...20...30...40...50...60...70...80...90...100 - done.\n");
}

// Under glibc's malloc (this test binary does not link jemalloc) the allocator controls do nothing.
#include "base/memory.hpp"
TEST(Memory, NoOpWithoutJemalloc) {
  fdr::EagerMemoryRelease eager;
  EXPECT_FALSE(eager.active());
  fdr::release_free_memory();
}
