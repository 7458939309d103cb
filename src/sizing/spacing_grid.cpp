// Spacing grid geometry (see spacing_grid.hpp).
#include "sizing/spacing_grid.hpp"
#include <algorithm>
#include <cmath>

namespace fdr::sizing {

Box2 spacing_box(const Box2& domain_bbox) {
  Box2 box = domain_bbox;
  const double margin = 0.02 * std::hypot(box.width(), box.height());
  box.add({box.lo.x - margin, box.lo.y - margin});
  box.add({box.hi.x + margin, box.hi.y + margin});
  return box;
}

double spacing_grid_cell(const Box2& box, double hmin) {
  return std::max(hmin, std::sqrt(box.width() * box.height() / 4e6));
}

Grid spacing_grid(const Box2& box, double cell) {
  Grid like;
  like.nx = static_cast<std::size_t>(std::ceil(box.width() / cell)) + 2;
  like.ny = static_cast<std::size_t>(std::ceil(box.height() / cell)) + 2;
  like.x0 = box.lo.x - cell;
  like.y0 = box.lo.y - cell;
  like.dx = like.dy = cell;
  like.v.assign(like.nx * like.ny, 0.0);
  return like;
}

}  // namespace fdr::sizing
