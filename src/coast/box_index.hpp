// Which of many boxes meet a query box: the pieces near each hole (ring_union.hpp), the rings of
// a polygon near a small one (minus_disjoint).
#pragma once
#include <cstddef>
#include <vector>

#include <ogr_geometry.h>

namespace fdr::coast {

// The indices of the boxes of `boxes` (kept by reference) that meet `query` (closed boxes),
// increasing, by a uniform grid built once.
class BoxIndex {
 public:
  explicit BoxIndex(const std::vector<OGREnvelope>& boxes);
  void near(const OGREnvelope& query, std::vector<std::size_t>* out) const;

 private:
  long cell_x(double x) const;
  long cell_y(double y) const;
  const std::vector<OGREnvelope>& boxes_;
  OGREnvelope all_;
  double cell_ = 1;
  long nx_ = 1, ny_ = 1;
  std::vector<std::vector<std::size_t>> cells_;
};

}  // namespace fdr::coast
