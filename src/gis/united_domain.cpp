// The united input domain (united_domain.hpp).
#include "gis/united_domain.hpp"

#include <algorithm>
#include <vector>

#include "coast/geometry_ops.hpp"
#include "coast/union.hpp"

namespace fdr::gis {
namespace {

// Whether two polygons share a vertex exactly: adjacent polygons cut from one coverage do
// along their common border. The vertices sorted by position, equal ones side by side.
bool share_a_vertex(const coast::Polygons& input) {
  struct At {
    double x, y;
    std::size_t poly;
  };
  std::vector<At> at;
  for (std::size_t k = 0; k < input.size(); ++k)
    for (const auto& ring : input[k])
      for (const Point2 p : ring) at.push_back({p.x, p.y, k});
  std::sort(at.begin(), at.end(), [](const At& a, const At& b) { return a.x != b.x ? a.x < b.x : a.y < b.y; });
  for (std::size_t i = 1; i < at.size(); ++i)
    if (at[i].x == at[i - 1].x && at[i].y == at[i - 1].y && at[i].poly != at[i - 1].poly) return true;
  return false;
}

}  // namespace

std::optional<coast::Polygons> united_domain(const coast::Polygons& input, bool overlaps) {
  if (input.size() < 2 || !(overlaps || share_a_vertex(input))) return std::nullopt;
  coast::GdalQuiet quiet;
  coast::Result scratch;  // the union's own repairs and figures are the generalisation's to report
  const coast::GeomPtr united = coast::unite(input, scratch);
  coast::OwnedPolygons ps;
  coast::polygons_of(united.get(), ps);
  coast::Polygons out;
  out.reserve(ps.size());
  for (const auto& p : ps) {
    coast::Rings rings;
    rings.push_back(coast::ring_points(p->getExteriorRing(), true));
    for (int i = 0; i < p->getNumInteriorRings(); ++i) rings.push_back(coast::ring_points(p->getInteriorRing(i), false));
    out.push_back(std::move(rings));
  }
  return out;
}

}  // namespace fdr::gis
