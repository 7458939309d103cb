// jemalloc's controls through a weak reference to mallctl, so that the library needs no allocator
// of its own and does nothing in hosts that use glibc's malloc.
#include "base/memory.hpp"
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <sys/mman.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

extern "C" int mallctl(const char* name, void* oldp, std::size_t* oldlenp, void* newp,
                       std::size_t newlen) __attribute__((weak));

namespace fdr {
namespace {

// Reads the ssize_t control `name` into *old and writes v; false if jemalloc refuses.
bool swap_ssize(const std::string& name, ssize_t* old, ssize_t v) {
  std::size_t len = sizeof *old;
  return mallctl(name.c_str(), old, &len, &v, sizeof v) == 0;
}

// Arenas that ArenaDecay leaves alone (OwnArena's), as a bit per arena index.
constexpr unsigned kMaxOwn = 1024;
std::atomic<std::uint64_t> g_own[kMaxOwn / 64];
bool own_arena(unsigned i) { return i < kMaxOwn && (g_own[i / 64].load() >> (i % 64) & 1u) != 0; }

unsigned arena_count() {
  unsigned n = 0;
  std::size_t len = sizeof n;
  return mallctl("arenas.narenas", &n, &len, nullptr, 0) == 0 ? n : 0;
}

// jemalloc 5's extent_hooks_t (jemalloc/jemalloc.h, "arena.<i>.extent_hooks" in jemalloc(3)):
// only `alloc` is called here, the other members are copied as they are.
struct ExtentHooks {
  void* (*alloc)(ExtentHooks*, void*, std::size_t, std::size_t, bool*, bool*, unsigned);
  void* rest[8];  // dalloc, destroy, commit, decommit, purge_lazy, purge_forced, split, merge
};

constexpr unsigned kMaxArenas = 1024;
ExtentHooks* g_previous[kMaxArenas];  // per arena: the hooks the wrapper calls
ExtentHooks g_wrapped[kMaxArenas];    // per arena: the previous hooks with `alloc` wrapped
std::atomic<bool> g_huge_active{false};
// What the wrapper advised, taken back when the HugePageArenas ends (fixed storage: the hook may
// not allocate). Past kMaxRanges nothing more is advised.
constexpr std::size_t kMaxRanges = 1 << 14;
struct Range {
  void* p;
  std::size_t size;
};
Range g_ranges[kMaxRanges];
std::atomic<std::size_t> g_nranges{0};

// Advises [p, p + size) and records it for the HugePageArenas' end (nothing past kMaxRanges).
void advise_and_record(void* p, std::size_t size) {
  const std::size_t k = g_nranges.fetch_add(1);
  if (k < kMaxRanges) {
    g_ranges[k] = {p, size};
    advise_huge_pages(p, size);
  }
}

void* huge_alloc(ExtentHooks* hooks, void* new_addr, std::size_t size, std::size_t alignment, bool* zero,
                 bool* commit, unsigned arena) {
  ExtentHooks* prev = arena < kMaxArenas ? g_previous[arena] : nullptr;
  if (prev == nullptr) {  // cannot happen: the wrapper is installed only where g_previous is set
    (void)hooks;
    return nullptr;
  }
  void* p = prev->alloc(prev, new_addr, size, alignment, zero, commit, arena);
  // An OwnArena's extents are its own: advised, not recorded (a HugePageArenas ending meanwhile
  // leaves them advised).
  if (p != nullptr && size >= (std::size_t{1} << 21)) {
    if (own_arena(arena)) advise_huge_pages(p, size);
    else advise_and_record(p, size);
  }
  return p;
}

bool jemalloc5() {
  const char* version = nullptr;
  std::size_t len = sizeof version;
  return mallctl("version", &version, &len, nullptr, 0) == 0 && version != nullptr && std::strncmp(version, "5.", 2) == 0;
}

// Wraps arena i's extent hooks with huge_alloc; returns the hooks before (nullptr: not wrapped).
ExtentHooks* wrap_hooks(unsigned i) {
  if (i >= kMaxArenas) return nullptr;
  const std::string name = "arena." + std::to_string(i) + ".extent_hooks";
  ExtentHooks* old = nullptr;
  std::size_t olen = sizeof old;
  if (mallctl(name.c_str(), &old, &olen, nullptr, 0) != 0 || old == nullptr || old->alloc == nullptr) return nullptr;
  if (old == &g_wrapped[i]) return nullptr;  // wrapped already (an ended OwnArena keeps its hooks)
  g_previous[i] = old;
  g_wrapped[i] = *old;
  g_wrapped[i].alloc = huge_alloc;
  ExtentHooks* mine = &g_wrapped[i];
  return mallctl(name.c_str(), nullptr, nullptr, &mine, sizeof mine) == 0 ? old : nullptr;
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

std::optional<ProcessMemory> process_memory(const std::string& status_path) {
  std::FILE* f = std::fopen(status_path.c_str(), "r");
  if (!f) return std::nullopt;
  ProcessMemory m;
  bool peak = false;
  char line[256];
  while (std::fgets(line, sizeof line, f)) {
    unsigned long long kb = 0;
    char unit[4] = "";
    const bool rss_line = std::sscanf(line, "VmRSS: %llu %3s", &kb, unit) == 2;
    const bool hwm_line = !rss_line && std::sscanf(line, "VmHWM: %llu %3s", &kb, unit) == 2;
    if (!(rss_line || hwm_line) || std::strcmp(unit, "kB") != 0) continue;
    (rss_line ? m.rss : m.peak) = static_cast<std::size_t>(kb) * 1024;
    peak = peak || hwm_line;
  }
  std::fclose(f);
  if (!peak) return std::nullopt;
  return m;
}

void set_process_allocator_policy() {
  if (mallctl) return;  // jemalloc: compiled-in options
#if defined(__GLIBC__) && defined(M_ARENA_MAX)
  mallopt(M_ARENA_MAX, 1);
#endif
}

void release_free_memory() {
  if (!mallctl) return;
  bool any_own = false;
  for (const auto& w : g_own) any_own = any_own || w.load() != 0;
  // 4096 = MALLCTL_ARENAS_ALL (jemalloc 5): every arena; else every arena but the OwnArenas.
  if (!any_own) {
    mallctl("arena.4096.purge", nullptr, nullptr, nullptr, 0);
    return;
  }
  const unsigned n = arena_count();
  for (unsigned i = 0; i < n; ++i)
    if (!own_arena(i)) mallctl(("arena." + std::to_string(i) + ".purge").c_str(), nullptr, nullptr, nullptr, 0);
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
    if (own_arena(i)) continue;
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
    if (own_arena(i)) continue;
    const std::string a = "arena." + std::to_string(i) + ".";
    const ssize_t d = i < dirty_.size() && dirty_[i] != -2 ? dirty_[i] : default_dirty_;
    const ssize_t m = i < muzzy_.size() && muzzy_[i] != -2 ? muzzy_[i] : default_muzzy_;
    swap_ssize(a + "dirty_decay_ms", &old, d);
    swap_ssize(a + "muzzy_decay_ms", &old, m);
  }
}


OwnArena::OwnArena() {
  if (!mallctl) return;
  unsigned i = 0;
  std::size_t len = sizeof i;
  if (mallctl("arenas.create", &i, &len, nullptr, 0) != 0 || i >= kMaxOwn) return;
  g_own[i / 64].fetch_or(std::uint64_t{1} << (i % 64));
  ssize_t old = 0;
  const std::string a = "arena." + std::to_string(i) + ".";
  swap_ssize(a + "dirty_decay_ms", &old, -1);
  swap_ssize(a + "muzzy_decay_ms", &old, -1);
  // Its extents on huge pages (jemalloc 5 hooks, as HugePageArenas): churn through a fresh arena
  // would otherwise fault in 4 KiB pages one by one.
  if (jemalloc5()) wrap_hooks(i);
  index_ = i;
  active_ = true;
}

OwnArena::~OwnArena() {
  if (!active_) return;
  // Its pages back to the system; objects still allocated there stay valid (any thread may free
  // them later). The arena itself stays (jemalloc does not reuse indices of destroyed arenas
  // that may still hold objects).
  ssize_t old = 0;
  const std::string a = "arena." + std::to_string(index_) + ".";
  swap_ssize(a + "dirty_decay_ms", &old, 0);
  swap_ssize(a + "muzzy_decay_ms", &old, 0);
  mallctl((a + "purge").c_str(), nullptr, nullptr, nullptr, 0);
  g_own[index_ / 64].fetch_and(~(std::uint64_t{1} << (index_ % 64)));
}

void OwnArena::bind() const {
  if (!active_) return;
  unsigned i = index_;
  mallctl("thread.arena", nullptr, nullptr, &i, sizeof i);
}

KeepFreedPages::~KeepFreedPages() { release_free_memory(); }

HugePageArenas::HugePageArenas() {
#ifdef MADV_HUGEPAGE
  if (!mallctl || !jemalloc5()) return;
  bool expected = false;
  if (!g_huge_active.compare_exchange_strong(expected, true)) return;  // one at a time
  // Every automatic arena is made now (an arena made later would take the default hooks), and
  // the arena of allocations above opt.oversize_threshold (8 MiB) by one such allocation. That
  // allocation's extent is mapped before the hooks are wrapped, and the arena keeps it for the
  // next large request: it is advised here, as the hook would have done (else the first large
  // array of a run would fault in 4 KiB pages).
  constexpr std::size_t kOversize = std::size_t{16} << 20;
  void* volatile oversize = std::malloc(kOversize);  // volatile: the pair is not elided
  if (oversize != nullptr) advise_and_record(oversize, kOversize);
  std::free(oversize);
  const unsigned n = std::min(arena_count(), kMaxArenas);
  previous_.assign(n, nullptr);
  for (unsigned i = 0; i < n; ++i)
    if (!own_arena(i)) previous_[i] = wrap_hooks(i);
  active_ = true;
#endif
}

HugePageArenas::~HugePageArenas() {
  if (!active_) return;
  for (unsigned i = 0; i < previous_.size(); ++i) {
    if (previous_[i] == nullptr) continue;
    const std::string name = "arena." + std::to_string(i) + ".extent_hooks";
    void* old = previous_[i];
    mallctl(name.c_str(), nullptr, nullptr, &old, sizeof old);
  }
  const std::size_t n = std::min(g_nranges.load(), kMaxRanges);
  for (std::size_t k = 0; k < n; ++k) unadvise_huge_pages(g_ranges[k].p, g_ranges[k].size);
  g_nranges.store(0);
  g_huge_active.store(false);
}

}  // namespace fdr
