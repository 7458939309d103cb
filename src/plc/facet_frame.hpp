// A facet's plane, decided exactly: three non-collinear vertices spanning it and the coordinate
// plane it is projected onto for the 2D steps (triangulation, in-facet tests).
#pragma once
#include <cstddef>
#include <string>
#include "base/point3.hpp"
#include "base/types.hpp"
#include "plc/plc.hpp"

namespace fdr::plc {

struct FacetFrame {
  VertexId p0 = 0, p1 = 0, p2 = 0;  // non-collinear vertices of the facet (its plane)
  int drop_axis = 2;                // the coordinate left out by project(): 0 x, 1 y, 2 z
  // Whether projecting reverses orientation: counter-clockwise in the projection is clockwise
  // seen from the side the normal (p1 - p0) x (p2 - p0) points to.
  bool flip = false;
  Point3 off_plane;                 // a point not in the plane (for the in-plane incircle)
};

// Drops coordinate `axis`: an affine map, so the signs of orient2d of projected points of one
// plane are those in the plane (up to the frame's flip), exactly.
Point2 project(Point3 p, int axis);

// Exact: whether a, b, c lie on one line (also when two of them coincide).
bool collinear(Point3 a, Point3 b, Point3 c);

// For coplanar u, v, ref, w with u, v, ref not collinear: +1 when w lies on ref's side of the line
// u v in their plane, 0 on the line, -1 on the other side; exact (decided in a projection that
// keeps u, v, ref apart, an affine map of the plane). 0 when u, v, ref are collinear.
int side_in_plane(Point3 u, Point3 v, Point3 ref, Point3 w);

// The frame of facet f: p0 its first vertex, p1 the next vertex distinct from it, p2 the next
// vertex off the line p0 p1; drop_axis the largest component of the normal (by a double estimate,
// then confirmed exactly: the projected p0, p1, p2 are not collinear). Throws Error(kInvalidGeometry)
// naming the facet when it has no three non-collinear vertices (a degenerate facet).
FacetFrame facet_frame(const Plc& plc, std::size_t f);

// For coplanar a, b, c, d with a, b, c not collinear: +1 when d is strictly inside the circle
// through a, b, c (in their plane), 0 on it, -1 outside; exact. `q` must lie off the plane: the
// sphere through a, b, c, q cuts the plane in that circle, so insphere decides it, its sign
// corrected by the orientation of (a, b, c, q).
int incircle_in_plane(Point3 a, Point3 b, Point3 c, Point3 d, Point3 q);

// "(x, y, z)" with every digit needed to find the point in the input.
std::string point_text(Point3 p);

// "<source>: facet F (marker M)" for messages.
std::string facet_label(const Plc& plc, std::size_t f);

}  // namespace fdr::plc
