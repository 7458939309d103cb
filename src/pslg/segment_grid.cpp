// Uniform grid for segment/point proximity queries and the exact contact classification.
#include "pslg/segment_grid.hpp"
#include <cmath>
#include "predicates/predicates.hpp"

namespace fdr::pslg {

using predicates::orient2d;

bool in_interior(Point2 a, Point2 b, Point2 p) {
  // Outside the segment's box (exact comparisons): not inside it, whatever the orientation.
  if (p.x < std::min(a.x, b.x) || p.x > std::max(a.x, b.x) || p.y < std::min(a.y, b.y) || p.y > std::max(a.y, b.y))
    return false;
  if (orient2d(a, b, p) != 0) return false;
  // Collinear: compare along an axis on which the segment is not degenerate (exact comparisons).
  if (a.x != b.x) return (a.x < p.x && p.x < b.x) || (b.x < p.x && p.x < a.x);
  return (a.y < p.y && p.y < b.y) || (b.y < p.y && p.y < a.y);
}

Contact classify(Point2 a, Point2 b, Point2 c, Point2 d) {
  // Cheap bounding-box rejection (exact comparisons, no arithmetic).
  if (std::max(a.x, b.x) < std::min(c.x, d.x) || std::max(c.x, d.x) < std::min(a.x, b.x) ||
      std::max(a.y, b.y) < std::min(c.y, d.y) || std::max(c.y, d.y) < std::min(a.y, b.y))
    return Contact::kNone;
  // Segments sharing one endpoint s (neighbours along a chain, the common case): s-u and s-v
  // overlap when collinear and u, v lie on the same side of s, and merely meet otherwise. One
  // orientation decides, and never the degenerate orient2d(a, b, b) that the filter cannot.
  if (a != b && c != d && !((a == c && b == d) || (a == d && b == c))) {
    const bool ac = a == c, ad = a == d, bc = b == c, bd = b == d;
    if (ac || ad || bc || bd) {
      const Point2 s = ac || ad ? a : b, u = ac || ad ? b : a, v = ac || bc ? d : c;
      if (orient2d(s, u, v) != 0) return Contact::kEndpoint;
      const bool same = u.x != s.x ? ((u.x > s.x) == (v.x > s.x)) : ((u.y > s.y) == (v.y > s.y));
      return same ? Contact::kOverlap : Contact::kEndpoint;
    }
  }
  const int o1 = orient2d(a, b, c), o2 = orient2d(a, b, d);
  if (o1 == 0 && o2 == 0) {
    // Collinear: identical, or one endpoint strictly inside the other means a shared stretch.
    if ((a == c && b == d) || (a == d && b == c)) return Contact::kOverlap;
    if (in_interior(a, b, c) || in_interior(a, b, d) || in_interior(c, d, a) || in_interior(c, d, b))
      return Contact::kOverlap;
    if (a == c || a == d || b == c || b == d) return Contact::kEndpoint;
    return Contact::kNone;
  }
  if (o1 * o2 > 0) return Contact::kNone;
  const int o3 = orient2d(c, d, a), o4 = orient2d(c, d, b);
  if (o3 * o4 > 0) return Contact::kNone;
  if (o1 != 0 && o2 != 0 && o3 != 0 && o4 != 0) return Contact::kProper;
  // Exactly one orientation is zero here: an endpoint lies on the other segment's line,
  // and the sign pattern puts it within that segment (closed). Endpoint shared or interior?
  if (a == c || a == d || b == c || b == d) return Contact::kEndpoint;
  return Contact::kTouch;
}

Point2 crossing_point(Point2 a, Point2 b, Point2 c, Point2 d) {
  // The exact intersection rounded to the nearest doubles: the best a double can do, so the
  // cut point moves each segment by at most half an ulp per coordinate.
  Point2 p;
  if (!predicates::line_intersection_rounded(a, b, c, d, &p)) {
    const Point2 r = b - a;
    p = {a.x + 0.5 * r.x, a.y + 0.5 * r.y};
  }
  // Keep the rounded point inside both bounding boxes so it never lands far from the crossing.
  const double lx = std::max(std::min(a.x, b.x), std::min(c.x, d.x));
  const double hx = std::min(std::max(a.x, b.x), std::max(c.x, d.x));
  const double ly = std::max(std::min(a.y, b.y), std::min(c.y, d.y));
  const double hy = std::min(std::max(a.y, b.y), std::max(c.y, d.y));
  if (lx <= hx) p.x = std::clamp(p.x, lx, hx);
  if (ly <= hy) p.y = std::clamp(p.y, ly, hy);
  return p;
}

SegmentGrid::SegmentGrid(Box2 box, std::size_t n_items, double mean_length) {
  if (box.empty()) box.add({0, 0});
  x0_ = box.lo.x;
  y0_ = box.lo.y;
  const double w = box.width(), h = box.height();
  const double n = static_cast<double>(std::max<std::size_t>(n_items, 1));
  // Cells about one mean segment long, but never more than ~2n cells in total.
  double cs = mean_length > 0 && std::isfinite(mean_length) ? mean_length : 0;
  const double min_cs = std::sqrt(w * h / (2.0 * n));
  cs = std::max(cs, min_cs);
  cs = std::max(cs, std::max(w, h) / (2.0 * n + 1.0));
  if (!(cs > 0) || !std::isfinite(cs)) cs = 1;
  cs_ = cs;
  nx_ = std::min<long>(static_cast<long>(w / cs) + 1, 1L << 20);
  ny_ = std::min<long>(static_cast<long>(h / cs) + 1, 1L << 20);
  while (static_cast<double>(nx_) * static_cast<double>(ny_) > 4.0 * n + 64.0) {
    cs_ *= 1.5;
    nx_ = static_cast<long>(w / cs_) + 1;
    ny_ = static_cast<long>(h / cs_) + 1;
  }
  const double mag = std::max({std::fabs(box.lo.x), std::fabs(box.hi.x), std::fabs(box.lo.y),
                               std::fabs(box.hi.y)});
  pad_ = 1e-7 * cs_ + 1e-13 * mag;
  // Point cells are made by the first add_point: many grids hold segments only.
  segs_.resize(static_cast<std::size_t>(nx_ * ny_));
}

long SegmentGrid::col(double x) const {
  const double c = std::floor((x - x0_) / cs_);
  if (!(c > 0)) return 0;
  return c >= static_cast<double>(nx_ - 1) ? nx_ - 1 : static_cast<long>(c);
}
long SegmentGrid::row(double y) const {
  const double r = std::floor((y - y0_) / cs_);
  if (!(r > 0)) return 0;
  return r >= static_cast<double>(ny_ - 1) ? ny_ - 1 : static_cast<long>(r);
}

std::size_t SegmentGrid::cell_of(Point2 p) const {
  return static_cast<std::size_t>(row(p.y) * nx_ + col(p.x));
}

void SegmentGrid::add_segment(Index id, Point2 a, Point2 b) {
  for_segment_cells(a, b, [&](std::size_t c) { segs_[c].push_back(id); });
  if (id >= seg_stamp_.size()) seg_stamp_.resize(static_cast<std::size_t>(id) + 1, 0);
}

void SegmentGrid::add_point(Index id, Point2 p) {
  if (pts_.empty()) pts_.resize(segs_.size());
  pts_[cell_of(p)].push_back(id);
  if (id >= pt_stamp_.size()) pt_stamp_.resize(static_cast<std::size_t>(id) + 1, 0);
}

void SegmentGrid::segments_near(Box2 box, std::vector<Index>* out) const {
  out->clear();
  ++stamp_;
  for_box_cells(box, [&](std::size_t c) {
    for (Index s : segs_[c])
      if (seg_stamp_[s] != stamp_) {
        seg_stamp_[s] = stamp_;
        out->push_back(s);
      }
  });
}

void SegmentGrid::points_near(Box2 box, std::vector<Index>* out) const {
  out->clear();
  if (pts_.empty()) return;
  for_box_cells(box, [&](std::size_t c) {
    for (Index p : pts_[c]) out->push_back(p);  // a point lives in exactly one cell
  });
}

}  // namespace fdr::pslg
