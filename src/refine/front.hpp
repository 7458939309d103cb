// The front of frontal refinement: which triangles are accepted (good) and which bad triangles
// border an accepted triangle or the domain's boundary (an edge on a constraint), taken largest
// badness first. Why: a point placed next to accepted triangles makes the new triangle on that
// edge the size the front asks for, so the vertices grow in rows from the boundary inwards.
#pragma once
#include <cstdint>
#include <vector>
#include "mesh/triangulation.hpp"

namespace fdr::refine {

class Front {
 public:
  struct Entry {
    TriangleId t = kNoId;
    Index c = kNoId;  // its third corner when queued (identifies the triangle in its slot)
  };

  // Records the badness key of the triangle in slot t (0: accepted; bad keys are > 1).
  void set_key(TriangleId t, double key);
  bool bad(TriangleId t) const { return t < key_.size() && key_[t] > 0; }
  double key(TriangleId t) const { return t < key_.size() ? key_[t] : 0.0; }
  // Whether half-edge h of a live triangle is a front edge: on a constraint or the domain's
  // boundary, or shared with an accepted triangle.
  bool front_edge(const mesh::Triangulation& T, HalfEdge h) const;
  bool has_front_edge(const mesh::Triangulation& T, TriangleId t) const;
  // Queues t if it is bad and has a front edge.
  void offer(const mesh::Triangulation& T, TriangleId t);
  // After an insertion (the keys of `fresh` already set): queues the bad new triangles on the
  // front and the bad old triangles that an accepted new triangle borders. v: the new vertex
  // (the third corner of each new triangle of the fan).
  void note_new(const mesh::Triangulation& T, const std::vector<TriangleId>& fresh, Index v);
  // The next entry, largest key first (by buckets of kSub per doubling of the key; newest first
  // within one, which keeps consecutive entries near each other). It may be stale: the caller
  // checks the slot still holds that triangle.
  bool pop(Entry* e);
  bool empty() const { return size_ == 0; }
  std::size_t size() const { return size_; }

  static constexpr int kSub = 8;
  static constexpr int kDoublings = 64;  // keys from 2^64 up share the top bucket
  static int bucket_of(double key);

 private:
  std::vector<float> key_;  // per slot
  std::vector<std::vector<Entry>> buckets_ = std::vector<std::vector<Entry>>(kSub * kDoublings);
  int top_ = -1;
  std::size_t size_ = 0;
};

}  // namespace fdr::refine
