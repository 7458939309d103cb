// The front of frontal refinement: which triangles are accepted (good) and which bad triangles
// border an accepted triangle or the domain's boundary (an edge on a constraint), taken in order.
// Why: a point placed next to accepted triangles makes the new triangle on that edge the size
// the front asks for, so the vertices grow in rows from the boundary inwards.
#pragma once
#include <cstdint>
#include <queue>
#include <vector>
#include "mesh/triangulation.hpp"

namespace fdr::refine {

class Front {
 public:
  enum class Order { kLargestFirst, kOldestFirst };
  struct Entry {
    float key = 0;        // the triangle's badness when pushed (kLargestFirst)
    std::uint64_t seq = 0;  // push order: ties (and kOldestFirst) go oldest first
    TriangleId t = kNoId;
    Index c = kNoId;  // its third corner when pushed (identifies the triangle in its slot)
  };

  explicit Front(Order order = Order::kLargestFirst) : order_(order) {}
  // Records the badness key of the triangle in slot t (0: accepted).
  void set_key(TriangleId t, double key);
  bool bad(TriangleId t) const { return t < key_.size() && key_[t] > 0; }
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
  // The next entry (possibly stale: the caller checks the slot still holds that triangle).
  bool pop(Entry* e);
  bool empty() const { return heap_.empty(); }
  std::size_t size() const { return heap_.size(); }

 private:
  struct Later {
    Order order;
    bool operator()(const Entry& a, const Entry& b) const {
      if (order == Order::kLargestFirst && a.key != b.key) return a.key < b.key;
      return a.seq > b.seq;
    }
  };
  Order order_;
  std::vector<float> key_;  // per slot
  std::uint64_t seq_ = 0;
  std::priority_queue<Entry, std::vector<Entry>, Later> heap_{Later{order_}};
};

}  // namespace fdr::refine
