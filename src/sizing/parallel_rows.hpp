// Row bands on up to max_threads() threads for the sizing rules. Each band writes only its own
// rows, so the result is the same whatever the thread count (FDR_THREADS).
#pragma once
#include <algorithm>
#include <cstddef>
#include <thread>
#include <vector>
#include "base/threads.hpp"

namespace fdr::sizing {

// Calls fn(begin, end) on disjoint bands covering [0, n); bands run concurrently when there are
// at least `min_per_thread` items per thread (threads cost ~50 us to start).
template <class Fn>
void parallel_rows(std::size_t n, Fn&& fn, std::size_t min_per_thread = 64) {
  const std::size_t threads =
      std::max<std::size_t>(1, std::min<std::size_t>(max_threads(), n / std::max<std::size_t>(min_per_thread, 1)));
  if (threads <= 1) {
    fn(std::size_t{0}, n);
    return;
  }
  const std::size_t band = (n + threads - 1) / threads;
  std::vector<std::thread> pool;
  for (std::size_t t = 1; t < threads; ++t)
    pool.emplace_back([&fn, t, band, n] { fn(std::min(n, t * band), std::min(n, (t + 1) * band)); });
  fn(std::size_t{0}, std::min(n, band));
  for (auto& th : pool) th.join();
}

}  // namespace fdr::sizing
