// Cache prefetch hints, the one place algorithm code gets them from: a hint never changes a
// result, only when the memory it names arrives.
#pragma once

namespace fdr {

// The cache line holding *p will be read soon.
inline void prefetch(const void* p) { __builtin_prefetch(p, 0); }
// The cache line holding *p will be written soon.
inline void prefetch_for_write(const void* p) { __builtin_prefetch(p, 1); }

}  // namespace fdr
