// A uniform grid of cells over points, for fixed-radius queries (refine/smooth.cpp).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>
#include "base/types.hpp"

namespace fdr {

// Points (those with keep(i)) in the cells of a uniform grid, in compressed rows: for_each_within
// calls f(i) for every kept point strictly nearer than sqrt(r2) to q, by the same test KdTree
// makes (norm2(p_i - q) < r2), so the same points (in another order). Why: the smoothing queries
// only its segment vertices, with radii near the cell length, so ordering every vertex for a
// tree (nth_element over copies of all of them) costs more than the queries gain; counting them
// into cells costs two passes. `cell`: the wanted cell length (enlarged to at most as many cells as
// points); `box`: the points' box (a point outside it falls in a border cell, still found).
class PointCells {
 public:
  template <class Keep>
  PointCells(std::span<const Point2> p, Keep&& keep, const Box2& box, double cell) : p_(p) {
    std::size_t n = 0;
    for (Index i = 0; i < p.size(); ++i) n += keep(i) ? 1 : 0;
    const double span = std::max(box.width(), box.height());
    if (n == 0 || box.empty() || !(span < std::numeric_limits<double>::infinity())) return;
    if (!(cell > 0) || !std::isfinite(cell)) cell = span;
    cell = std::max(cell, span * 1e-6);
    if (!(cell > 0)) cell = 1;  // every point at one place
    // At most about as many cells as points.
    auto cells = [&] { return (box.width() / cell + 1) * (box.height() / cell + 1); };
    for (int guard = 0; guard < 64 && cells() > static_cast<double>(n) + 64; ++guard) cell *= 1.5;
    lo_ = box.lo;
    inv_ = 1 / cell;
    nx_ = static_cast<std::size_t>(box.width() * inv_) + 1;
    ny_ = static_cast<std::size_t>(box.height() * inv_) + 1;
    start_.assign(nx_ * ny_ + 1, 0);
    for (Index i = 0; i < p.size(); ++i)
      if (keep(i)) ++start_[cell_of(p[i]) + 1];
    for (std::size_t c = 0; c + 1 < start_.size(); ++c) start_[c + 1] += start_[c];
    items_.resize(n);
    std::vector<std::uint32_t> cursor(start_.begin(), start_.end() - 1);
    for (Index i = 0; i < p.size(); ++i)
      if (keep(i)) items_[cursor[cell_of(p[i])]++] = i;
  }
  template <class F>
  void for_each_within(Point2 q, double r2, F&& f) const {
    if (items_.empty() || !(r2 > 0)) return;
    const double r = std::sqrt(r2);
    if (!std::isfinite(r)) {  // every point
      for (const Index i : items_)
        if (norm2(p_[i] - q) < r2) f(i);
      return;
    }
    // One cell more on each side: the cells of q -/+ r as rounded cannot miss a point within r.
    const std::size_t i0 = ix(q.x - r, lo_.x, nx_), i1 = ix(q.x + r, lo_.x, nx_);
    const std::size_t j0 = ix(q.y - r, lo_.y, ny_), j1 = ix(q.y + r, lo_.y, ny_);
    for (std::size_t j = j0 == 0 ? 0 : j0 - 1; j <= std::min(j1 + 1, ny_ - 1); ++j)
      for (std::size_t c = j * nx_ + (i0 == 0 ? 0 : i0 - 1), ce = j * nx_ + std::min(i1 + 1, nx_ - 1); c <= ce; ++c)
        for (std::uint32_t k = start_[c]; k < start_[c + 1]; ++k)
          if (norm2(p_[items_[k]] - q) < r2) f(items_[k]);
  }

 private:
  // The cell along one axis of n cells: the floor of (v - origin) / cell, clamped (NaN: 0).
  std::size_t ix(double v, double origin, std::size_t n) const {
    const double c = (v - origin) * inv_;
    return !(c > 0) ? 0 : c >= static_cast<double>(n - 1) ? n - 1 : static_cast<std::size_t>(c);
  }
  std::size_t cell_of(Point2 q) const { return ix(q.y, lo_.y, ny_) * nx_ + ix(q.x, lo_.x, nx_); }
  std::span<const Point2> p_;
  Point2 lo_{0, 0};
  double inv_ = 0;
  std::size_t nx_ = 0, ny_ = 0;
  std::vector<std::uint32_t> start_, items_;
};

}  // namespace fdr
