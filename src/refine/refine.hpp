// Functional Delaunay Refinement (FDR): split B-bad triangles (R/f(c) > B) at their circumcenters,
// largest R/f(c) first (buckets; four per doubling of (R/f)^2 just above the bound, taken in Morton
// order when descending to them), encroached subsegments first, with concentric-shell segment splitting.
#pragma once
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>
#include "base/progress.hpp"
#include "cdt/insert.hpp"
#include "mesh/triangulation.hpp"
#include "refine/front.hpp"
#include "refine/spatial_buckets.hpp"
#include "sizing/sizing_field.hpp"

namespace fdr::refine {

struct RefineOptions {
  double bound = 1.0;          // B: a triangle is bad when R / f(c) > B
  double min_angle_deg = 0.0;  // optional extra bound (like Triangle -q); 0 disables
  // Triangles bad only by min_angle_deg split at Ungor's off-center when it is nearer than the
  // circumcenter (as Triangle does); false: always the circumcenter.
  bool off_centers = true;
  // A triangle bad only by min_angle_deg whose split point encroaches a subsegment splits it only
  // if both halves are at least angle_split_min_f times f at the split point; else it is left
  // (counted as exempt). 0: always split (Triangle's -q). Why: near narrow water the angle bound
  // alone would split the banks to a fraction of f, and the smallest element sets a model's time
  // step; the GIS pipeline uses 0.5. R/f(c)-bad triangles always split.
  double angle_split_min_f = 0.0;
  // ... except for triangles with an angle under this (they split as Triangle would): the rule
  // trades angles between this and min_angle_deg for edges, never worse ones.
  double angle_split_floor_deg = 20.0;
  // Frontal point placement (Rebay's frontal Delaunay): an R/f(c)-bad triangle that borders an
  // accepted triangle or a boundary segment (the front) is split on the bisector of that edge
  // where the triangle made on it has circumradius frontal_radius * B * f (equilateral-ish), inside
  // the bad triangle's circumcircle; the point is used only when no vertex is nearer to it than
  // B * f there (what a circumcentre insertion has, so the termination and size proofs hold as
  // they are); else the circumcentre. Bad triangles off the front wait; with no front triangle
  // left, the circumcentre rule goes on in largest-R/f order. Why: the vertex set it makes is
  // more regular (better mean quality), which smoothing cannot reach from circumcentres alone.
  bool frontal = false;
  double frontal_radius = 0.75;
  // Cap on inserted Steiner points; reaching it ends in Error(kWorkLimit). Documented default.
  std::uint64_t max_steiner = 20'000'000;
  // Triangle .poly area constraints: per Pslg::regions index the largest triangle area (<= 0:
  // none); a triangle of Triangulation::region r with a larger area is bad too.
  std::vector<double> region_max_area;
  ProgressFn progress;              // called every few thousand insertions (may cancel)
  double expected_steiner = 0;      // for progress fractions (0: unknown)
};

struct RefineStats {
  std::uint64_t segment_splits = 0;        // Steiner points on segments (midpoints or shells)
  std::uint64_t circumcenters = 0;         // interior Steiner points (circumcenters, off-centers, frontal points)
  std::uint64_t frontal_points = 0;        // of those, frontal points (RefineOptions::frontal)
  std::uint64_t frontal_fallbacks = 0;     // front triangles split at their circumcenter instead
  std::uint64_t rejected_circumcenters = 0;  // circumcenters that would encroach a subsegment
  std::uint64_t exempt_small_angle = 0;    // angle-bad triangles left alone: small input angle
  std::uint64_t stuck = 0;                 // bad triangles whose circumcenter could not be placed
  std::uint64_t triangles_tested = 0;
  // The Delaunay-refinement-conforming mesh M_c (paper, Section 2: the first mesh without an
  // encroached subsegment, before any circumcenter is inserted): D = min over its vertices v of
  // nn(v) / f(v), the constant of the theorems' assumption nn_Mc >= D f, and where it is attained
  // (world coordinates); NaN when refinement never got there.
  double conforming_D = std::numeric_limits<double>::quiet_NaN();
  Point2 conforming_D_at{0, 0};
  std::uint64_t conforming_vertices = 0;
  std::uint64_t steiner() const { return segment_splits + circumcenters; }
};

// What is left after run(): triangles with R/f(c) > B (none unless the Steiner cap or an
// undefined f stopped refinement) and triangles that only fail --min-angle because of a small
// input angle (left alone on purpose).
struct RefineLeftovers {
  std::size_t r_over_f_bad = 0;
  std::size_t angle_bad = 0;
};

class Refiner {
 public:
  Refiner(mesh::Triangulation& tri, const sizing::SizingField& f, const RefineOptions& opt);
  ~Refiner();
  Refiner(const Refiner&) = delete;
  Refiner& operator=(const Refiner&) = delete;
  // Reserves arrays for about this many triangles (from estimate_triangles), avoiding
  // reallocation peaks.
  void reserve(double expected_triangles);
  // Queues every encroached subsegment and every bad triangle of the current mesh.
  void init();
  // One refinement action (split one encroached subsegment, or handle one bad triangle).
  // Returns false when nothing is left to do.
  bool step();
  // Runs to completion; throws Error(kWorkLimit) at the Steiner cap, kCancelled on cancel.
  void run();
  const RefineStats& stats() const { return stats_; }
  // with_r_over_f false: r_over_f_bad is not counted, and f is evaluated only at the triangles
  // bad by angle (angle_bad is the same count).
  RefineLeftovers leftovers(bool with_r_over_f = true) const;
  // Bad-triangle test as used by the queue: returns the squared priority key (> 1 means bad,
  // 0 when good); exempt is set when the triangle is bad only by angle and the small angle is
  // forced by the input.
  double badness(TriangleId t, bool* exempt = nullptr) const;

 private:
  // t: slot, c: its third corner when queued (identifies the triangle), z: Morton code of corner 0.
  using BadEntry = SpatialBuckets::Entry;
  void evaluate(TriangleId t);
  void push_bad(TriangleId t, double key2);
  void check_encroached_edges(TriangleId t);
  void split_subsegment(Index a, Index b);
  void split_triangle(const BadEntry& e);
  enum class Frontal { kDone, kWait, kFallback };
  bool step_front();
  Frontal split_frontal(const BadEntry& e);
  HalfEdge choose_front_edge(TriangleId t, double* rho) const;
  bool split_long_front_segment(TriangleId t);
  // A front edge serves while half its length is under this times B f (the triangle made on it,
  // at least a right one, is then good).
  static constexpr double kLongEdge = 0.95;
  void after_insert(Index v);
  void queue_fresh(const std::vector<TriangleId>& fresh, Index v);
  bool borders_dropped(TriangleId t) const;
  void give_up(TriangleId t);
  bool queue_missed();
  Point2 steiner_point(Point2 a, Point2 b, Point2 c, bool angle_bad_only) const;
  bool angle_only(Point2 a, Point2 b, Point2 c) const;
  bool below_floor(Point2 a, Point2 b, Point2 c) const;
  // Off-center distance from the short edge, as a fraction of the one at which that edge is seen
  // at exactly the bound angle (a margin so that the new triangle is not bad by rounding).
  static constexpr double kOffCenter = 0.95;
  bool shell_apex_equal(Index p, Index q) const;
  bool same_cluster(Index v, Index a, Index b) const;
  bool cluster_pair(Index s1, Index s2) const;
  Point2 split_point(Index a, Index b, Index* apex, int* shell_exp) const;
  bool may_split_for(const BadEntry& e, const std::vector<std::pair<Index, Index>>& segs) const;
  void record_conforming();

  mesh::Triangulation& tri_;
  const sizing::SizingField& f_;
  RefineOptions opt_;
  RefineStats stats_;
  cdt::Inserter ins_;
  double b2_inv_ = 1, rho2_inv_ = 0, off_cot_ = 0;
  std::vector<std::pair<Index, Index>> enc_, seg_tmp_;
  std::vector<TriangleId> off_front_;  // queue_fresh's bad new triangles off the front
  std::uint64_t swept_at_ = ~std::uint64_t{0};  // Steiner count at queue_missed's last sweep
  SpatialBuckets queue_;  // the largest-R/f(c)-first queue
  bool conforming_done_ = false;
  MortonFrame zframe_;
  // Per Steiner point on a segment (Triangulation::segment_vertex_index), the concentric shell
  // it was placed on: the input vertex at the centre and the radius's power of two (apex kNoId:
  // a midpoint).
  struct Shell {
    Index apex = kNoId;
    int exp = 0;
  };
  const Shell* shell_of(Index v) const;  // nullptr: v was not placed on a shell
  void mark_clusters();
  std::vector<Shell> shell_;
  std::vector<bool> in_cluster_;  // per input segment
  std::unique_ptr<Front> front_;  // frontal placement (RefineOptions::frontal), else null
};

// Estimated number of triangles FDR will produce: adaptive quadrature of c / f^2 over the
// triangulated domain (c calibrated on the paper's test cases for the given B).
double estimate_triangles(const mesh::Triangulation& tri, const sizing::SizingField& f, double bound);

}  // namespace fdr::refine
