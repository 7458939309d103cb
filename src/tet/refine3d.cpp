#include "tet/refine3d.hpp"
#include <algorithm>
#include "tet/tet_geometry.hpp"

namespace fdr::tet {

SizeRatio size_ratio(const Delaunay3& dt, TetId t, const Spacing3& f) {
  const auto& v = dt.vertices(t);
  const Sphere s = circumsphere(dt.point(v[0]), dt.point(v[1]), dt.point(v[2]), dt.point(v[3]));
  return {s.centre, s.radius / f(s.centre)};
}

bool BadTetQueue::Worse::operator()(const BadTet& a, const BadTet& b) const {
  // priority_queue puts the largest first: "a below b" when a's ratio is smaller.
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
  heap_.push({s.ratio, t, dt.vertices(t), s.centre});
  return true;
}

bool BadTetQueue::pop(const Delaunay3& dt, BadTet* out) {
  while (!heap_.empty()) {
    const BadTet b = heap_.top();
    heap_.pop();
    if (dt.alive(b.tet) && dt.vertices(b.tet) == b.v) {
      *out = b;
      return true;
    }
  }
  return false;
}

}  // namespace fdr::tet
