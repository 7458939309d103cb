// Exact fallbacks of the predicates through CGAL's Epick kernel (filtered + exact).
#include "predicates/predicates.hpp"
#include "base/parallel.hpp"
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <gmp.h>
#include <cmath>
#include <cstring>

namespace fdr::predicates {
namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using P = K::Point_2;
inline P cg(Point2 p) { return P(p.x, p.y); }

// A worker thread's counters are added to the thread that started it (base/parallel.hpp), so
// the report counts every call whichever thread made it.
void* take_counters() {
  auto* c = new Counters(counters());
  reset_counters();
  return c;
}
void give_counters(void* blob) {
  auto* c = static_cast<Counters*>(blob);
  counters().filtered += c->filtered;
  counters().exact += c->exact;
  delete c;
}
[[maybe_unused]] const bool kCountersRegistered = register_thread_state({take_counters, give_counters});
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

namespace {
// RAII mpq_t.
struct Q {
  mpq_t v;
  Q() { mpq_init(v); }
  explicit Q(double d) { mpq_init(v); mpq_set_d(v, d); }
  ~Q() { mpq_clear(v); }
  Q(const Q&) = delete;
  Q& operator=(const Q&) = delete;
};

// The double nearest to q (ties: the one with even last bit), for |q| within double range.
double round_nearest(const mpq_t q) {
  const double d = mpq_get_d(q);  // truncated towards zero
  if (!std::isfinite(d)) return d;
  const double e = std::nextafter(d, mpq_sgn(q) >= 0 ? HUGE_VAL : -HUGE_VAL);
  Q qd(d), qe(e), diff_d, diff_e;
  mpq_sub(diff_d.v, q, qd.v);
  mpq_abs(diff_d.v, diff_d.v);
  mpq_sub(diff_e.v, q, qe.v);
  mpq_abs(diff_e.v, diff_e.v);
  const int c = mpq_cmp(diff_d.v, diff_e.v);
  if (c < 0) return d;
  if (c > 0) return e;
  std::uint64_t bits;
  std::memcpy(&bits, &d, sizeof bits);
  return (bits & 1) ? e : d;
}
}  // namespace

bool line_intersection_rounded(Point2 a, Point2 b, Point2 c, Point2 d, Point2* out) {
  // p = a + t (b - a), t = ((c - a) x (d - c)) / ((b - a) x (d - c)), all in rationals.
  Q ax(a.x), ay(a.y), rx, ry, sx, sy, qx, qy, num, den, tmp, t, px, py;
  Q bx(b.x), by(b.y), cx(c.x), cy(c.y), dx(d.x), dy(d.y);
  mpq_sub(rx.v, bx.v, ax.v);
  mpq_sub(ry.v, by.v, ay.v);
  mpq_sub(sx.v, dx.v, cx.v);
  mpq_sub(sy.v, dy.v, cy.v);
  mpq_sub(qx.v, cx.v, ax.v);
  mpq_sub(qy.v, cy.v, ay.v);
  mpq_mul(den.v, rx.v, sy.v);
  mpq_mul(tmp.v, ry.v, sx.v);
  mpq_sub(den.v, den.v, tmp.v);
  if (mpq_sgn(den.v) == 0) return false;
  mpq_mul(num.v, qx.v, sy.v);
  mpq_mul(tmp.v, qy.v, sx.v);
  mpq_sub(num.v, num.v, tmp.v);
  mpq_div(t.v, num.v, den.v);
  mpq_mul(px.v, t.v, rx.v);
  mpq_add(px.v, px.v, ax.v);
  mpq_mul(py.v, t.v, ry.v);
  mpq_add(py.v, py.v, ay.v);
  *out = {round_nearest(px.v), round_nearest(py.v)};
  return true;
}

}  // namespace fdr::predicates
