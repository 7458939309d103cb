// How many threads fdrmesh may use for work that is free to overlap (writers, report).
#pragma once

#include <exception>
#include <thread>

namespace fdr {

// The FDR_THREADS environment variable when it holds a positive number (at most 64), else
// min(2, hardware threads). Results never depend on it: threads only run independent pieces of
// work whose results are combined in a fixed order.
unsigned max_threads();

// Runs `other` on a second thread while `mine` runs on the calling thread, waits for both (also
// when `mine` throws) and then rethrows: the caller's exception first, else the other thread's.
template <class Other, class Mine>
void run_beside(Other&& other, Mine&& mine) {
  std::exception_ptr error;
  std::thread t([&] {
    try {
      other();
    } catch (...) {
      error = std::current_exception();
    }
  });
  struct Join {
    std::thread& t;
    ~Join() {
      if (t.joinable()) t.join();
    }
  } join{t};
  mine();
  t.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace fdr
