#include "predicates/predicates3d.hpp"
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

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

int diametral_side(Point3 a, Point3 b, Point3 p) {
  ++counters().exact;
  return static_cast<int>(CGAL::side_of_bounded_sphere(cgal(a), cgal(b), cgal(p)));
}

int equatorial_side(Point3 a, Point3 b, Point3 c, Point3 p) {
  ++counters().exact;
  return static_cast<int>(CGAL::side_of_bounded_sphere(cgal(a), cgal(b), cgal(c), cgal(p)));
}

namespace {
using EK = CGAL::Exact_predicates_exact_constructions_kernel;
EK::Point_3 ek(Point3 p) { return {p.x, p.y, p.z}; }
Point3 rounded(const EK::Point_3& o) { return {CGAL::to_double(o.x()), CGAL::to_double(o.y()), CGAL::to_double(o.z())}; }
}  // namespace

Point3 circumcentre_exact(Point3 a, Point3 b, Point3 c, Point3 d) {
  return rounded(CGAL::circumcenter(ek(a), ek(b), ek(c), ek(d)));
}

Point3 triangle_circumcentre_exact(Point3 a, Point3 b, Point3 c) {
  return rounded(CGAL::circumcenter(ek(a), ek(b), ek(c)));
}

bool collinear3d(Point3 a, Point3 b, Point3 c) {
  ++counters().exact;
  return CGAL::collinear(cgal(a), cgal(b), cgal(c));
}

}  // namespace fdr::predicates
