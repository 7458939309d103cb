// Exact fallbacks of the predicates through CGAL's Epick kernel (filtered + exact).
#include "predicates/predicates.hpp"
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

namespace fdr::predicates {
namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using P = K::Point_2;
inline P cg(Point2 p) { return P(p.x, p.y); }
}  // namespace


int orient2d_exact(Point2 a, Point2 b, Point2 c) {
  return static_cast<int>(CGAL::orientation(cg(a), cg(b), cg(c)));
}

int incircle_exact(Point2 a, Point2 b, Point2 c, Point2 d) {
  // side_of_oriented_circle: ON_POSITIVE_SIDE means inside for CCW (a,b,c).
  return static_cast<int>(CGAL::side_of_oriented_circle(cg(a), cg(b), cg(c), cg(d)));
}

int diametral_exact(Point2 a, Point2 b, Point2 p) {
  // CGAL::angle(a,p,b) is the angle at p: OBTUSE <=> (a-p).(b-p) < 0 <=> inside.
  switch (CGAL::angle(cg(a), cg(p), cg(b))) {
    case CGAL::OBTUSE: return 1;
    case CGAL::RIGHT: return 0;
    default: return -1;
  }
}

}  // namespace fdr::predicates
