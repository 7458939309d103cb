// fdrmesh: Functional Delaunay Refinement mesher for coastlines and terrain.
#include "cli/cli.hpp"
#if defined(__GLIBC__) && !defined(FDR_JEMALLOC)
#include <malloc.h>
#endif

// FDR_JEMALLOC: the program links jemalloc (src/cli/CMakeLists.txt; README "Allocator"), with one
// arena (src/base/jemalloc_conf.cpp); the pipeline keeps freed pages for reuse in the GIS input
// stages and purges them at once from the triangulation on (base/memory.hpp).

int main(int argc, char** argv) {
#if defined(__GLIBC__) && !defined(FDR_JEMALLOC)
  // One malloc arena for every thread: the report's second thread and the concurrent writers then
  // reuse the memory the refinement freed instead of growing arenas of their own (+6 MiB of peak
  // at 1 M triangles; README "Benchmark"). Their few large allocations do not contend.
  mallopt(M_ARENA_MAX, 1);
#endif
  return fdr::cli::run(argc, argv);
}
