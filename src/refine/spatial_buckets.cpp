// The refinement's bucketed queue of triangles in Morton order (see spatial_buckets.hpp).
#include "refine/spatial_buckets.hpp"
#include <algorithm>
#include <type_traits>
#include <utility>

namespace fdr::refine {

namespace {
std::uint32_t spread16(std::uint32_t x) {
  x &= 0xffff;
  x = (x | (x << 8)) & 0x00ff00ffu;
  x = (x | (x << 4)) & 0x0f0f0f0fu;
  x = (x | (x << 2)) & 0x33333333u;
  x = (x | (x << 1)) & 0x55555555u;
  return x;
}

// In-place MSD radix sort by descending z of the entries [lo, hi) (American flag sort, 8 bits a
// level; ranges under 64 entries by std::sort). Deterministic: the same input always gives the
// same order. In place: no second buffer at the memory peak.
template <class B>
void radix_desc(B& b, std::size_t lo, std::size_t hi, int shift) {
  using E = std::remove_cvref_t<decltype(b[lo])>;
  const std::size_t n = hi - lo;
  if (n < 64) {  // (shift stays >= 0: the recursion ends with the last byte)
    E tmp[64];
    for (std::size_t i = 0; i < n; ++i) tmp[i] = b[lo + i];
    std::sort(tmp, tmp + n, [](const E& x, const E& y) { return x.z > y.z; });
    for (std::size_t i = 0; i < n; ++i) b[lo + i] = tmp[i];
    return;
  }
  std::size_t count[256] = {}, start[256], next[256];
  auto digit = [shift](const E& e) { return 255u - ((e.z >> shift) & 255u); };
  for (std::size_t p = lo; p != hi; ++p) ++count[digit(b[p])];
  std::size_t sum = lo;
  for (int d = 0; d < 256; ++d) {
    start[d] = next[d] = sum;
    sum += count[d];
  }
  for (int d = 0; d < 256; ++d) {
    const std::size_t end = start[d] + count[d];
    while (next[d] < end) {
      E e = b[next[d]];
      unsigned g = digit(e);
      while (g != static_cast<unsigned>(d)) {  // each swap puts one entry in its final bin
        std::swap(e, b[next[g]++]);
        g = digit(e);
      }
      b[next[d]++] = e;
    }
  }
  if (shift == 0) return;
  for (int d = 0; d < 256; ++d)
    if (count[d] > 1) radix_desc(b, start[d], start[d] + count[d], shift - 8);
}
}  // namespace

MortonFrame MortonFrame::of(std::span<const Point2> pts) {
  MortonFrame fr;
  if (pts.empty()) return fr;
  Point2 lo = pts[0], hi = pts[0];
  for (const Point2& q : pts) {
    lo.x = std::min(lo.x, q.x);
    lo.y = std::min(lo.y, q.y);
    hi.x = std::max(hi.x, q.x);
    hi.y = std::max(hi.y, q.y);
  }
  fr.lo = lo;
  const double w = std::max(hi.x - lo.x, hi.y - lo.y);
  fr.scale = w > 0 ? 65535.0 / w : 0.0;
  return fr;
}

std::uint32_t MortonFrame::code(Point2 p) const {
  const double gx = std::clamp((p.x - lo.x) * scale, 0.0, 65535.0);
  const double gy = std::clamp((p.y - lo.y) * scale, 0.0, 65535.0);
  return spread16(static_cast<std::uint32_t>(gx)) | (spread16(static_cast<std::uint32_t>(gy)) << 1);
}

void sort_desc_by_z(std::vector<SpatialBuckets::Entry>& v) { radix_desc(v, 0, v.size(), 24); }

SpatialBuckets::SpatialBuckets(int buckets) : buckets_(static_cast<std::size_t>(buckets)) {}

void SpatialBuckets::push(int bucket, const Entry& e) {
  Bucket& b = buckets_[static_cast<std::size_t>(bucket)];
  if (b.n == b.chunks.size() << kChunkShift) {
    if (free_chunks_.empty()) {
      chunk_store_.emplace_back(new Entry[kChunkEntries]);
      free_chunks_.push_back(chunk_store_.back().get());
    }
    b.chunks.push_back(free_chunks_.back());
    free_chunks_.pop_back();
  }
  b[b.n++] = e;
  ++size_;
  if (bucket > top_) top_ = bucket;
}

void SpatialBuckets::pop_back(Bucket& b) {
  --b.n;
  --size_;
  if (b.sorted > b.n) b.sorted = b.n;
  // A chunk goes back once the bucket is a whole chunk below it (one chunk of slack: a bucket
  // that grows and shrinks across a chunk boundary does not trade it every time).
  if (b.chunks.size() >= 2 && b.n + 2 * kChunkEntries <= b.chunks.size() << kChunkShift) {
    free_chunks_.push_back(b.chunks.back());
    b.chunks.pop_back();
  }
}

bool SpatialBuckets::pop(Entry* e) {
  while (top_ >= 0 && buckets_[static_cast<std::size_t>(top_)].n == 0) {
    --top_;
    sort_next_ = true;
  }
  if (top_ < 0) return false;
  Bucket& b = buckets_[static_cast<std::size_t>(top_)];
  if (sort_next_) {
    // Why only when the unsorted tail is at least as long as the sorted part: the queue can climb
    // to a higher bucket and come back many times; sorting the whole bucket each time would be
    // quadratic. This way each entry is sorted O(1) times.
    if (b.n - b.sorted >= b.sorted) {
      radix_desc(b, 0, b.n, 24);
      b.sorted = b.n;
    }
    sort_next_ = false;
  }
  *e = b[b.n - 1];
  pop_back(b);
  return true;
}

const SpatialBuckets::Entry* SpatialBuckets::ahead(std::size_t k) const {
  if (top_ < 0) return nullptr;
  const Bucket& b = buckets_[static_cast<std::size_t>(top_)];
  return b.n >= k ? &b[b.n - k] : nullptr;
}

}  // namespace fdr::refine
