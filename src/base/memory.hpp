// The allocator's controls: freed memory returned to the system or kept, huge pages, the process's
// arenas. Which of them a run uses is decided in one place (pipeline/memory_policy.hpp).
#pragma once
#include <sys/types.h>
#include <cstddef>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

namespace fdr {

// The process-wide allocator settings of a program (the fdrmesh command calls it first thing;
// libraries leave their host's allocator alone). Under glibc's malloc: one arena for every thread,
// so that a second thread and the concurrent writers reuse the memory the refinement freed instead
// of growing arenas of their own. Under jemalloc nothing: its options are compiled in
// (src/base/jemalloc_conf.cpp).
void set_process_allocator_policy();

// Gives the pages of freed memory back to the system when the program's allocator is jemalloc
// (the fdrmesh program links it, see src/cli/CMakeLists.txt); a no-op under any other allocator.
// Why: jemalloc keeps freed pages resident for seconds and serves the next stage's arrays from
// other pages, so one stage's garbage would sit in the peak beside the next stage's data.
void release_free_memory();

// Asks the kernel to back [p, p + bytes) with transparent huge pages (madvise MADV_HUGEPAGE on
// the 2 MiB-aligned pages inside the range; nothing for smaller ranges or where the kernel has no
// THP). Call it on a large array's buffer before its pages are first touched. Why: the mesh's
// arrays are tens of MiB written once in scattered order, and a 4 KiB page fault costs about as
// much as writing the page.
void advise_huge_pages(const void* p, std::size_t bytes);

// Takes the advice back (MADV_NOHUGEPAGE on the same pages; pages already huge stay so until
// freed). Call it before a buffer is freed: the allocator keeps the range mapped, the range would
// keep the advice, and small allocations placed there later would each fault in 2 MiB.
void unadvise_huge_pages(const void* p, std::size_t bytes);

// The same for a vector's whole capacity.
template <class V>
void advise_huge_pages(const V& v) {
  advise_huge_pages(static_cast<const void*>(v.data()), v.capacity() * sizeof(typename V::value_type));
}
template <class V>
void unadvise_huge_pages(const V& v) {
  unadvise_huge_pages(static_cast<const void*>(v.data()), v.capacity() * sizeof(typename V::value_type));
}

// Frees v's buffer, its advice taken back first.
template <class V>
void release_huge(V& v) {
  unadvise_huge_pages(v);
  V().swap(v);
}

// v.assign(n, x) / v.resize(n) with a new buffer advised before it is written (a buffer that
// already holds n stays).
template <class V>
void assign_huge(V& v, std::size_t n, const typename V::value_type& x) {
  if (v.capacity() < n) {
    V().swap(v);
    v.reserve(n);
    advise_huge_pages(v);
  }
  v.assign(n, x);
}
// v.reserve(n), the new buffer advised before the elements move in.
template <class V>
void reserve_huge(V& v, std::size_t n) {
  if (v.capacity() >= n) return;
  V w;
  w.reserve(n);
  advise_huge_pages(w);
  w.insert(w.end(), std::make_move_iterator(v.begin()), std::make_move_iterator(v.end()));
  v.swap(w);
  unadvise_huge_pages(w);
}
template <class V>
void resize_huge(V& v, std::size_t n) {
  reserve_huge(v, n);
  v.resize(n);
}

// While it lives, every jemalloc arena's dirty and muzzy decay is `ms` (0: freed pages go back to
// the system at once; -1: never, they stay for reuse); a no-op under any other allocator. The
// previous settings come back when it ends, so a host program keeps its own.
class ArenaDecay {
 public:
  explicit ArenaDecay(ssize_t ms);
  ~ArenaDecay();
  ArenaDecay(const ArenaDecay&) = delete;
  ArenaDecay& operator=(const ArenaDecay&) = delete;
  bool active() const { return active_; }

 private:
  bool active_ = false;
  ssize_t default_dirty_ = 0, default_muzzy_ = 0;  // arenas.*_decay_ms (arenas made later)
  std::vector<ssize_t> dirty_, muzzy_;             // arena.<i>.*_decay_ms
};

// Decay -1 while it lives (freed pages stay with the allocator and serve the next allocations),
// and every freed page goes back to the system when it ends. Why: where millions of small objects
// are allocated and freed, pages purged by the default decay would be faulted in again.
class KeepFreedPages : public ArenaDecay {
 public:
  KeepFreedPages() : ArenaDecay(-1) {}
  ~KeepFreedPages();
};

// This process's resident memory now and at its peak (Linux /proc/self/status VmRSS, VmHWM, in
// kB there), in bytes; nullopt without a VmHWM line (rss 0 without a VmRSS line). `status_path`:
// another status file (tests).
struct ProcessMemory {
  std::size_t rss = 0, peak = 0;
};
std::optional<ProcessMemory> process_memory(const std::string& status_path = "/proc/self/status");

// A jemalloc arena of its own for work that runs beside the pipeline's stages (the GIS filter's
// removed-water listing: GEOS's small objects), whose freed pages it keeps (decay -1) whatever the
// ArenaDecay of the stages meanwhile and release_free_memory() leaves alone, and whose extents of
// 2 MiB or more are advised for huge pages; bind() puts the calling thread's allocations there.
// When it ends its pages go back to the system (the arena stays: objects made there may live on;
// a process makes at most 1 024, then it is a no-op). Why: under the stages' own settings and the
// purge at every stage's end, every page the work beside them freed would be faulted in again.
// A no-op under any other allocator.
class OwnArena {
 public:
  OwnArena();
  ~OwnArena();
  OwnArena(const OwnArena&) = delete;
  OwnArena& operator=(const OwnArena&) = delete;
  void bind() const;  // the calling thread allocates from it (until it ends)
  bool active() const { return active_; }

 private:
  bool active_ = false;
  unsigned index_ = 0;
};

// While it lives, the memory jemalloc maps for its arenas is backed by transparent huge pages
// (every arena's extent allocation hook is wrapped to madvise MADV_HUGEPAGE the extents of 2 MiB
// or more that it maps; the advice is taken back and the previous hooks come back when it ends,
// so a host program keeps its own). A no-op under any other allocator, under a jemalloc other
// than 5.x, or while another HugePageArenas lives. Why: memory written once in scattered order
// (many small objects, grids of tens of MiB) takes one fault per 2 MiB instead of one per 4 KiB.
// Memory mapped before it lives is not advised: jemalloc reuses what it retains without calling
// the hook, so it must live from the first stage that wants it on. Not for phases of few large
// arrays: there small allocations would each take a 2 MiB page, and the large arrays are advised
// one by one (advise_huge_pages).
class HugePageArenas {
 public:
  HugePageArenas();
  ~HugePageArenas();
  HugePageArenas(const HugePageArenas&) = delete;
  HugePageArenas& operator=(const HugePageArenas&) = delete;
  bool active() const { return active_; }

 private:
  bool active_ = false;
  std::vector<void*> previous_;  // per arena: its hooks before (nullptr: not changed)
};

}  // namespace fdr
