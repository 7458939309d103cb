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
  const unsigned hw = std::thread::hardware_concurrency();
  return hw == 0 ? 1 : std::min(hw, 2u);
}

}  // namespace fdr
