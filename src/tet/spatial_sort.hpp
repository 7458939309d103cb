// Insertion order for the Delaunay tetrahedralization: a biased randomized insertion order (BRIO,
// Amenta, Choi and Rote 2003) whose rounds follow a 3D Hilbert curve, so that consecutive points
// are close (short walks, cache-friendly) while the rounds keep the expected cost of random order.
#pragma once
#include <cstdint>
#include <span>
#include <vector>
#include "base/point3.hpp"
#include "base/types.hpp"

namespace fdr::tet {

// Position of the cell (x, y, z) along the Hilbert curve through the 2^bits-cube of cells
// (bits <= 21): consecutive keys belong to cells that share a face.
std::uint64_t hilbert_key(std::uint32_t x, std::uint32_t y, std::uint32_t z, int bits);

// The round (0 first) of input point i among `rounds` rounds: about half of the points fall in
// the last round, a quarter in the one before, and so on; the first round takes the rest. A hash
// of i decides it, so the order is the same on every run.
int brio_round(std::uint64_t i, int rounds);

// How many rounds n points get: the first round holds about a thousand points.
int brio_rounds(std::size_t n);

// The insertion order: indices into pts, round by round, each round along the Hilbert curve of
// the points' bounding box (ties by index).
std::vector<Index> brio_order(std::span<const Point3> pts);

}  // namespace fdr::tet
