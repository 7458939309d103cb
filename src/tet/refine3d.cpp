#include "tet/refine3d.hpp"
#include "base/prefetch.hpp"
#include <algorithm>
#include <cmath>
#include <limits>
#include "tet/tet_geometry.hpp"

namespace fdr::tet {

SizeRatio size_ratio(const Delaunay3& dt, TetId t, const Spacing3& f) {
  const auto& v = dt.vertices(t);
  const Sphere s = circumsphere(dt.point(v[0]), dt.point(v[1]), dt.point(v[2]), dt.point(v[3]));
  return {s.centre, s.radius / f(s.centre)};
}

int BadTetQueue::bucket(double ratio) {
  // ratio = m 2^e with m in [0.5, 1): the octave from e, the range inside it from m.
  constexpr int kMinExp = -64, kMaxExp = 64;
  constexpr int kTop = (kMaxExp - kMinExp + 1) * kBucketsPerOctave;
  if (!(ratio < std::numeric_limits<double>::infinity())) return kTop;
  if (!(ratio > 0)) return 0;
  int e = 0;
  const double m = std::frexp(ratio, &e);
  if (e < kMinExp) return 0;
  if (e > kMaxExp) return kTop - 1;
  const int sub = std::min(kBucketsPerOctave - 1, static_cast<int>((m - 0.5) * 2 * kBucketsPerOctave));
  return (e - kMinExp) * kBucketsPerOctave + sub;
}

void BadTetQueue::push(const BadTet& b) {
  const int k = bucket(b.ratio);
  if (static_cast<std::size_t>(k) >= buckets_.size()) buckets_.resize(static_cast<std::size_t>(k) + 1);
  Bucket& r = buckets_[static_cast<std::size_t>(k)];
  if (r.sorted) {
    r.late.push_back({b.ratio, b.tet, b.v});
    std::push_heap(r.late.begin(), r.late.end(), Below{});
  } else {
    r.items.push_back({b.ratio, b.tet, b.v});
  }
  top_ = std::max(top_, k);
  ++size_;
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
  for (; top_ >= 0; --top_) {
    Bucket& r = buckets_[static_cast<std::size_t>(top_)];
    if (!r.sorted) {
      std::sort(r.items.begin(), r.items.end(), Below{});
      r.sorted = true;
    }
    while (!r.items.empty() || !r.late.empty()) {
      Entry e;
      if (r.late.empty() || (!r.items.empty() && Below{}(r.late.front(), r.items.back()))) {
        e = r.items.back();
        r.items.pop_back();
      } else {
        std::pop_heap(r.late.begin(), r.late.end(), Below{});
        e = r.late.back();
        r.late.pop_back();
      }
      --size_;
      // The next entry's tetrahedron lies anywhere in the array: have it fetched now, so that
      // its staleness test does not wait for memory.
      if (!r.items.empty()) fdr::prefetch(&dt.vertices(r.items.back().tet));
      if (!r.late.empty()) fdr::prefetch(&dt.vertices(r.late.front().tet));
      if (!dt.alive(e.tet) || dt.vertices(e.tet) != e.v) continue;
      const auto& v = e.v;
      *out = {e.ratio, e.tet, v, circumsphere(dt.point(v[0]), dt.point(v[1]), dt.point(v[2]), dt.point(v[3])).centre};
      return true;
    }
    // An emptied range gives its memory back and collects unsorted again.
    std::vector<Entry>().swap(r.items);
    std::vector<Entry>().swap(r.late);
    r.sorted = false;
  }
  return false;
}

}  // namespace fdr::tet
