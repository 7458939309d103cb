// Sliver removal after rule 3: a tetrahedron whose smallest dihedral angle is under a threshold is
// split by a point in a small ball around its circumcentre, picked from a fixed sequence of
// candidates so that no tetrahedron the point creates is a sliver (Li and Teng's perturbed Steiner
// point, made deterministic). The pieces here are the step's measurements and its queue; the step
// itself is Refiner3::remove_slivers (slivers.cpp).
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <queue>
#include <vector>
#include "base/point3.hpp"
#include "tet/delaunay3.hpp"
#include "tet/tet_geometry.hpp"

namespace fdr::tet {

// The cosine of the smallest of the six interior dihedral angles (1 for a flat tetrahedron):
// larger is worse, so comparing cosines orders tetrahedra without an arccosine (the angle itself
// is tet_output.hpp's min_dihedral_deg).
double smallest_dihedral_cos(Point3 a, Point3 b, Point3 c, Point3 d);

// The ball the candidates are drawn from, for positively oriented (a, b, c, d): the circumsphere
// when its double-precision centre lies strictly inside it (exact insphere), else, for a tetrahedron too flat for that, the circle of its
// largest face (whose centre is always inside the circumsphere).
Sphere sliver_ball(Point3 a, Point3 b, Point3 c, Point3 d);

// The candidate Steiner points for a sliver with circumcentre `centre` and circumradius `radius`:
// the centre first, then `count - 1` points spread evenly through the ball of radius
// delta * radius around it (directions on a spherical Fibonacci lattice, distances from a van der
// Corput sequence, so the two are not correlated). The same arguments give the same points.
std::vector<Point3> sliver_candidates(Point3 centre, double radius, double delta, int count);

// What inserting p with conflict region `cavity` would do to the dihedral angles: the cosine of
// the smallest angle among the finite tetrahedra it destroys and among those it creates (each
// face of the cavity's boundary joined to p). `scratch` is reused memory.
// A caller that only wants p when it creates no angle with cosine above `good_cos`, or else
// improves on both the destroyed tetrahedra and `rival_cos`, gets the created tetrahedra measured
// only until p fails both: created_cos is then a lower bound (above good_cos and at least
// min(destroyed_cos, rival_cos)). The defaults measure them all.
struct InsertionAngles {
  double destroyed_cos = -1;
  double created_cos = -1;
};
InsertionAngles insertion_angles(const Delaunay3& dt, Point3 p, const std::vector<TetId>& cavity,
                                 std::vector<TetId>& scratch, double good_cos = 2, double rival_cos = 2);

// A sliver waiting for removal, with the vertices it had when queued (its slot may be reused).
struct SliverTet {
  double cos = 0;  // smallest_dihedral_cos
  TetId tet = kNoId;
  std::array<VertexId, 4> v{};
};

// Slivers worst first (largest cosine), ties by their sorted vertex ids, so that the order does
// not depend on where tetrahedra are stored. Entries whose tetrahedron was destroyed are dropped
// when they come up.
class SliverQueue {
 public:
  void push(const SliverTet& s) { heap_.push(s); }
  bool pop(const Delaunay3& dt, SliverTet* out);
  std::size_t size() const { return heap_.size(); }

 private:
  struct Better {
    bool operator()(const SliverTet& a, const SliverTet& b) const;
  };
  std::priority_queue<SliverTet, std::vector<SliverTet>, Better> heap_;
};

// The ball's radius as a fraction of the circumradius: every candidate is at least (1 - delta) R
// from every vertex, since the sliver's circumsphere is empty, so the new edges stay comparable to
// the old ones.
inline constexpr double kSliverBallDelta = 0.4;
inline constexpr int kSliverCandidates = 24;
// A few times the conflict region of a circumcentre in a good mesh (a few dozen tetrahedra).
inline constexpr std::size_t kSliverMaxCavity = 128;

// The state of the sliver phase: the threshold, the queue and scratch.
struct SliverState {
  double cos_threshold = 1;  // a tetrahedron with a larger smallest-angle cosine is a sliver
  double cos_floor = 1;      // slivers flatter than this may split the boundary at acute facet pairs
  SliverQueue queue;
  std::vector<TetId> sorted;  // scratch of insertion_angles
  std::vector<TetId> cavity;
};

}  // namespace fdr::tet
