// release_free_memory: jemalloc's "arena.<all>.purge" through a weak reference, so that the
// library needs no allocator of its own and stays a no-op in hosts that use glibc's malloc.
#include "base/memory.hpp"
#include <cstddef>
#include <string>
#include <sys/types.h>

extern "C" int mallctl(const char* name, void* oldp, std::size_t* oldlenp, void* newp,
                       std::size_t newlen) __attribute__((weak));

namespace fdr {

void release_free_memory() {
  // 4096 = MALLCTL_ARENAS_ALL (jemalloc 5): every arena.
  if (mallctl) mallctl("arena.4096.purge", nullptr, nullptr, nullptr, 0);
}

void release_freed_memory_at_once() {
  if (!mallctl) return;
  ssize_t zero = 0;
  for (const char* name : {"arenas.dirty_decay_ms", "arenas.muzzy_decay_ms"})  // arenas made later
    mallctl(name, nullptr, nullptr, &zero, sizeof zero);
  unsigned n = 0;
  std::size_t len = sizeof n;
  if (mallctl("arenas.narenas", &n, &len, nullptr, 0) != 0) return;
  for (unsigned i = 0; i < n; ++i)
    for (const char* what : {"dirty_decay_ms", "muzzy_decay_ms"}) {
      const std::string name = "arena." + std::to_string(i) + "." + what;
      mallctl(name.c_str(), nullptr, nullptr, &zero, sizeof zero);
    }
  mallctl("arena.4096.purge", nullptr, nullptr, nullptr, 0);
}

bool allocator_is_jemalloc() {
  if (!mallctl) return false;
  const char* v = nullptr;
  std::size_t n = sizeof v;
  return mallctl("version", &v, &n, nullptr, 0) == 0 && v != nullptr;
}

}  // namespace fdr
