// PSLG validation: duplicates, zero-length segments, vertices on segments, crossings.
#pragma once
#include <string>
#include <utility>
#include <vector>
#include "pslg/pslg.hpp"

namespace fdr::pslg {

// Throws Error(kInvalidGeometry, "<source>: ...") naming ids (0-based) and world coordinates
// of the first problem found, in this order: non-finite coordinates, segment index out of range,
// duplicate vertices (equal coordinates), zero-length segments, duplicate segments, a vertex in a
// segment's interior, two segments crossing or overlapping other than at a shared endpoint.
void validate(const Pslg& pslg, const std::string& source);

// Pairs (i < j, sorted) of segments that cross, touch or overlap other than at a shared
// endpoint. Zero-length segments are ignored. Near-linear (uniform grid), decisions by orient2d.
std::vector<std::pair<Index, Index>> find_crossings(const Pslg& pslg);

// Pairs (vertex, segment), sorted, where the vertex lies in the segment's open interior.
std::vector<std::pair<Index, Index>> find_vertices_on_segments(const Pslg& pslg);

}  // namespace fdr::pslg
