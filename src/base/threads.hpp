// How many threads fdrmesh may use for work that is free to overlap (writers, report); the
// helpers that use them are in base/parallel.hpp.
#pragma once

namespace fdr {

// The FDR_THREADS environment variable when it holds a positive number (at most 64), else
// min(2, hardware threads). Results never depend on it: threads only run independent pieces of
// work whose results are combined in a fixed order.
unsigned max_threads();

}  // namespace fdr
