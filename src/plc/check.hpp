// Checks of a PLC before meshing: every defect of the input is an fdr::Error with a documented exit
// code and a message naming the source file, the facet (index and marker), vertex ids and
// coordinates. Each step is its own function; check() runs them all in order. Inputs without
// facets (a point set meshed as its convex hull) are checked with CheckOptions::closed = false.
#pragma once
#include "plc/plc.hpp"
#include "plc/triangulate_facets.hpp"

namespace fdr::plc {

struct CheckOptions {
  // The facets must enclose a volume (a mesher input): an edge used by a single facet triangle
  // must lie inside the volume (a free edge of an internal facet), never on its outer surface.
  bool closed = true;
};

// Coordinates of points, volume hole points and region points, and region attributes are finite,
// region volume bounds are numbers, no two points coincide (kInvalidGeometry).
void check_points(const Plc& plc);

// Vertex ids of facets and free segments are in range and point markers, if any, one per point
// (kInputMalformed); every facet has a polygon, polygons are not degenerate (no vertices, a vertex
// repeated consecutively, three or more vertices all on one line) and free segments have two
// distinct ends (kInvalidGeometry).
void check_ids_and_polygons(const Plc& plc);

// Every facet is planar: each vertex against three non-collinear ones of it, exactly
// (kInvalidGeometry). A facet hole point must lie in the plane: within 1e-6 of the facet's
// extent, since a hole point written in decimal is rarely exactly on a tilted plane and only
// selects a region (the projection decides which, exactly). Its position inside the facet is
// checked when the facet is triangulated.
void check_planarity(const Plc& plc);

// Runs every step, including the facet triangulation (hole points outside their facet, polygons
// crossing inside a facet), facet intersections (intersections.hpp) and, with opt.closed, the
// closed boundary and the volume hole and region points (cells.hpp). Returns the facet
// triangulation it made, so that a caller need not make it again.
FacetTriangulation check_and_triangulate(const Plc& plc, const CheckOptions& opt = {});

// check_and_triangulate without the result.
void check(const Plc& plc, const CheckOptions& opt = {});

}  // namespace fdr::plc
