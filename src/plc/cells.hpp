// The cells of space that the facets of a PLC cut out, as classes of triangle sides: whether the
// facets close a volume, and which cell a point lies in (outside the domain or not).
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>
#include "plc/plc.hpp"
#include "plc/triangulate_facets.hpp"

namespace fdr::plc {

// Every facet triangle has two sides; two sides belong to one class when a path joins them without
// crossing a facet. Classes are found exactly: around every edge the triangles are sorted by angle
// (orient3d), and the sides facing one wedge join; then rays between points far outside the
// facets' box join the sides that face each other along them, one ray through every connected
// piece of the surface, so that pieces nested in others or beside them are placed. One class, the
// unbounded one, holds what lies outside every volume. A segment query costs O(log n + hits)
// (CGAL's AABB tree), so the whole is O(n log n) for a surface of few pieces.
// Expects a PLC whose facets passed check_intersections (no overlaps or crossings). Not for use
// from several threads at once (queries join classes as they learn about them).
class SurfaceCells {
 public:
  SurfaceCells(const Plc& plc, const FacetTriangulation& ft);
  ~SurfaceCells();
  SurfaceCells(const SurfaceCells&) = delete;
  SurfaceCells& operator=(const SurfaceCells&) = delete;

  // Throws Error(kInvalidGeometry) when the facets bound no volume or leave a hole in its surface
  // (an edge used by a single triangle with the outside on both of its sides), naming the edge,
  // its coordinates and its facet; or when a facet lies outside every volume.
  void check_closed();

  // Throws Error(kInvalidGeometry) when a volume hole point or a region point lies outside the
  // domain or on a facet, naming the point and its coordinates.
  void check_volume_points();

  // Whether p lies outside every volume. Throws Error(kInvalidGeometry) naming `what` when p lies
  // on a facet.
  bool outside(Point3 p, const std::string& what);

  // The class of side `positive` (orient3d of the triangle's corners and a point on that side > 0)
  // of triangle k (facets' triangles in order), and the unbounded class.
  std::size_t side_class(std::size_t k, bool positive);
  std::size_t unbounded_class();

 private:
  struct Crossing;
  struct RayIndex;  // an AABB tree of the triangles: a segment query visits only those it meets
  std::size_t find(std::size_t s);
  void join(std::size_t a, std::size_t b);
  void join_around_edges();
  void place_pieces();
  // The triangles the segment p r crosses, in order from p; false when it meets an edge or vertex
  // or runs in a triangle's plane (then another segment is needed). Throws when p lies on a
  // triangle (`what` names p).
  bool crossings(Point3 p, Point3 r, std::vector<Crossing>& out, const std::string& what) const;
  // Joins the sides met along a segment whose ends lie in the unbounded class (far_end) or from
  // p's class (then returns the class of p).
  std::size_t walk(const std::vector<Crossing>& cs, bool start_unbounded);
  Point3 far_point(Point3 through, std::uint64_t attempt, double sign) const;

  const Plc& plc_;
  std::vector<Triangle> tris_;
  std::vector<std::uint32_t> facet_of_;
  std::vector<std::pair<Edge, std::size_t>> edge_uses_;  // (edge, triangle) for every triangle edge, sorted
  std::vector<std::size_t> parent_;  // 2 per triangle (negative, positive side), then the unbounded class
  std::unique_ptr<RayIndex> rays_;
  Box3 box_;
  double reach_ = 1;                 // far points lie this far from the box
};

}  // namespace fdr::plc
