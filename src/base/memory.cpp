// jemalloc's controls through a weak reference to mallctl, so that the library needs no allocator
// of its own and does nothing in hosts that use glibc's malloc.
#include "base/memory.hpp"
#include <cstddef>
#include <string>
#include <cstdint>
#include <sys/mman.h>

extern "C" int mallctl(const char* name, void* oldp, std::size_t* oldlenp, void* newp,
                       std::size_t newlen) __attribute__((weak));

namespace fdr {
namespace {

// Reads the ssize_t control `name` into *old and writes v; false if jemalloc refuses.
bool swap_ssize(const std::string& name, ssize_t* old, ssize_t v) {
  std::size_t len = sizeof *old;
  return mallctl(name.c_str(), old, &len, &v, sizeof v) == 0;
}

unsigned arena_count() {
  unsigned n = 0;
  std::size_t len = sizeof n;
  return mallctl("arenas.narenas", &n, &len, nullptr, 0) == 0 ? n : 0;
}

}  // namespace

#if defined(MADV_HUGEPAGE) && defined(MADV_NOHUGEPAGE)
namespace {
// madvise(advice) on the 2 MiB-aligned pages inside [p, p + bytes); advice only: errors are ignored.
void advise_inner(const void* p, std::size_t bytes, int advice) {
  constexpr std::uintptr_t kHuge = std::uintptr_t{1} << 21;
  const auto b = reinterpret_cast<std::uintptr_t>(p);
  const std::uintptr_t lo = (b + kHuge - 1) & ~(kHuge - 1), hi = (b + bytes) & ~(kHuge - 1);
  if (p != nullptr && hi > lo) madvise(reinterpret_cast<void*>(lo), hi - lo, advice);
}
}  // namespace

void advise_huge_pages(const void* p, std::size_t bytes) { advise_inner(p, bytes, MADV_HUGEPAGE); }
void unadvise_huge_pages(const void* p, std::size_t bytes) { advise_inner(p, bytes, MADV_NOHUGEPAGE); }
#else
void advise_huge_pages(const void*, std::size_t) {}
void unadvise_huge_pages(const void*, std::size_t) {}
#endif

void release_free_memory() {
  // 4096 = MALLCTL_ARENAS_ALL (jemalloc 5): every arena.
  if (mallctl) mallctl("arena.4096.purge", nullptr, nullptr, nullptr, 0);
}

ArenaDecay::ArenaDecay(ssize_t ms) {
  if (!mallctl) return;
  if (!swap_ssize("arenas.dirty_decay_ms", &default_dirty_, ms)) return;
  if (!swap_ssize("arenas.muzzy_decay_ms", &default_muzzy_, ms)) {
    swap_ssize("arenas.dirty_decay_ms", &default_dirty_, default_dirty_);
    return;
  }
  active_ = true;
  const unsigned n = arena_count();
  dirty_.assign(n, -2);  // -2: not changed (an arena not initialised yet)
  muzzy_.assign(n, -2);
  for (unsigned i = 0; i < n; ++i) {
    const std::string a = "arena." + std::to_string(i) + ".";
    ssize_t old = 0;
    if (swap_ssize(a + "dirty_decay_ms", &old, ms)) dirty_[i] = old;
    if (swap_ssize(a + "muzzy_decay_ms", &old, ms)) muzzy_[i] = old;
  }
}

ArenaDecay::~ArenaDecay() {
  if (!active_) return;
  ssize_t old = 0;
  swap_ssize("arenas.dirty_decay_ms", &old, default_dirty_);
  swap_ssize("arenas.muzzy_decay_ms", &old, default_muzzy_);
  const unsigned n = arena_count();
  for (unsigned i = 0; i < n; ++i) {  // arenas made meanwhile took ms: they get the default
    const std::string a = "arena." + std::to_string(i) + ".";
    const ssize_t d = i < dirty_.size() && dirty_[i] != -2 ? dirty_[i] : default_dirty_;
    const ssize_t m = i < muzzy_.size() && muzzy_[i] != -2 ? muzzy_[i] : default_muzzy_;
    swap_ssize(a + "dirty_decay_ms", &old, d);
    swap_ssize(a + "muzzy_decay_ms", &old, m);
  }
}

EagerMemoryRelease::EagerMemoryRelease() : ArenaDecay(0) { release_free_memory(); }

KeepFreedPages::~KeepFreedPages() { release_free_memory(); }

}  // namespace fdr
