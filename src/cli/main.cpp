// fdrmesh: Functional Delaunay Refinement mesher for coastlines and terrain.
#include "cli/cli.hpp"
#ifdef __GLIBC__
#include <malloc.h>
#endif

int main(int argc, char** argv) {
#ifdef __GLIBC__
  // One malloc arena for every thread: the report's second thread and the concurrent writers then
  // reuse the memory the refinement freed instead of growing arenas of their own (+6 MiB of peak
  // at 1 M triangles; README "Benchmark"). Their few large allocations do not contend.
  mallopt(M_ARENA_MAX, 1);
#endif
  return fdr::cli::run(argc, argv);
}
