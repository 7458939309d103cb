// Returning freed memory to the system between pipeline stages.
#pragma once

namespace fdr {

// Gives the pages of freed memory back to the system when the program's allocator is jemalloc
// (the fdrmesh program links it, see src/cli/CMakeLists.txt); a no-op under any other allocator.
// Why: jemalloc keeps freed pages resident for seconds and serves the next stage's arrays from
// other pages, so one stage's garbage would sit in the peak beside the next stage's data.
void release_free_memory();

// From now on, freed pages go back to the system at once (jemalloc: every arena's dirty and muzzy
// decay set to 0; a no-op under any other allocator). The pipeline switches it on before the
// triangulation: the mesh's arrays are few and large, and lazily kept pages of one stage would
// otherwise add to the next stage's peak (at 1 M triangles 76 -> 58 MiB). The GIS input stages
// before keep the lazy default: GEOS frees millions of small objects, and purging each page at
// once costs system time (Gulf of Maine: +1 s).
void release_freed_memory_at_once();

// True when the process's allocator is jemalloc (for the report's provenance and the tests).
bool allocator_is_jemalloc();

}  // namespace fdr
