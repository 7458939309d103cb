// The base seams: parallel helpers (exceptions, thread states), LargeArray, the debug registry.
#include <gtest/gtest.h>
#include <atomic>
#include <stdexcept>
#include <string>
#include <vector>
#include "base/debug.hpp"
#include "base/large_array.hpp"
#include "base/parallel.hpp"

using namespace fdr;

namespace {
thread_local int tls_count = 0;
void* take_count() {
  auto* p = new int(tls_count);
  tls_count = 0;
  return p;
}
void give_count(void* p) {
  tls_count += *static_cast<int*>(p);
  delete static_cast<int*>(p);
}
const bool kRegistered = register_thread_state({take_count, give_count});
}  // namespace

TEST(Parallel, BandsCoverEveryItemOnce) {
  for (unsigned threads : {1u, 2u, 3u}) {
    std::vector<int> hits(1000, 0);
    parallel_bands(hits.size(), [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) ++hits[i];
    }, 1, threads);
    for (int h : hits) ASSERT_EQ(h, 1) << threads;
  }
}

TEST(Parallel, ChunksCoverEveryChunkOnce) {
  std::vector<std::atomic<int>> hits(257);
  parallel_chunks(hits.size(), [&](std::size_t c, unsigned) { hits[c]++; }, 2);
  for (auto& h : hits) ASSERT_EQ(h.load(), 1);
}

TEST(Parallel, ExceptionsReachTheCaller) {
  EXPECT_THROW(run_beside([] { throw std::runtime_error("other"); }, [] {}), std::runtime_error);
  try {
    run_beside([] { throw std::runtime_error("other"); }, [] { throw std::logic_error("mine"); });
    FAIL();
  } catch (const std::logic_error&) {  // the caller's first
  }
  EXPECT_THROW(parallel_bands(100, [](std::size_t b, std::size_t) {
    if (b > 0) throw std::runtime_error("band");
  }, 1, 2), std::runtime_error);
  EXPECT_THROW(parallel_chunks(50, [](std::size_t c, unsigned) {
    if (c == 7) throw std::runtime_error("chunk");
  }, 2), std::runtime_error);
}

TEST(Parallel, WorkersHandTheirThreadStatesBack) {
  ASSERT_TRUE(kRegistered);
  tls_count = 0;
  run_beside([] { tls_count += 5; }, [] { tls_count += 1; });
  EXPECT_EQ(tls_count, 6);
  parallel_bands(10, [](std::size_t b, std::size_t e) { tls_count += static_cast<int>(e - b); }, 1, 2);
  EXPECT_EQ(tls_count, 16);
}

TEST(LargeArray, BehavesAsAVector) {
  LargeArray<int> a;
  for (int i = 0; i < 100000; ++i) a.push_back(i);
  ASSERT_EQ(a.size(), 100000u);
  EXPECT_EQ(a[99999], 99999);
  a.assign(1 << 20, 7);
  EXPECT_EQ(a.size(), std::size_t{1} << 20);
  EXPECT_EQ(a.back(), 7);
  LargeArray<int> b = a;
  EXPECT_TRUE(a == b);
  std::vector<int> v = std::move(b).take();
  EXPECT_EQ(v.size(), a.size());
  a.release();
  EXPECT_EQ(a.capacity(), 0u);
}

TEST(Debug, RegistryNamesEveryAidInOrder) {
  const auto r = debug::registry();
  ASSERT_EQ(r.size(), static_cast<std::size_t>(debug::Aid::kCount));
  for (std::size_t i = 0; i < r.size(); ++i) {
    EXPECT_EQ(static_cast<std::size_t>(r[i].aid), i);
    const std::string v = r[i].variable;
    EXPECT_TRUE(v.rfind("FDR_", 0) == 0 || v.rfind("FDRMESH_", 0) == 0) << v;
  }
}
