// Static 2-d tree for exact nearest-other-point queries (quality report, refinement's D).
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>
#include "base/parallel.hpp"
#include "base/types.hpp"

namespace fdr {

// Static 2-d tree (implicit: the median of each range is its node) over copies of the points
// kept in tree order, so a query reads contiguous memory and consecutive queries in tree order
// share most of it.
class KdTree {
 public:
  // threads >= 2: the two halves below the first split are built on two threads (the same tree:
  // each range is ordered by the same nth_element calls whatever the thread).
  explicit KdTree(const std::vector<Point2>& p, unsigned threads = 1) : t_(p.size()), axis_(p.size(), 0) {
    for (std::size_t i = 0; i < p.size(); ++i) t_[i] = {p[i], static_cast<Index>(i)};
    if (threads >= 2 && t_.size() >= (std::size_t{1} << 16)) {
      const std::size_t mid = split(0, t_.size());
      run_beside([&] { build(mid + 1, t_.size()); }, [&] { build(0, mid); });
    } else {
      build(0, t_.size());
    }
  }
  std::size_t size() const { return t_.size(); }
  Index id_at(std::size_t pos) const { return t_[pos].id; }
  // Squared distance from the point at tree position `pos` to the nearest point with another
  // index. `bound` is an upper bound that is itself such a squared distance norm2(p_v - p_self)
  // (or +inf): only points strictly closer are searched, so the result is the same value either way.
  double nearest_sq_at(std::size_t pos, double bound = std::numeric_limits<double>::infinity()) const {
    double best = bound;
    // Why the points beside pos in tree order first: they are near it, and a bound found before
    // the descent keeps a query that ties with a split (a point on a straight boundary meeting
    // another at a corner) from searching the far side's whole subtree.
    const std::size_t lo = pos >= kScan ? pos - kScan : 0, hi = std::min(t_.size(), pos + kScan + 1);
    for (std::size_t k = lo; k < hi; ++k)
      if (t_[k].id != t_[pos].id) best = std::min(best, norm2(t_[k].p - t_[pos].p));
    query(t_[pos].p, t_[pos].id, 0, t_.size(), best);
    return best;
  }
  // Calls f(index) for every point strictly nearer than sqrt(r2) to q (in tree order).
  template <class F>
  void for_each_within(Point2 q, double r2, F&& f) const {
    within(q, r2, 0, t_.size(), f);
  }

 private:
  struct Node {
    Point2 p;
    Index id;
  };
  static constexpr std::size_t kScan = 8;  // ranges this small are scanned
  static double coord(Point2 q, int axis) { return axis == 0 ? q.x : q.y; }
  // Puts the median of [lo, hi) along the axis of its larger extent at its middle, smaller ones
  // before, and records that axis there; returns the middle. Why the larger extent rather than
  // alternating axes: points on one vertical or horizontal line (a resampled straight boundary)
  // all tie on the other axis, and a query from such a point would search both sides of every
  // split along it.
  std::size_t split(std::size_t lo, std::size_t hi) {
    Box2 b;
    for (std::size_t k = lo; k < hi; ++k) b.add(t_[k].p);
    const int axis = b.width() >= b.height() ? 0 : 1;
    const std::size_t mid = lo + (hi - lo) / 2;
    std::nth_element(t_.begin() + static_cast<std::ptrdiff_t>(lo), t_.begin() + static_cast<std::ptrdiff_t>(mid),
                     t_.begin() + static_cast<std::ptrdiff_t>(hi),
                     [axis](const Node& a, const Node& b) { return coord(a.p, axis) < coord(b.p, axis); });
    axis_[mid] = static_cast<std::uint8_t>(axis);
    return mid;
  }
  void build(std::size_t lo, std::size_t hi) {
    if (hi - lo <= kScan) return;  // queries scan such ranges whole: no order needed inside
    const std::size_t mid = split(lo, hi);
    build(lo, mid);
    build(mid + 1, hi);
  }
  // Why the far side is visited only conditionally: points across the splitting line are at
  // least |diff| away, so they cannot beat a best distance already below diff^2.
  void query(Point2 q, Index self, std::size_t lo, std::size_t hi, double& best) const {
    if (hi - lo <= kScan) {
      for (std::size_t k = lo; k < hi; ++k)
        if (t_[k].id != self) best = std::min(best, norm2(t_[k].p - q));
      return;
    }
    const std::size_t mid = lo + (hi - lo) / 2;
    const Node& n = t_[mid];
    if (n.id != self) best = std::min(best, norm2(n.p - q));
    const double diff = coord(q, axis_[mid]) - coord(n.p, axis_[mid]);
    if (diff < 0) {
      query(q, self, lo, mid, best);
      if (diff * diff < best) query(q, self, mid + 1, hi, best);
    } else {
      query(q, self, mid + 1, hi, best);
      if (diff * diff < best) query(q, self, lo, mid, best);
    }
  }
  template <class F>
  void within(Point2 q, double r2, std::size_t lo, std::size_t hi, F& f) const {
    if (hi - lo <= kScan) {
      for (std::size_t k = lo; k < hi; ++k)
        if (norm2(t_[k].p - q) < r2) f(t_[k].id);
      return;
    }
    const std::size_t mid = lo + (hi - lo) / 2;
    if (norm2(t_[mid].p - q) < r2) f(t_[mid].id);
    const double diff = coord(q, axis_[mid]) - coord(t_[mid].p, axis_[mid]);
    if (diff < 0 || diff * diff < r2) within(q, r2, lo, mid, f);
    if (diff >= 0 || diff * diff < r2) within(q, r2, mid + 1, hi, f);
  }
  std::vector<Node> t_;
  std::vector<std::uint8_t> axis_;  // per node (the middle of its range): 0 x, 1 y
};

}  // namespace fdr
