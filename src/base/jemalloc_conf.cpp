// jemalloc's compiled-in options for the programs that link it (fdrmesh, bench_gis and the
// jemalloc test; CMakeLists.txt: fdr_jemalloc). One arena for every thread: pages that one
// thread freed serve the next allocations of any thread (GEOS on the feature filter's two
// threads, std::async threads that come and go), so the GIS input stages, which keep freed pages
// for reuse (base/memory.hpp: KeepFreedPages), do not fault in fresh pages per arena (GSHHG-h
// basin: read 26 s with jemalloc's 8 arenas, 19-20 s with one; README "Allocator"). The mesh
// stages' few threads allocate few large arrays and do not contend. MALLOC_CONF, read after this,
// tunes it as usual.
extern "C" {
extern const char* malloc_conf;
const char* malloc_conf = "narenas:1";
}
