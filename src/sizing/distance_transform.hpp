// Exact Euclidean distance transform of a raster mask (separable, O(cells)).
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace fdr::sizing {

constexpr std::uint32_t kNoFeature = 0xffffffffu;

// For every cell of an nx x ny raster (row-major, index j * nx + i; cells dx x dy), the index of
// a nearest `seed` cell (seed[k] != 0) by Euclidean distance between cell centres, and, when
// `d2` is given, that squared distance computed as (di * dx)^2 + (dj * dy)^2 with di, dj the
// index differences. kNoFeature (and +inf) everywhere when there is no seed.
//
// Algorithm (Meijster, Roerdink & Hesselink 2000; Felzenszwalb & Huttenlocher 2004): pass 1
// finds the nearest seed in each column (one upward and one downward scan over the rows, all
// columns at once); pass 2 takes, row by row, the lower envelope of the parabolas
// (x - i)^2 dx^2 + g_i^2 dy^2 of the columns i. Exact: the distance returned is the minimum over
// all seeds (for square cells the envelope is computed on integers held exactly in doubles; for
// dx != dy a tie between two seeds may be resolved to either). Both passes split the raster over
// max_threads() threads by columns / rows; the result does not depend on the thread count.
// Needs nx * ny < 2^32.
void nearest_seed(std::size_t nx, std::size_t ny, double dx, double dy, const std::vector<char>& seed,
                  std::vector<std::uint32_t>& feature, std::vector<double>* d2 = nullptr);

}  // namespace fdr::sizing
