// jemalloc's compiled-in options for the programs that link it (fdrmesh, bench_gis and the
// jemalloc test; CMakeLists.txt: fdr_jemalloc). One arena for every thread: pages that one
// thread freed serve the next allocations of any thread (GEOS on the feature filter's two
// threads, std::async threads that come and go), so the GIS input stages, which keep freed pages
// for reuse (base/memory.hpp: KeepFreedPages), do not fault in fresh pages per arena, which on
// large inputs costs more than the arenas save in contention. The mesh stages' few threads
// allocate few large arrays and do not contend. MALLOC_CONF, read after this, tunes it as usual.
extern "C" {
extern const char* malloc_conf;
const char* malloc_conf = "narenas:1";
}
