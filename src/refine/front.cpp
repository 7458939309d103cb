// Front bookkeeping of frontal refinement (see front.hpp).
#include "refine/front.hpp"
#include <algorithm>
#include <cmath>

namespace fdr::refine {

void Front::set_key(TriangleId t, double key) {
  if (t >= key_.size()) key_.resize(std::max<std::size_t>(t + 1, key_.size() + key_.size() / 2), 0.0f);
  // A bad key stays positive as a float (FLT_MIN at least), an overflowing one finite.
  float k = key > 0 ? static_cast<float>(std::min(key, 1e38)) : 0.0f;
  if (key > 0 && !(k > 0)) k = 1e-38f;
  key_[t] = k;
}

bool Front::front_edge(const mesh::Triangulation& T, HalfEdge h) const {
  if (T.constrained(h)) return true;
  const HalfEdge w = T.twin(h);
  if (w == kNoId) return true;
  const TriangleId n = mesh::tri_of(w);
  return !T.dead(n) && !bad(n);
}

bool Front::has_front_edge(const mesh::Triangulation& T, TriangleId t) const {
  for (Index k = 0; k < 3; ++k)
    if (front_edge(T, 3 * t + k)) return true;
  return false;
}

int Front::bucket_of(double key) {
  if (!(key < 0x1p64)) return kSub * kDoublings - 1;
  int e;
  const double m = std::frexp(key, &e);  // key = m 2^e, m in [0.5, 1), e >= 1 for a bad key
  const int i = (e - 1) * kSub + static_cast<int>((2 * m - 1) * kSub);
  return std::clamp(i, 0, kSub * kDoublings - 1);
}

void Front::push(const mesh::Triangulation& T, TriangleId t) {
  queue_.push(bucket_of(key(t)), {t, T.corner(t, 2), frame_.code(T.point(T.corner(t, 0)))});
}

bool Front::offer(const mesh::Triangulation& T, TriangleId t) {
  if (!bad(t) || !has_front_edge(T, t)) return false;
  push(T, t);
  return true;
}

void Front::note_new(const mesh::Triangulation& T, const std::vector<TriangleId>& fresh, Index v,
                     std::vector<TriangleId>* off) {
  for (TriangleId t : fresh) {
    if (bad(t)) {
      if (!offer(T, t)) off->push_back(t);
      continue;
    }
    // An accepted new triangle makes its bad neighbours front triangles (the edge they share is a
    // front edge); bad new neighbours are offered in their own turn (each is in `fresh`), so only
    // old ones are queued here (a triangle of a repair flip may be queued twice: the second entry
    // is then stale or waits).
    for (Index k = 0; k < 3; ++k) {
      const HalfEdge h = 3 * t + k;
      if (T.constrained(h) || T.twin(h) == kNoId) continue;
      const TriangleId n = mesh::tri_of(T.twin(h));
      if (bad(n) && T.corner(n, 2) != v) push(T, n);
    }
  }
}

}  // namespace fdr::refine
