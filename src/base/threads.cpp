// Thread budget (see threads.hpp).
#include "base/threads.hpp"

#include <algorithm>
#include <cstdlib>
#include <thread>

namespace fdr {

unsigned max_threads() {
  if (const char* env = std::getenv("FDR_THREADS")) {
    char* end = nullptr;
    const long v = std::strtol(env, &end, 10);
    if (end != env && *end == '\0' && v > 0) return static_cast<unsigned>(std::min<long>(v, 64));
  }
  // The cores are counted once: glibc reads /sys/devices/system/cpu/online on every call, and the
  // GIS filter asks once per polygon it buffers (thousands of times on a coast).
  static const unsigned hw = std::thread::hardware_concurrency();
  return hw == 0 ? 1 : std::min(hw, 2u);
}

}  // namespace fdr
