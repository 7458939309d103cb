// Step of the islet handling: islets grouped into clusters, the islets nearer to each other than
// the water between them can hold.
//
// Why clusters: islets a fraction of hmin apart (a ledge of rocks, a chain of cays) each leave
// the others no room for a triangle, and one by one each is removed or placed beside the next,
// with water narrower than an element between them. As one group they become one island (their
// convex hull), one triangle or one join to nearby land, and the gaps inside the group go.
#pragma once
#include <cstddef>
#include <vector>

#include "base/types.hpp"

namespace fdr::coast {

// Distance between the rings a and b (vertices without the closing repeat), along their
// segments (0 when they meet; rings inside one another are not looked for).
double ring_gap(const std::vector<Point2>& a, const std::vector<Point2>& b);

// Groups of the rings nearer than `gap` to each other (single link: a chain of pairs each
// nearer than gap is one group). Every ring is in exactly one group; each group lists its rings
// in ascending order and the groups come in the order of their first ring, so the result does
// not depend on anything but the rings' order.
std::vector<std::vector<std::size_t>> islet_clusters(const std::vector<std::vector<Point2>>& rings, double gap);

}  // namespace fdr::coast
