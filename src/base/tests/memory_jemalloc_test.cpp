// ArenaDecay, KeepFreedPages and HugePageArenas in a process whose allocator is jemalloc
// (this test links it, as the fdrmesh program does, with the same compiled-in options): every
// arena's decay is 0 (-1) while it lives, the previous values after; the extent hooks wrapped and
// restored.
#include <gtest/gtest.h>
#include <sys/types.h>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <thread>
#include <vector>
#include "base/memory.hpp"
#include "base/tests/smaps_flags.hpp"

extern "C" int mallctl(const char* name, void* oldp, std::size_t* oldlenp, void* newp, std::size_t newlen);

namespace {
template <class T>
T read_ctl(const std::string& name) {
  T v{};
  std::size_t len = sizeof v;
  EXPECT_EQ(mallctl(name.c_str(), &v, &len, nullptr, 0), 0) << name;
  return v;
}
ssize_t read_ssize(const std::string& name) {
  ssize_t v = -99;
  std::size_t len = sizeof v;
  EXPECT_EQ(mallctl(name.c_str(), &v, &len, nullptr, 0), 0) << name;
  return v;
}
}  // namespace

TEST(ArenaDecay, DecayZeroWhileItLivesThenTheHostsSettings) {
  std::vector<std::unique_ptr<char[]>> keep;
  for (int i = 0; i < 100; ++i) keep.emplace_back(new char[1000 + i]);  // arena 0 in use
  const ssize_t dirty0 = read_ssize("arenas.dirty_decay_ms"), arena0 = read_ssize("arena.0.dirty_decay_ms");
  ASSERT_GT(dirty0, 0);  // jemalloc's default (10 s)
  {
    fdr::ArenaDecay eager(0);
    EXPECT_TRUE(eager.active());
    EXPECT_EQ(read_ssize("arenas.dirty_decay_ms"), 0);
    EXPECT_EQ(read_ssize("arenas.muzzy_decay_ms"), 0);
    EXPECT_EQ(read_ssize("arena.0.dirty_decay_ms"), 0);
    fdr::release_free_memory();
  }
  EXPECT_EQ(read_ssize("arenas.dirty_decay_ms"), dirty0);
  EXPECT_EQ(read_ssize("arena.0.dirty_decay_ms"), arena0);
}


TEST(JemallocOptions, OneArenaForEveryThread) {  // src/base/jemalloc_conf.cpp
  EXPECT_EQ(read_ctl<unsigned>("opt.narenas"), 1u);
}

TEST(KeepFreedPages, DecayMinusOneWhileItLivesThenPurgedAndTheHostsSettings) {
  const ssize_t dirty0 = read_ssize("arenas.dirty_decay_ms"), arena0 = read_ssize("arena.0.dirty_decay_ms");
  auto dirty_pages = [] {
    std::uint64_t epoch = 1;
    std::size_t len = sizeof epoch;
    EXPECT_EQ(mallctl("epoch", &epoch, &len, &epoch, len), 0);
    return read_ctl<std::size_t>("stats.arenas.4096.pdirty");  // every arena's (MALLCTL_ARENAS_ALL)
  };
  {
    fdr::KeepFreedPages keep;
    EXPECT_TRUE(keep.active());
    EXPECT_EQ(read_ssize("arenas.dirty_decay_ms"), -1);
    EXPECT_EQ(read_ssize("arenas.muzzy_decay_ms"), -1);
    EXPECT_EQ(read_ssize("arena.0.dirty_decay_ms"), -1);
    std::vector<std::unique_ptr<char[]>> blocks;
    for (int i = 0; i < 4096; ++i) blocks.emplace_back(new char[2000]);  // small objects, ~8 MiB
    for (auto& b : blocks) b[0] = 1;
    blocks.clear();
    EXPECT_GT(dirty_pages(), 0u);  // kept for reuse
  }
  EXPECT_EQ(dirty_pages(), 0u);  // given back when it ended
  EXPECT_EQ(read_ssize("arenas.dirty_decay_ms"), dirty0);
  EXPECT_EQ(read_ssize("arena.0.dirty_decay_ms"), arena0);
}

namespace {
void* read_hooks(unsigned arena) {
  void* h = nullptr;
  std::size_t len = sizeof h;
  const std::string name = "arena." + std::to_string(arena) + ".extent_hooks";
  EXPECT_EQ(mallctl(name.c_str(), &h, &len, nullptr, 0), 0) << name;
  return h;
}
}  // namespace

// The hooks are wrapped while it lives (one at a time), what the arena maps then is advised, and
// the hooks and the advice are taken back when it ends.
TEST(HugePageArenas, WrapsEveryArenasHooksWhileItLivesThenRestoresThem) {
  std::vector<std::unique_ptr<char[]>> keep;
  for (int i = 0; i < 100; ++i) keep.emplace_back(new char[1000 + i]);  // arena 0 in use
  void* const before = read_hooks(0);
  std::unique_ptr<char[]> big;
  {
    fdr::HugePageArenas huge;
    ASSERT_TRUE(huge.active());
    EXPECT_NE(read_hooks(0), before);
    {
      fdr::HugePageArenas second;  // one at a time
      EXPECT_FALSE(second.active());
    }
    EXPECT_NE(read_hooks(0), before);
    // New memory the arena maps now is advised (a 256 MiB block: more than anything retained).
    big.reset(new char[std::size_t{256} << 20]);
    EXPECT_TRUE(fdr::test::advised_huge(big.get() + (std::size_t{128} << 20)));
  }
  EXPECT_EQ(read_hooks(0), before);
  EXPECT_FALSE(fdr::test::advised_huge(big.get() + (std::size_t{128} << 20)));  // the advice taken back
}

// The constructor makes the arena of allocations above opt.oversize_threshold with one 16 MiB
// allocation before it wraps the hooks; the arena keeps that extent for the next large request,
// which must be advised too (it was not: the first 16 MiB array of a run faulted in 4 KiB pages).
TEST(HugePageArenas, AdvisesTheExtentItAllocatesBeforeWrappingTheHooks) {
  std::unique_ptr<char[]> grid;
  {
    fdr::HugePageArenas huge;
    ASSERT_TRUE(huge.active());
    grid.reset(new char[std::size_t{16} << 20]);
    EXPECT_TRUE(fdr::test::advised_huge(grid.get() + (std::size_t{8} << 20)));
  }
  EXPECT_FALSE(fdr::test::advised_huge(grid.get() + (std::size_t{8} << 20)));  // the advice taken back
}

// An OwnArena keeps its decay at -1 while an ArenaDecay(0) sets every other arena's to 0,
// the bound thread allocates from it, release_free_memory() leaves its pages, and its end
// purges them.
TEST(OwnArena, KeepsItsPagesUnderEagerReleaseAndIsBound) {
  fdr::OwnArena own;
  ASSERT_TRUE(own.active());
  unsigned mine = 0;
  std::vector<std::unique_ptr<char[]>> blocks;
  std::thread t([&] {
    own.bind();
    mine = read_ctl<unsigned>("thread.arena");
    for (int i = 0; i < 2000; ++i) blocks.emplace_back(new char[4096]);
  });
  t.join();
  ASSERT_NE(mine, 0u);
  const std::string a = "arena." + std::to_string(mine) + ".";
  EXPECT_EQ(read_ssize(a + "dirty_decay_ms"), -1);
  {
    fdr::ArenaDecay eager(0);
    EXPECT_EQ(read_ssize("arena.0.dirty_decay_ms"), 0);
    EXPECT_EQ(read_ssize(a + "dirty_decay_ms"), -1);  // left alone
    blocks.clear();  // freed into the own arena: kept
    fdr::release_free_memory();
    std::size_t dirty = 0;
    const std::uint64_t epoch = 1;
    mallctl("epoch", nullptr, nullptr, const_cast<std::uint64_t*>(&epoch), sizeof epoch);
    dirty = read_ctl<std::size_t>("stats.arenas." + std::to_string(mine) + ".pdirty");
    EXPECT_GT(dirty, 0u);  // its freed pages stay for reuse
  }
  EXPECT_EQ(read_ssize(a + "dirty_decay_ms"), -1);
}

TEST(ProcessMemory, PeakAtLeastResident) {
  const auto m = fdr::process_memory();
  ASSERT_TRUE(m.has_value());
  EXPECT_GT(m->rss, 0u);
  EXPECT_GE(m->peak, m->rss);
}
