#include "predicates/predicates3d.hpp"
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include "predicates/predicates.hpp"

namespace fdr::predicates {
namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
K::Point_3 cgal(Point3 p) { return {p.x, p.y, p.z}; }
}  // namespace

int orient3d_exact(Point3 a, Point3 b, Point3 c, Point3 d) {
  return static_cast<int>(CGAL::orientation(cgal(a), cgal(b), cgal(c), cgal(d)));
}

int insphere_exact(Point3 a, Point3 b, Point3 c, Point3 d, Point3 e) {
  return static_cast<int>(CGAL::side_of_oriented_sphere(cgal(a), cgal(b), cgal(c), cgal(d), cgal(e)));
}

// The double filter comes with the Delaunay tetrahedralization; until then every sign is exact.
int orient3d(Point3 a, Point3 b, Point3 c, Point3 d) {
  ++counters().exact;
  return orient3d_exact(a, b, c, d);
}

int insphere(Point3 a, Point3 b, Point3 c, Point3 d, Point3 e) {
  ++counters().exact;
  return insphere_exact(a, b, c, d, e);
}

}  // namespace fdr::predicates
