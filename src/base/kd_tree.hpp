// Static 2-d tree for exact nearest-other-point queries (quality report, refinement's D).
#pragma once
#include <algorithm>
#include <cstddef>
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
  explicit KdTree(const std::vector<Point2>& p, unsigned threads = 1) : t_(p.size()) {
    for (std::size_t i = 0; i < p.size(); ++i) t_[i] = {p[i], static_cast<Index>(i)};
    if (threads >= 2 && t_.size() >= (std::size_t{1} << 16)) {
      const std::size_t mid = split(0, t_.size(), 0);
      run_beside([&] { build(mid + 1, t_.size(), 1); }, [&] { build(0, mid, 1); });
    } else {
      build(0, t_.size(), 0);
    }
  }
  std::size_t size() const { return t_.size(); }
  Index id_at(std::size_t pos) const { return t_[pos].id; }
  // Squared distance from the point at tree position `pos` to the nearest point with another
  // index. `bound` is an upper bound that is itself such a squared distance norm2(p_v - p_self)
  // (or +inf): only points strictly closer are searched, so the result is the same value either way.
  double nearest_sq_at(std::size_t pos, double bound = std::numeric_limits<double>::infinity()) const {
    double best = bound;
    query(t_[pos].p, t_[pos].id, 0, t_.size(), 0, best);
    return best;
  }
  // Calls f(index) for every point strictly nearer than sqrt(r2) to q (in tree order).
  template <class F>
  void for_each_within(Point2 q, double r2, F&& f) const {
    within(q, r2, 0, t_.size(), 0, f);
  }

 private:
  struct Node {
    Point2 p;
    Index id;
  };
  static constexpr std::size_t kScan = 8;  // ranges this small are scanned
  static double coord(Point2 q, int axis) { return axis == 0 ? q.x : q.y; }
  // Puts the median of [lo, hi) along `axis` at its middle, smaller ones before; returns the middle.
  std::size_t split(std::size_t lo, std::size_t hi, int axis) {
    const std::size_t mid = lo + (hi - lo) / 2;
    std::nth_element(t_.begin() + static_cast<std::ptrdiff_t>(lo), t_.begin() + static_cast<std::ptrdiff_t>(mid),
                     t_.begin() + static_cast<std::ptrdiff_t>(hi),
                     [axis](const Node& a, const Node& b) { return coord(a.p, axis) < coord(b.p, axis); });
    return mid;
  }
  void build(std::size_t lo, std::size_t hi, int axis) {
    if (hi - lo <= kScan) return;  // queries scan such ranges whole: no order needed inside
    const std::size_t mid = split(lo, hi, axis);
    build(lo, mid, 1 - axis);
    build(mid + 1, hi, 1 - axis);
  }
  // Why the far side is visited only conditionally: points across the splitting line are at
  // least |diff| away, so they cannot beat a best distance already below diff^2.
  void query(Point2 q, Index self, std::size_t lo, std::size_t hi, int axis, double& best) const {
    if (hi - lo <= kScan) {
      for (std::size_t k = lo; k < hi; ++k)
        if (t_[k].id != self) best = std::min(best, norm2(t_[k].p - q));
      return;
    }
    const std::size_t mid = lo + (hi - lo) / 2;
    const Node& n = t_[mid];
    if (n.id != self) best = std::min(best, norm2(n.p - q));
    const double diff = coord(q, axis) - coord(n.p, axis);
    if (diff < 0) {
      query(q, self, lo, mid, 1 - axis, best);
      if (diff * diff < best) query(q, self, mid + 1, hi, 1 - axis, best);
    } else {
      query(q, self, mid + 1, hi, 1 - axis, best);
      if (diff * diff < best) query(q, self, lo, mid, 1 - axis, best);
    }
  }
  template <class F>
  void within(Point2 q, double r2, std::size_t lo, std::size_t hi, int axis, F& f) const {
    if (hi - lo <= kScan) {
      for (std::size_t k = lo; k < hi; ++k)
        if (norm2(t_[k].p - q) < r2) f(t_[k].id);
      return;
    }
    const std::size_t mid = lo + (hi - lo) / 2;
    if (norm2(t_[mid].p - q) < r2) f(t_[mid].id);
    const double diff = coord(q, axis) - coord(t_[mid].p, axis);
    if (diff < 0 || diff * diff < r2) within(q, r2, lo, mid, 1 - axis, f);
    if (diff >= 0 || diff * diff < r2) within(q, r2, mid + 1, hi, 1 - axis, f);
  }
  std::vector<Node> t_;
};

}  // namespace fdr
