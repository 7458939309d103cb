// Tests for base: boxes, error codes, GDAL-style progress text.
#include <gtest/gtest.h>
#include <algorithm>
#include <cstdio>
#include <string>
#include <cmath>
#include <limits>
#include <random>
#include <vector>
#include "base/error.hpp"
#include "base/kd_tree.hpp"
#include "base/point_cells.hpp"
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
  fdr::ArenaDecay eager(0);
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

// PointCells: the same points as brute force (and as KdTree) for every radius, the kept points
// only; clustered points (a coast), duplicates, points outside the given box, one-point and
// one-place sets, and radii 0, NaN and infinite.
TEST(PointCells, WithinEqualsBruteForce) {
  std::mt19937_64 gen(11);
  std::uniform_real_distribution<double> u(0.0, 1000.0), w(0.0, 1.0);
  std::vector<fdr::Point2> p;
  for (int i = 0; i < 20000; ++i) p.push_back({u(gen), u(gen)});
  for (int i = 0; i < 20000; ++i) {  // a dense band along y = 500 (a coast)
    const double x = u(gen);
    p.push_back({x, 500 + 3 * w(gen)});
  }
  for (int i = 0; i < 100; ++i) p.push_back(p[static_cast<std::size_t>(i) * 7]);  // duplicates
  auto keep = [](fdr::Index i) { return i % 5 != 3; };
  fdr::Box2 box;
  for (fdr::Index i = 0; i < p.size(); ++i)
    if (keep(i)) box.add(p[i]);
  auto brute = [&](fdr::Point2 q, double r2) {
    std::vector<fdr::Index> out;
    for (fdr::Index i = 0; i < p.size(); ++i)
      if (keep(i) && fdr::norm2(p[i] - q) < r2) out.push_back(i);
    return out;
  };
  auto within = [&](const fdr::PointCells& c, fdr::Point2 q, double r2) {
    std::vector<fdr::Index> out;
    c.for_each_within(q, r2, [&](fdr::Index i) { out.push_back(i); });
    std::sort(out.begin(), out.end());
    return out;
  };
  for (const double cell : {0.5, 3.0, 40.0, 0.0, -1.0, std::nan("")}) {
    const fdr::PointCells c(p, keep, box, cell);
    for (int k = 0; k < 300; ++k) {
      const fdr::Point2 q = k % 3 == 0 ? p[static_cast<std::size_t>(k) * 131] : fdr::Point2{u(gen) * 1.2 - 100, u(gen)};
      const double r = k % 4 == 0 ? 0.7 : k % 4 == 1 ? 5.0 : k % 4 == 2 ? 60.0 : 1500.0;
      ASSERT_EQ(within(c, q, r * r), brute(q, r * r)) << "cell " << cell << " query " << k;
    }
    EXPECT_TRUE(within(c, p[0], 0.0).empty());
    EXPECT_TRUE(within(c, p[0], std::nan("")).empty());
    EXPECT_EQ(within(c, p[0], std::numeric_limits<double>::infinity()).size(), brute(p[0], 1e300).size());
  }
  const fdr::PointCells outside(p, keep, fdr::Box2{{400, 400}, {600, 600}}, 10.0);  // points beyond the box
  EXPECT_EQ(within(outside, {950, 20}, 2500.0), brute({950, 20}, 2500.0));
  const std::vector<fdr::Point2> same(50, fdr::Point2{3, 4});  // one place: a box of zero size
  fdr::Box2 b1;
  b1.add(same[0]);
  const fdr::PointCells one(same, [](fdr::Index) { return true; }, b1, 0.0);
  std::size_t n = 0;
  one.for_each_within({3, 4.5}, 1.0, [&](fdr::Index) { ++n; });
  EXPECT_EQ(n, 50u);
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
