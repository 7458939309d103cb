// The front of frontal refinement: which triangles are accepted (good) and which bad triangles
// border an accepted triangle or the domain's boundary (an edge on a constraint), taken largest
// badness first. Why: a point placed next to accepted triangles makes the new triangle on that
// edge the size the front asks for, so the vertices grow in rows from the boundary inwards.
#pragma once
#include <cmath>
#include <cstdint>
#include <vector>
#include "base/large_array.hpp"
#include "mesh/triangulation.hpp"
#include "refine/spatial_buckets.hpp"

namespace fdr::refine {

class Front {
 public:
  using Entry = SpatialBuckets::Entry;  // t, its third corner c when queued, a Morton code

  // frame: where the queue's Morton codes are taken (see SpatialBuckets).
  explicit Front(MortonFrame frame = {}) : frame_(frame) {}
  // Room for this many triangle slots.
  void reserve(std::size_t slots) { key_.reserve(slots); }
  // Records the badness key of the triangle in slot t (0: accepted; bad keys are > 1).
  void set_key(TriangleId t, double key);
  bool bad(TriangleId t) const { return t < key_.size() && key_[t] != 0; }
  double key(TriangleId t) const { return t < key_.size() ? std::fabs(key_[t]) : 0.0; }
  // Marks a bad triangle that refinement leaves as it is (bad only by an angle the rules exempt,
  // or no usable split point): it stays bad for the front (its edges are no front edges), and
  // its bad neighbours off the front are the refiner's to queue. Offered again, it is retried.
  void drop(TriangleId t) { key_[t] = -std::fabs(key_[t]); }
  bool dropped(TriangleId t) const { return t < key_.size() && key_[t] < 0; }
  // Whether half-edge h of a live triangle is a front edge: on a constraint or the domain's
  // boundary, or shared with an accepted triangle.
  bool front_edge(const mesh::Triangulation& T, HalfEdge h) const;
  bool has_front_edge(const mesh::Triangulation& T, TriangleId t) const;
  // Queues t if it is bad and has a front edge; returns whether it did.
  bool offer(const mesh::Triangulation& T, TriangleId t);
  // After an insertion (the keys of `fresh` already set): queues the bad new triangles on the
  // front and the bad old triangles that an accepted new triangle borders. v: the new vertex
  // (the third corner of each new triangle of the fan). Appends to *off the bad new triangles
  // it did not queue (no front edge).
  void note_new(const mesh::Triangulation& T, const std::vector<TriangleId>& fresh, Index v,
                std::vector<TriangleId>* off);
  // The next entry, largest key first (by buckets of kSub per doubling of the key; within one
  // newest first, and in Morton order when the queue descends to it). It may be stale: the
  // caller checks the slot still holds that triangle.
  bool pop(Entry* e) { return queue_.pop(e); }
  // The entry k places below the next (nullptr if none), to fetch what it will touch.
  const Entry* ahead(std::size_t k) const { return queue_.ahead(k); }
  bool empty() const { return queue_.empty(); }
  std::size_t size() const { return queue_.size(); }

  static constexpr int kSub = 8;
  static constexpr int kDoublings = 64;  // keys from 2^64 up share the top bucket
  static int bucket_of(double key);

 private:
  void push(const mesh::Triangulation& T, TriangleId t);

  LargeArray<float> key_;  // per slot; negative: dropped (see drop())
  MortonFrame frame_;
  SpatialBuckets queue_{kSub * kDoublings};
};

}  // namespace fdr::refine
