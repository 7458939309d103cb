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

void StaticFilter3::cover(Point3 p) {
  box_.add(p);
  // Upper bounds on |difference| per axis: the extent, rounded, then raised past its rounding.
  // Every computed difference of two coordinates in the box is at most this double (rounding is
  // monotone), so each bound below holds for every call on points of the box.
  const double up = 1 + 4 * detail::kEps;
  const double mx = (box_.hi.x - box_.lo.x) * up, my = (box_.hi.y - box_.lo.y) * up, mz = (box_.hi.z - box_.lo.z) * up;
  // orient3d's permanent is three terms (|x y| + |x y|) |z|: at most 6 mx my mz, times (1 + eps)
  // for each of its five roundings and one more for the bound's product. insphere's is four terms
  // of three (|x y| + |x y|) |z| times a lift x^2 + y^2 + z^2: at most 24 mx my mz (mx^2 + my^2 +
  // mz^2), times (1 + eps)^13. The factor 1 + 64 eps covers those and this computation's own
  // roundings, so the doubles here are at least the dynamic filter's bounds.
  const double slack = 1 + 64 * detail::kEps;
  o3d_ = detail::kO3dBound * 6 * mx * my * mz * slack;
  isp_ = detail::kIspBound * 24 * mx * my * mz * (mx * mx + my * my + mz * mz) * slack;
}

}  // namespace fdr::predicates
