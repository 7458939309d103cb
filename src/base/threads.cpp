// Thread budget (threads.hpp) and the registry of per-thread states (parallel.hpp).
#include "base/parallel.hpp"

#include <algorithm>
#include <cstdlib>
#include "base/debug.hpp"
#include <atomic>
#include <thread>

namespace fdr {

unsigned max_threads() {
  if (const char* env = debug::value(debug::Aid::kThreads)) {
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

namespace fdr {
namespace {
ThreadStateHooks g_states[kMaxThreadStates];
std::atomic<std::size_t> g_nstates{0};
}  // namespace

bool register_thread_state(ThreadStateHooks hooks) {
  const std::size_t k = g_nstates.fetch_add(1);
  if (k >= kMaxThreadStates) return false;
  g_states[k] = hooks;
  return true;
}

namespace detail {
void ThreadStates::take() {
  const std::size_t n = std::min(g_nstates.load(), kMaxThreadStates);
  for (std::size_t k = 0; k < n; ++k) blobs[k] = g_states[k].take();
}
void ThreadStates::give() {
  const std::size_t n = std::min(g_nstates.load(), kMaxThreadStates);
  for (std::size_t k = 0; k < n; ++k)
    if (blobs[k]) g_states[k].give(blobs[k]), blobs[k] = nullptr;
}
}  // namespace detail
}  // namespace fdr
