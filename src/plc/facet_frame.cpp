// Facet planes: exact choice of the spanning vertices and the projection axis.
#include "plc/facet_frame.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "base/error.hpp"
#include "predicates/predicates.hpp"
#include "predicates/predicates3d.hpp"

namespace fdr::plc {

Point2 project(Point3 p, int axis) {
  if (axis == 0) return {p.y, p.z};
  if (axis == 1) return {p.z, p.x};
  return {p.x, p.y};
}

bool collinear(Point3 a, Point3 b, Point3 c) {
  // Collinear in space exactly when collinear in all three coordinate projections.
  for (int axis = 0; axis < 3; ++axis)
    if (predicates::orient2d(project(a, axis), project(b, axis), project(c, axis)) != 0) return false;
  return true;
}

int side_in_plane(Point3 u, Point3 v, Point3 ref, Point3 w) {
  for (int axis = 0; axis < 3; ++axis) {
    const int o = predicates::orient2d(project(u, axis), project(v, axis), project(ref, axis));
    if (o != 0) return o * predicates::orient2d(project(u, axis), project(v, axis), project(w, axis));
  }
  return 0;
}

std::string point_text(Point3 p) {
  std::ostringstream s;
  s.precision(17);
  s << "(" << p.x << ", " << p.y << ", " << p.z << ")";
  return s.str();
}

std::string facet_label(const Plc& plc, std::size_t f) {
  return (plc.source.empty() ? std::string("input") : plc.source) + ": facet " + std::to_string(f) + " (marker " +
         std::to_string(plc.facets[f].marker) + ")";
}

FacetFrame facet_frame(const Plc& plc, std::size_t f) {
  const Facet& facet = plc.facets[f];
  FacetFrame fr;
  int found = 0;
  for (const auto& poly : facet.polygons)
    for (VertexId v : poly) {
      if (v >= plc.points.size()) continue;  // reported by check()
      const Point3 p = plc.points[v];
      if (found == 0) {
        fr.p0 = v, found = 1;
      } else if (found == 1 && !(p == plc.points[fr.p0])) {
        fr.p1 = v, found = 2;
      } else if (found == 2 && !collinear(plc.points[fr.p0], plc.points[fr.p1], p)) {
        fr.p2 = v, found = 3;
      }
    }
  if (found < 3)
    throw Error(ExitCode::kInvalidGeometry,
                facet_label(plc, f) + " is degenerate: its vertices do not span a plane (fewer than three "
                                      "non-collinear vertices)");
  const Point3 a = plc.points[fr.p0], b = plc.points[fr.p1], c = plc.points[fr.p2];
  const Point3 n = cross(b - a, c - a);
  const double an[3] = {std::abs(n.x), std::abs(n.y), std::abs(n.z)};
  int order[3] = {2, 0, 1};  // largest estimated component first, z preferred on ties
  std::sort(order, order + 3, [&](int i, int j) { return an[i] > an[j]; });
  for (int axis : order) {
    const int o = predicates::orient2d(project(a, axis), project(b, axis), project(c, axis));
    if (o == 0) continue;
    fr.drop_axis = axis;
    // orient2d of the projection is the sign of the normal's component along the dropped axis
    // (the maps to (x, y), (y, z), (z, x) are cyclic), so the projection is seen from +axis.
    fr.flip = o < 0;
    Point3 q = a;
    const double span = std::max({std::abs(b.x - a.x), std::abs(b.y - a.y), std::abs(b.z - a.z),
                                  std::abs(c.x - a.x), std::abs(c.y - a.y), std::abs(c.z - a.z), 1.0});
    double* coord = axis == 0 ? &q.x : axis == 1 ? &q.y : &q.z;
    const double base = *coord;
    for (double t = span; *coord == base; t *= 2) *coord = base + t;
    fr.off_plane = q;
    // q - a is along +axis, so orient3d(a, b, c, q) has that same sign.
    if (predicates::orient3d(a, b, c, q) != o)
      throw Error(ExitCode::kInternal, facet_label(plc, f) + ": projection orientation disagrees with orient3d");
    return fr;
  }
  throw Error(ExitCode::kInternal, facet_label(plc, f) + ": no projection keeps its spanning vertices apart");
}

int incircle_in_plane(Point3 a, Point3 b, Point3 c, Point3 d, Point3 q) {
  const int o = predicates::orient3d(a, b, c, q);
  return o * predicates::insphere(a, b, c, q, d);
}

}  // namespace fdr::plc
