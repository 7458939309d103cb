// Small geometry helpers of the coast generalisation: ring areas, convex hulls, distances between
// segments and convex polygons, boxes, and a grid of disks. Doubles: these decide where new coast
// goes, not the mesh; the mesher's exact predicates check the result.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "base/types.hpp"

namespace fdr::coast {

// Signed area of a ring without the closing repeat (counter-clockwise positive).
double signed_area(const std::vector<Point2>& r);
// Convex hull, counter-clockwise, without collinear points (Andrew's monotone chain).
std::vector<Point2> convex_hull(std::vector<Point2> p);
// Closed segments ab and cd meet (exact orientations).
bool segments_meet(Point2 a, Point2 b, Point2 c, Point2 d);
// Distance between segments ab and cd (0 when they meet).
double segment_distance(Point2 a, Point2 b, Point2 c, Point2 d);
Box2 box_of(const std::vector<Point2>& pts);
// p farther than r from box b (a cheap test before the exact ones).
bool beyond(Point2 p, double r, const Box2& b);
// Boxes a and b farther apart than r along x or y.
bool apart(const Box2& a, const Box2& b, double r);
// p inside the ring (even-odd; a ray through a vertex counts once: the half-open rule on y).
bool inside_ring(Point2 p, const std::vector<Point2>& ring);
// p in the closed convex polygon h (counter-clockwise).
bool inside_convex(Point2 p, const std::vector<Point2>& h);
// Distance from segment ab to the convex polygon h (0 when they meet).
double convex_distance(Point2 a, Point2 b, const std::vector<Point2>& h);
// Distance between the convex polygons a and b (counter-clockwise; 0 when they meet or one holds
// the other).
double convex_gap(const std::vector<Point2>& a, const std::vector<Point2>& b);

// Disks (centre, radius) by the cells of a uniform grid their boxes cover: which of them may
// meet a box. For the islets' triangles (thousands, each placement testing every one before).
class DiskGrid {
 public:
  explicit DiskGrid(double cell) : cell_(cell > 0 ? cell : 1) {}
  void add(std::uint32_t id, Point2 c, double r) {
    cells({{c.x - r, c.y - r}, {c.x + r, c.y + r}}, [&](std::uint64_t k) {
      m_[k].push_back(id);
      return false;
    });
  }
  // The ids of the disks whose boxes may meet b, ascending, without repeats.
  void near(const Box2& b, std::vector<std::uint32_t>* out) const {
    out->clear();
    cells(b, [&](std::uint64_t k) {
      if (auto it = m_.find(k); it != m_.end()) out->insert(out->end(), it->second.begin(), it->second.end());
      return false;
    });
    std::sort(out->begin(), out->end());
    out->erase(std::unique(out->begin(), out->end()), out->end());
  }

 private:
  template <class F>
  void cells(const Box2& b, F f) const {
    const auto i0 = static_cast<std::int64_t>(std::floor(b.lo.x / cell_)), i1 = static_cast<std::int64_t>(std::floor(b.hi.x / cell_));
    const auto j0 = static_cast<std::int64_t>(std::floor(b.lo.y / cell_)), j1 = static_cast<std::int64_t>(std::floor(b.hi.y / cell_));
    for (std::int64_t i = i0; i <= i1; ++i)
      for (std::int64_t j = j0; j <= j1; ++j)
        if (f((static_cast<std::uint64_t>(i) << 32) ^ static_cast<std::uint64_t>(static_cast<std::uint32_t>(j)))) return;
  }
  double cell_;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> m_;
};

}  // namespace fdr::coast
