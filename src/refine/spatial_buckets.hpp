// A bucketed priority queue of triangles for the refinement's queues (the largest-R/f(c)-first
// queue and the frontal one): highest bucket first; within a bucket newest first, except that a
// bucket reached by descending is first put in Morton order of its entries' points. Why: entries
// pushed long ago lie all over the domain, and taken in push order they miss the cache at nearly
// every step; taken along a Morton curve, consecutive entries are neighbours in the mesh.
#pragma once
#include <cstdint>
#include <memory>
#include <span>
#include <vector>
#include "base/types.hpp"

namespace fdr::refine {

// Morton codes of points in a square frame (16 bits a coordinate).
struct MortonFrame {
  Point2 lo{0, 0};
  double scale = 0;  // grid cells per unit: 65535 / the frame's side
  // The frame of the points' bounding box.
  static MortonFrame of(std::span<const Point2> pts);
  std::uint32_t code(Point2 p) const;
};

class SpatialBuckets {
 public:
  // t: triangle slot, c: its third corner when queued (identifies the triangle in its slot),
  // z: Morton code of a point of it.
  struct Entry {
    TriangleId t = kNoId;
    Index c = kNoId;
    std::uint32_t z = 0;
  };

  explicit SpatialBuckets(int buckets);
  void push(int bucket, const Entry& e);
  // The next entry (see the file comment); false when the queue is empty.
  bool pop(Entry* e);
  // The entry k places below the top of the bucket the last pop took from (nullptr if none): the
  // caller may fetch what it will touch.
  const Entry* ahead(std::size_t k) const;
  bool empty() const { return size_ == 0; }
  std::size_t size() const { return size_; }

 private:
  // A bucket's entries in chunks of kChunkEntries taken from the queue's pool and given back when
  // the bucket shrinks. Why: grown by doubling, every bucket copied its entries into fresh pages
  // and freed the old ones; a chunk another bucket gave back has its pages.
  static constexpr std::size_t kChunkShift = 10;  // 1 024 entries, 12 KiB
  static constexpr std::size_t kChunkEntries = std::size_t{1} << kChunkShift;
  struct Bucket {
    std::vector<Entry*> chunks;
    std::size_t n = 0;
    std::size_t sorted = 0;  // its first `sorted` entries are in Morton order
    Entry& operator[](std::size_t i) { return chunks[i >> kChunkShift][i & (kChunkEntries - 1)]; }
    const Entry& operator[](std::size_t i) const { return chunks[i >> kChunkShift][i & (kChunkEntries - 1)]; }
    std::size_t size() const { return n; }
  };
  void pop_back(Bucket& b);

  std::vector<Bucket> buckets_;
  std::vector<std::unique_ptr<Entry[]>> chunk_store_;  // every chunk made (freed with the queue)
  std::vector<Entry*> free_chunks_;                    // chunks no bucket holds
  int top_ = -1;
  bool sort_next_ = false;
  std::size_t size_ = 0;
};

// Sorts entries by descending z in place, the sort the queue applies to a bucket (exposed for its
// test): the same input always gives the same order.
void sort_desc_by_z(std::vector<SpatialBuckets::Entry>& v);

}  // namespace fdr::refine
