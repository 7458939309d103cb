// Parallel helpers: the one place that starts threads. Work is split into pieces whose results
// are written to their own places or combined in a fixed order, so that every result is the same
// whatever the thread count (max_threads(), FDR_THREADS in base/debug.hpp).
#pragma once
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <functional>
#include <memory>
#include <thread>
#include <vector>
#include "base/threads.hpp"

namespace fdr {

// Per-thread state that a worker hands back to the thread that started it when it ends (the
// predicates' call counters): `take` moves the calling thread's state out (a heap blob, reset
// to zero), `give` adds a blob to the calling thread's state and frees it. Registered once at
// static initialisation by the module that owns the state; at most kMaxThreadStates.
struct ThreadStateHooks {
  void* (*take)();
  void (*give)(void*);
};
constexpr std::size_t kMaxThreadStates = 4;
bool register_thread_state(ThreadStateHooks hooks);

namespace detail {
// The worker's states (take at its end) and their merge on the starting thread.
struct ThreadStates {
  void* blobs[kMaxThreadStates] = {};
  void take();
  void give();
};
}  // namespace detail

// Runs fn on a thread of its own; join() waits for it, merges its thread states into the
// calling thread's and returns its exception (null when none). Destroying it joins.
class Worker {
 public:
  explicit Worker(std::function<void()> fn)
      : fn_(std::move(fn)), t_([this] {
          try {
            fn_();
          } catch (...) {
            error_ = std::current_exception();
          }
          states_.take();
        }) {}
  ~Worker() {
    if (t_.joinable()) t_.join();
  }
  Worker(const Worker&) = delete;
  Worker& operator=(const Worker&) = delete;
  std::exception_ptr join() {
    if (t_.joinable()) {
      t_.join();
      states_.give();
    }
    return error_;
  }

 private:
  std::function<void()> fn_;
  std::exception_ptr error_;
  detail::ThreadStates states_;
  std::thread t_;  // last: starts once the members above exist
};

// Runs `other` on a second thread while `mine` runs on the calling thread, waits for both (also
// when `mine` throws) and then rethrows: the caller's exception first, else the other thread's.
template <class Other, class Mine>
void run_beside(Other&& other, Mine&& mine) {
  Worker w([&other] { other(); });
  try {
    mine();
  } catch (...) {
    w.join();
    throw;
  }
  if (std::exception_ptr e = w.join()) std::rethrow_exception(e);
}

// Calls fn(begin, end) on up to `threads` disjoint bands covering [0, n), concurrently when there
// are at least `min_per_thread` items per thread (a thread costs tens of microseconds to start).
// The first exception (by band) is rethrown once every band is done.
template <class Fn>
void parallel_bands(std::size_t n, Fn&& fn, std::size_t min_per_thread = 64, unsigned threads = max_threads()) {
  const std::size_t k =
      std::max<std::size_t>(1, std::min<std::size_t>(threads, n / std::max<std::size_t>(min_per_thread, 1)));
  if (k <= 1) {
    fn(std::size_t{0}, n);
    return;
  }
  const std::size_t band = (n + k - 1) / k;
  std::vector<std::unique_ptr<Worker>> pool;
  std::exception_ptr first;
  for (std::size_t t = 1; t < k; ++t)
    pool.push_back(std::make_unique<Worker>(
        [&fn, t, band, n] { fn(std::min(n, t * band), std::min(n, (t + 1) * band)); }));
  try {
    fn(std::size_t{0}, std::min(n, band));
  } catch (...) {
    first = std::current_exception();
  }
  for (auto& w : pool)
    if (std::exception_ptr e = w->join(); e && !first) first = e;
  if (first) std::rethrow_exception(first);
}

// Calls fn(chunk, worker) for every chunk in [0, nchunks) on up to `threads` threads (worker 0 is
// the calling thread); chunks are claimed in increasing order, so a fast thread takes more. fn
// must write each chunk's results to that chunk's own place. The first exception is rethrown
// once every thread stopped (the others stop claiming).
template <class Fn>
void parallel_chunks(std::size_t nchunks, Fn&& fn, unsigned threads = max_threads()) {
  const unsigned k = static_cast<unsigned>(std::max<std::size_t>(1, std::min<std::size_t>(threads, nchunks)));
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  auto loop = [&](unsigned worker) {
    for (std::size_t c; !stop.load(std::memory_order_relaxed) && (c = next.fetch_add(1)) < nchunks;) {
      try {
        fn(c, worker);
      } catch (...) {
        stop = true;
        throw;
      }
    }
  };
  if (k <= 1) {
    loop(0);
    return;
  }
  std::vector<std::unique_ptr<Worker>> pool;
  for (unsigned w = 1; w < k; ++w) pool.push_back(std::make_unique<Worker>([&loop, w] { loop(w); }));
  std::exception_ptr first;
  try {
    loop(0);
  } catch (...) {
    first = std::current_exception();
  }
  for (auto& w : pool)
    if (std::exception_ptr e = w->join(); e && !first) first = e;
  if (first) std::rethrow_exception(first);
}

}  // namespace fdr
