// Coast deviation on the sphere: how far (great-circle metres) the input coast lies from the mesh
// boundary of a global mesh and back, both taken as chains of great-circle arcs.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>
#include "base/point3.hpp"
#include "base/types.hpp"
#include "gis/global_sphere.hpp"

namespace fdr::gis {

// The minor great-circle arc between two unit vectors.
struct SphereArc {
  Point3 a, b;
};

// Angle (radians) from the unit vector p to the nearest point of the minor arc ab.
double arc_distance(Point3 p, Point3 a, Point3 b);

// Nearest-arc queries over a set of arcs: a bounding-volume tree of the arcs' boxes (each arc's
// chord box grown by its sagitta), searched nearest box first, pruned by the chord distance.
class ArcIndex {
 public:
  explicit ArcIndex(const std::vector<SphereArc>& arcs);
  // Angle (radians) from unit vector p to the nearest arc; +inf without arcs.
  double nearest(Point3 p) const;

 private:
  struct Node {
    Box3 box;
    std::uint32_t first = 0, count = 0;  // a leaf's arcs in order_; count 0: an inner node
    std::uint32_t left = 0, right = 0;
  };
  std::uint32_t build(std::uint32_t lo, std::uint32_t hi);

  const std::vector<SphereArc>& arcs_;
  std::vector<Box3> boxes_;
  std::vector<std::uint32_t> order_;
  std::vector<Node> nodes_;
};

// Every arc's start and points every `step_rad` (angle) along it.
std::vector<Point3> sample_arcs(const std::vector<SphereArc>& arcs, double step_rad);

struct SphereDeviation {
  std::size_t samples = 0;
  double max_m = 0, p99_m = 0;  // great-circle metres; p99 by nearest rank
  LonLat max_at{};
};

// From the samples of `from` (every arc start and every `step_m` on the ground) to the nearest arc
// of `to`, on the sphere of radius r. The step is raised when it would give over 4 M samples.
SphereDeviation sphere_deviation(const std::vector<SphereArc>& from, const std::vector<SphereArc>& to, double step_m,
                                 double r = kEarthRadius);

// The same from the rings of `from` that have a counterpart in `to`, as the regional yardstick
// (coast_quality.py) measures: `from` is rings of consecutive arcs, each closing on its first
// point; a ring whose vertices all lie farther than keep_m from `to` (an island the
// generalisation removed) is left out and counted in `lost_rings`. Water the generalisation
// closed off along a kept ring still counts.
SphereDeviation sphere_deviation_kept(const std::vector<SphereArc>& from, const std::vector<SphereArc>& to,
                                      double step_m, double keep_m, std::size_t* lost_rings, double r = kEarthRadius);

}  // namespace fdr::gis
