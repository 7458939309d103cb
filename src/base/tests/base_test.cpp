// Tests for base: boxes, error codes, GDAL-style progress text.
#include <gtest/gtest.h>
#include <cstdio>
#include <string>
#include <cmath>
#include <limits>
#include <random>
#include <vector>
#include "base/error.hpp"
#include "base/kd_tree.hpp"
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
#include "base/tests/smaps_flags.hpp"
TEST(Memory, NoOpWithoutJemalloc) {
  fdr::EagerMemoryRelease eager;
  EXPECT_FALSE(eager.active());
  fdr::release_free_memory();
}

#include <sys/mman.h>
#include <cstdint>
#include <vector>


TEST(AdviseHugePages, AdvisesTheAlignedInsideOfARange) {
  const std::size_t len = std::size_t{8} << 20;
  void* p = mmap(nullptr, len, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  ASSERT_NE(p, MAP_FAILED);
  char* c = static_cast<char*>(p);
  EXPECT_FALSE(fdr::test::advised_huge(c + len / 2));
  fdr::advise_huge_pages(c, len);
  EXPECT_TRUE(fdr::test::advised_huge(c + len / 2));
  fdr::unadvise_huge_pages(c, len);
  EXPECT_FALSE(fdr::test::advised_huge(c + len / 2));
  std::vector<double> small(100);
  fdr::advise_huge_pages(small);  // under 2 MiB: nothing to advise, no error
  munmap(p, len);
}

// KdTree: the tree built on two threads is the same tree (same order of the points, so the same
// answers in the same order), and its queries match brute force.
TEST(KdTree, TwoThreadBuildIsTheSameTreeAndQueriesAreExact) {
  std::mt19937_64 gen(7);
  std::uniform_real_distribution<double> u(0.0, 100.0);
  std::vector<fdr::Point2> p(70000);
  for (auto& q : p) q = {u(gen), std::floor(u(gen))};  // repeated y: ties in the splits
  const fdr::KdTree one(p, 1), two(p, 2);
  ASSERT_EQ(one.size(), p.size());
  for (std::size_t k = 0; k < one.size(); ++k) ASSERT_EQ(one.id_at(k), two.id_at(k)) << k;
  for (std::size_t k = 0; k < one.size(); k += 997) {
    const fdr::Point2 q = p[two.id_at(k)];
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < p.size(); ++i)
      if (i != two.id_at(k)) best = std::min(best, fdr::norm2(p[i] - q));
    EXPECT_EQ(two.nearest_sq_at(k), best);
    std::vector<fdr::Index> a, b;
    one.for_each_within(q, 4.0, [&](fdr::Index i) { a.push_back(i); });
    two.for_each_within(q, 4.0, [&](fdr::Index i) { b.push_back(i); });
    EXPECT_EQ(a, b);
    std::size_t brute = 0;
    for (const auto& r : p) brute += fdr::norm2(r - q) < 4.0;
    EXPECT_EQ(b.size(), brute);
  }
}
