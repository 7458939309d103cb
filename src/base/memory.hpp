// Returning freed memory to the system between pipeline stages.
#pragma once
#include <sys/types.h>
#include <vector>

namespace fdr {

// Gives the pages of freed memory back to the system when the program's allocator is jemalloc
// (the fdrmesh program links it, see src/cli/CMakeLists.txt); a no-op under any other allocator.
// Why: jemalloc keeps freed pages resident for seconds and serves the next stage's arrays from
// other pages, so one stage's garbage would sit in the peak beside the next stage's data.
void release_free_memory();

// While it lives, freed pages go back to the system at once (jemalloc: every arena's dirty and
// muzzy decay 0; a no-op under any other allocator); the previous settings come back when it
// ends, so a host program keeps its own. The pipeline holds one from the triangulation on: the
// mesh's arrays are few and large, and pages kept lazily by one stage would add to the next
// stage's peak (at 1 M triangles 76 -> 57 MiB). The GIS input stages before keep the lazy
// default: GEOS frees millions of small objects, and purging each page at once costs system time
// (Gulf of Maine: +1 s).
class EagerMemoryRelease {
 public:
  EagerMemoryRelease();
  ~EagerMemoryRelease();
  EagerMemoryRelease(const EagerMemoryRelease&) = delete;
  EagerMemoryRelease& operator=(const EagerMemoryRelease&) = delete;
  bool active() const { return active_; }

 private:
  bool active_ = false;
  ssize_t default_dirty_ = 0, default_muzzy_ = 0;  // arenas.*_decay_ms (arenas made later)
  std::vector<ssize_t> dirty_, muzzy_;             // arena.<i>.*_decay_ms
};

}  // namespace fdr
