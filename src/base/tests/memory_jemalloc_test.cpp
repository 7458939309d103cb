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

#include <sys/mman.h>
#include <cstdint>
#include <fstream>
#include <sstream>

namespace {
void* read_hooks(unsigned arena) {
  void* h = nullptr;
  std::size_t len = sizeof h;
  const std::string name = "arena." + std::to_string(arena) + ".extent_hooks";
  EXPECT_EQ(mallctl(name.c_str(), &h, &len, nullptr, 0), 0) << name;
  return h;
}

// True when the mapping that holds p is advised for huge pages ("hg" in its VmFlags).
bool advised_huge(const void* p) {
  std::ifstream smaps("/proc/self/smaps");
  const auto a = reinterpret_cast<std::uintptr_t>(p);
  bool inside = false;
  for (std::string line; std::getline(smaps, line);) {
    std::uintptr_t lo = 0, hi = 0;
    char dash = 0;
    std::istringstream ls(line);
    if (ls >> std::hex >> lo >> dash >> hi && dash == '-') {
      inside = a >= lo && a < hi;
      continue;
    }
    if (inside && line.rfind("VmFlags:", 0) == 0) return line.find(" hg") != std::string::npos;
  }
  return false;
}
}  // namespace

TEST(HugePageArenas, WrapsEveryArenasHooksWhileItLivesThenRestoresThem) {
  std::vector<std::unique_ptr<char[]>> keep;
  for (int i = 0; i < 100; ++i) keep.emplace_back(new char[1000 + i]);  // arena 0 in use
  void* const before = read_hooks(0);
  {
    fdr::HugePageArenas huge;
    ASSERT_TRUE(huge.active());
    EXPECT_NE(read_hooks(0), before);
    {
      fdr::HugePageArenas second;  // one at a time
      EXPECT_FALSE(second.active());
    }
    EXPECT_NE(read_hooks(0), before);
    // New memory the arena maps now is advised (a 64 MiB block: more than anything retained).
    std::unique_ptr<char[]> big(new char[std::size_t{64} << 20]);
    EXPECT_TRUE(advised_huge(big.get() + (std::size_t{32} << 20)));
  }
  EXPECT_EQ(read_hooks(0), before);
}

TEST(AdviseHugePages, AdvisesTheAlignedInsideOfARange) {
  const std::size_t len = std::size_t{8} << 20;
  void* p = mmap(nullptr, len, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  ASSERT_NE(p, MAP_FAILED);
  char* c = static_cast<char*>(p);
  EXPECT_FALSE(advised_huge(c + len / 2));
  fdr::advise_huge_pages(c, len);
  EXPECT_TRUE(advised_huge(c + len / 2));
  std::vector<double> small(100);
  fdr::advise_huge_pages(small);  // under 2 MiB: nothing to advise, no error
  munmap(p, len);
}
