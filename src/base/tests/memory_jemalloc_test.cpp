// EagerMemoryRelease in a process whose allocator is jemalloc (this test links it, as the
// fdrmesh program does): every arena's decay is 0 while it lives, the previous values after.
#include <gtest/gtest.h>
#include <sys/types.h>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>
#include "base/memory.hpp"

extern "C" int mallctl(const char* name, void* oldp, std::size_t* oldlenp, void* newp, std::size_t newlen);

namespace {
ssize_t read_ssize(const std::string& name) {
  ssize_t v = -99;
  std::size_t len = sizeof v;
  EXPECT_EQ(mallctl(name.c_str(), &v, &len, nullptr, 0), 0) << name;
  return v;
}
}  // namespace

TEST(EagerMemoryRelease, DecayZeroWhileItLivesThenTheHostsSettings) {
  std::vector<std::unique_ptr<char[]>> keep;
  for (int i = 0; i < 100; ++i) keep.emplace_back(new char[1000 + i]);  // arena 0 in use
  const ssize_t dirty0 = read_ssize("arenas.dirty_decay_ms"), arena0 = read_ssize("arena.0.dirty_decay_ms");
  ASSERT_GT(dirty0, 0);  // jemalloc's default (10 s)
  {
    fdr::EagerMemoryRelease eager;
    EXPECT_TRUE(eager.active());
    EXPECT_EQ(read_ssize("arenas.dirty_decay_ms"), 0);
    EXPECT_EQ(read_ssize("arenas.muzzy_decay_ms"), 0);
    EXPECT_EQ(read_ssize("arena.0.dirty_decay_ms"), 0);
    fdr::release_free_memory();
  }
  EXPECT_EQ(read_ssize("arenas.dirty_decay_ms"), dirty0);
  EXPECT_EQ(read_ssize("arena.0.dirty_decay_ms"), arena0);
}

