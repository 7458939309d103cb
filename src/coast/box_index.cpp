// Which of many boxes meet a query box (box_index.hpp).
#include "coast/box_index.hpp"

#include <algorithm>
#include <cmath>

namespace fdr::coast {

BoxIndex::BoxIndex(const std::vector<OGREnvelope>& boxes) : boxes_(boxes) {
  if (boxes.empty()) return;
  double area = 0;
  for (const OGREnvelope& b : boxes) {
    all_.Merge(b);
    area += (b.MaxX - b.MinX) * (b.MaxY - b.MinY);
  }
  // Cells about the size of a mean box (at least a 1/1024 of the extent): a box lands in a few.
  const double extent = std::max(all_.MaxX - all_.MinX, all_.MaxY - all_.MinY);
  cell_ = std::max({std::sqrt(area / static_cast<double>(boxes.size())), extent / 1024, 1e-300});
  nx_ = std::max(1L, static_cast<long>((all_.MaxX - all_.MinX) / cell_) + 1);
  ny_ = std::max(1L, static_cast<long>((all_.MaxY - all_.MinY) / cell_) + 1);
  cells_.resize(static_cast<std::size_t>(nx_ * ny_));
  for (std::size_t i = 0; i < boxes.size(); ++i)
    for (long y = cell_y(boxes[i].MinY); y <= cell_y(boxes[i].MaxY); ++y)
      for (long x = cell_x(boxes[i].MinX); x <= cell_x(boxes[i].MaxX); ++x)
        cells_[static_cast<std::size_t>(y * nx_ + x)].push_back(i);
}

long BoxIndex::cell_x(double x) const {
  return std::clamp(static_cast<long>(std::floor((x - all_.MinX) / cell_)), 0L, nx_ - 1);
}
long BoxIndex::cell_y(double y) const {
  return std::clamp(static_cast<long>(std::floor((y - all_.MinY) / cell_)), 0L, ny_ - 1);
}

void BoxIndex::near(const OGREnvelope& q, std::vector<std::size_t>* out) const {
  out->clear();
  if (cells_.empty() || !q.Intersects(all_)) return;
  for (long y = cell_y(q.MinY); y <= cell_y(q.MaxY); ++y)
    for (long x = cell_x(q.MinX); x <= cell_x(q.MaxX); ++x)
      for (const std::size_t i : cells_[static_cast<std::size_t>(y * nx_ + x)])
        if (boxes_[i].Intersects(q)) out->push_back(i);
  std::sort(out->begin(), out->end());
  out->erase(std::unique(out->begin(), out->end()), out->end());
}

}  // namespace fdr::coast
