// The start of Functional Delaunay Refinement in 3D: which tetrahedra are B-bad (circumradius
// over the spacing at the circumcentre, R / f(c), above the bound B) and the order in which
// refinement splits them (largest R / f(c) first).
#pragma once
#include <array>
#include <functional>
#include <vector>
#include "base/point3.hpp"
#include "tet/delaunay3.hpp"

namespace fdr::tet {

// The spacing function f: a positive length at every point of the domain.
using Spacing3 = std::function<double(Point3)>;

// A finite tetrahedron's circumcentre and R / f(c).
struct SizeRatio {
  Point3 centre;
  double ratio = 0;
};
SizeRatio size_ratio(const Delaunay3& dt, TetId t, const Spacing3& f);

// True when the tetrahedron is B-bad: R / f(c) > B.
inline bool is_bad(const SizeRatio& s, double bound) { return s.ratio > bound; }

// A B-bad tetrahedron waiting to be split, with the vertices it had when queued (its slot may be
// reused by the time it is taken out).
struct BadTet {
  double ratio = 0;
  TetId tet = kNoId;
  std::array<VertexId, 4> v{};
  Point3 centre;
};

// The B-bad tetrahedra by decreasing R / f(c), ties by their vertex ids, so that the order does not
// depend on where tetrahedra are stored. The order is exact: with the radius-edge bound of 2 asked
// for besides R / f(c) <= B (which the paper's termination proof does not cover), a cheaper order
// that splits the newest of nearly equal ratios first can run away. Entries
// whose tetrahedron was destroyed meanwhile are dropped when they come up.
// Kept cheap without changing the order: the ratios are cut into ranges on a log scale
// (kBucketsPerOctave per factor of two) and the top range is emptied first. A range below the top
// only collects its entries (an append, no heap to sift through memory); when it becomes the top it
// is sorted once and taken from its end, and entries that arrive while it is sorted wait in a small
// heap beside it, the larger of the two heads coming out first. Equal ratios share a range, so the
// order is the one a single heap would give.
class BadTetQueue {
 public:
  explicit BadTetQueue(double bound) : bound_(bound) {}
  // Queues t when it is finite and B-bad; returns whether it was queued.
  bool offer(const Delaunay3& dt, TetId t, const Spacing3& f);
  // Queues an entry measured by the caller (e.g. bad by another test than R / f(c)).
  void push(const BadTet& b);
  // The worst tetrahedron still in dt, or false when none is left. Its centre is
  // computed again from its vertices (the same value as when it was queued).
  bool pop(const Delaunay3& dt, BadTet* out);
  std::size_t size() const { return size_; }
  double bound() const { return bound_; }

  static constexpr int kBucketsPerOctave = 64;
  // The range of a ratio: non-decreasing in the ratio; NaN and infinity go to the top one.
  static int bucket(double ratio);

 private:
  // A queued tetrahedron without its centre (half the bytes of a BadTet: the heap is the largest
  // array of the refinement after the tetrahedra).
  struct Entry {
    double ratio;
    TetId tet;
    std::array<VertexId, 4> v;
  };
  struct Below {
    bool operator()(const Entry& a, const Entry& b) const;
  };
  struct Bucket {
    std::vector<Entry> items;  // unsorted, or (sorted) ascending by Below, taken from the back
    std::vector<Entry> late;   // a heap by Below: entries pushed while the range was sorted
    bool sorted = false;
  };
  double bound_;
  std::vector<Bucket> buckets_;
  int top_ = -1;  // no range above it holds an entry
  std::size_t size_ = 0;
};

}  // namespace fdr::tet
