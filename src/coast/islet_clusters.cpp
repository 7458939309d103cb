// Islet clusters (islet_clusters.hpp).
#include "coast/islet_clusters.hpp"

#include <algorithm>
#include <limits>
#include <numeric>

#include "coast/convex.hpp"

namespace fdr::coast {

double ring_gap(const std::vector<Point2>& a, const std::vector<Point2>& b) {
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < a.size() && d > 0; ++i)
    for (std::size_t j = 0; j < b.size() && d > 0; ++j)
      d = std::min(d, segment_distance(a[i], a[(i + 1) % a.size()], b[j], b[(j + 1) % b.size()]));
  return d;
}

std::vector<std::vector<std::size_t>> islet_clusters(const std::vector<std::vector<Point2>>& rings, double gap) {
  const std::size_t n = rings.size();
  std::vector<std::size_t> up(n);
  std::iota(up.begin(), up.end(), std::size_t{0});
  auto root = [&](std::size_t i) {
    while (up[i] != i) i = up[i] = up[up[i]];
    return i;
  };
  std::vector<Box2> box(n);
  for (std::size_t i = 0; i < n; ++i) box[i] = box_of(rings[i]);
  // A sweep along x: the pairs whose boxes come within gap, each tested once by its segments.
  std::vector<std::size_t> by_x(n);
  std::iota(by_x.begin(), by_x.end(), std::size_t{0});
  std::sort(by_x.begin(), by_x.end(), [&](std::size_t a, std::size_t b) {
    return box[a].lo.x < box[b].lo.x || (box[a].lo.x == box[b].lo.x && a < b);
  });
  for (std::size_t s = 0; s < n; ++s) {
    const std::size_t i = by_x[s];
    for (std::size_t t = s + 1; t < n && !(box[by_x[t]].lo.x > box[i].hi.x + gap); ++t) {
      const std::size_t j = by_x[t];
      if (apart(box[i], box[j], gap) || root(i) == root(j)) continue;
      if (ring_gap(rings[i], rings[j]) < gap) up[root(i)] = root(j);
    }
  }
  std::vector<std::vector<std::size_t>> members(n);
  for (std::size_t i = 0; i < n; ++i) members[root(i)].push_back(i);
  std::vector<std::vector<std::size_t>> out;
  for (std::size_t i = 0; i < n; ++i)  // in the order of their first ring
    if (!members[root(i)].empty() && members[root(i)].front() == i) out.push_back(std::move(members[root(i)]));
  return out;
}

}  // namespace fdr::coast
