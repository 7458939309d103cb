// Uniform-grid bucketing of segments and points, and the exact segment contact classification
// shared by validate() and clean(); keeps intersection searches near-linear in practice.
#pragma once
#include <cstdint>
#include <vector>
#include "base/types.hpp"

namespace fdr::pslg {

// How two closed, non-degenerate segments ab and cd meet (decided by orient2d only).
enum class Contact {
  kNone,      // disjoint
  kEndpoint,  // they meet only at an endpoint common to both (same coordinates)
  kProper,    // interiors cross at a single point
  kTouch,     // an endpoint of one lies in the interior of the other (not collinear)
  kOverlap,   // collinear and share a stretch of positive length (or are identical)
};
Contact classify(Point2 a, Point2 b, Point2 c, Point2 d);

// True if p lies in the open segment ab (a != b); exact.
bool in_interior(Point2 a, Point2 b, Point2 p);

// Intersection point of two properly crossing segments, rounded, clamped into both bounding boxes.
Point2 crossing_point(Point2 a, Point2 b, Point2 c, Point2 d);

// Fixed grid over a box; cells hold segment ids and point ids. Cells are registered
// conservatively (padded), so every cell that a segment touches lists it; extra entries are
// harmless because every decision is re-made exactly. Cost is linear in the registrations plus
// the pairs per cell: fine for coastlines, quadratic for pathological stars (one vertex of
// degree d costs O(d^2)).
class SegmentGrid {
 public:
  // `box` must contain every geometry added later; `n_items` and `mean_length` size the cells.
  SegmentGrid(Box2 box, std::size_t n_items, double mean_length);

  void add_segment(Index id, Point2 a, Point2 b);
  void add_point(Index id, Point2 p);

  // Calls f(cell) for every cell that segment ab may touch.
  template <class F>
  void for_segment_cells(Point2 a, Point2 b, F&& f) const;
  // Calls f(cell) for every cell overlapping the box.
  template <class F>
  void for_box_cells(Box2 box, F&& f) const;
  std::size_t cell_of(Point2 p) const;

  std::size_t num_cells() const { return segs_.size(); }
  const std::vector<Index>& segments_in(std::size_t cell) const { return segs_[cell]; }
  const std::vector<Index>& points_in(std::size_t cell) const { return pts_.empty() ? kNone : pts_[cell]; }

  // Distinct segment ids near a box (deduplicated with a stamp array sized to max id seen).
  void segments_near(Box2 box, std::vector<Index>* out) const;
  void points_near(Box2 box, std::vector<Index>* out) const;

 private:
  long col(double x) const;
  long row(double y) const;
  double x0_ = 0, y0_ = 0, cs_ = 1, pad_ = 0;
  long nx_ = 1, ny_ = 1;
  std::vector<std::vector<Index>> segs_, pts_;
  mutable std::vector<std::uint32_t> seg_stamp_, pt_stamp_;
  mutable std::uint32_t stamp_ = 0;
  static inline const std::vector<Index> kNone;  // the points of every cell before add_point
};

template <class F>
void SegmentGrid::for_box_cells(Box2 box, F&& f) const {
  const long c0 = col(box.lo.x - pad_), c1 = col(box.hi.x + pad_);
  const long r0 = row(box.lo.y - pad_), r1 = row(box.hi.y + pad_);
  for (long r = r0; r <= r1; ++r)
    for (long c = c0; c <= c1; ++c) f(static_cast<std::size_t>(r * nx_ + c));
}

template <class F>
void SegmentGrid::for_segment_cells(Point2 a, Point2 b, F&& f) const {
  if (a.x > b.x) std::swap(a, b);
  const long c0 = col(a.x - pad_), c1 = col(b.x + pad_);
  const double dx = b.x - a.x, dy = b.y - a.y;
  // Why per column: a long diagonal segment touches O(length/cell) cells, not its whole bbox.
  for (long c = c0; c <= c1; ++c) {
    double xl = std::max(a.x, x0_ + static_cast<double>(c) * cs_);
    double xr = std::min(b.x, x0_ + static_cast<double>(c + 1) * cs_);
    if (c == c0) xl = a.x;
    if (c == c1) xr = b.x;
    double ya, yb;
    if (dx > 0) {
      ya = a.y + (xl - a.x) / dx * dy;
      yb = a.y + (xr - a.x) / dx * dy;
    } else {
      ya = a.y;
      yb = b.y;
    }
    const double lo = std::max(std::min(ya, yb), std::min(a.y, b.y));
    const double hi = std::min(std::max(ya, yb), std::max(a.y, b.y));
    const long r0 = row(lo - pad_), r1 = row(hi + pad_);
    for (long r = r0; r <= r1; ++r) f(static_cast<std::size_t>(r * nx_ + c));
  }
}

}  // namespace fdr::pslg

#include "pslg/pslg.hpp"
namespace fdr::pslg {

// Every bad contact in a segment set: segment pairs (i < j) meeting other than at a common
// endpoint, and points lying in a segment's open interior. Zero-length segments are skipped;
// `point_alive` (optional) masks points out of the vertex test. Results sorted, deterministic.
struct Contacts {
  std::vector<std::pair<Index, Index>> segment_pairs;
  std::vector<Contact> kinds;  // parallel to segment_pairs
  std::vector<std::pair<Index, Index>> vertex_on_segment;  // (point, segment)
};
Contacts find_contacts(const std::vector<Point2>& points, const std::vector<Segment>& segments,
                       const std::vector<char>* point_alive);

}  // namespace fdr::pslg
