#include "tet/refine3d.hpp"
#include <algorithm>
#include "tet/tet_geometry.hpp"

namespace fdr::tet {

SizeRatio size_ratio(const Delaunay3& dt, TetId t, const Spacing3& f) {
  const auto& v = dt.vertices(t);
  const Sphere s = circumsphere(dt.point(v[0]), dt.point(v[1]), dt.point(v[2]), dt.point(v[3]));
  return {s.centre, s.radius / f(s.centre)};
}

void BadTetQueue::push(const BadTet& b) {
  heap_.push_back({b.ratio, b.tet, b.v});
  std::push_heap(heap_.begin(), heap_.end(), Below{});
}

bool BadTetQueue::Below::operator()(const Entry& a, const Entry& b) const {
  if (a.ratio != b.ratio) return a.ratio < b.ratio;
  auto sa = a.v, sb = b.v;
  std::sort(sa.begin(), sa.end());
  std::sort(sb.begin(), sb.end());
  return sa > sb;
}

bool BadTetQueue::offer(const Delaunay3& dt, TetId t, const Spacing3& f) {
  if (!dt.alive(t) || dt.is_ghost(t)) return false;
  const SizeRatio s = size_ratio(dt, t, f);
  if (!is_bad(s, bound_)) return false;
  push({s.ratio, t, dt.vertices(t), s.centre});
  return true;
}

bool BadTetQueue::pop(const Delaunay3& dt, BadTet* out) {
  while (!heap_.empty()) {
    std::pop_heap(heap_.begin(), heap_.end(), Below{});
    const Entry e = heap_.back();
    heap_.pop_back();
    if (!dt.alive(e.tet) || dt.vertices(e.tet) != e.v) continue;
    const auto& v = e.v;
    *out = {e.ratio, e.tet, v, circumsphere(dt.point(v[0]), dt.point(v[1]), dt.point(v[2]), dt.point(v[3])).centre};
    return true;
  }
  return false;
}

}  // namespace fdr::tet
