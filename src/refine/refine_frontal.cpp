// The Refiner's frontal steps (RefineOptions::frontal): which front edge to build on, the
// frontal split with the checks the guarantees need, and the front's queueing.
#include <algorithm>
#include <cmath>
#include <limits>
#include "base/triangle_geometry.hpp"
#include "cdt/locate.hpp"
#include "predicates/predicates.hpp"
#include "refine/frontal.hpp"
#include "refine/refine.hpp"

namespace fdr::refine {
using mesh::VertexKind;
using predicates::diametral;

// Frontal mode: bad triangles on the front go to the front's queue; the bad ones off it wait for
// the front to reach them, except next to a triangle refinement gave up on (see give_up).
void Refiner::queue_fresh(const std::vector<TriangleId>& fresh, Index v) {
  off_front_.clear();
  front_->note_new(tri_, fresh, v, &off_front_);
  for (TriangleId t : off_front_)
    if (borders_dropped(t)) push_bad(t, front_->key(t));
}

bool Refiner::borders_dropped(TriangleId t) const {
  const auto& T = tri_;
  for (Index k = 0; k < 3; ++k) {
    const HalfEdge w = T.twin(3 * t + k);
    if (w != kNoId && !T.constrained(3 * t + k) && front_->dropped(mesh::tri_of(w))) return true;
  }
  return false;
}

// Why: a bad triangle off the front waits until the front reaches it, which happens unless every
// way there leads through triangles refinement leaves bad (an exempt angle, no usable split
// point); those do not make front edges, so their bad neighbours off the front are queued for the
// circumcentre rule here, and new ones beside them by queue_fresh.
void Refiner::give_up(TriangleId t) {
  if (!front_) return;
  front_->drop(t);
  const auto& T = tri_;
  for (Index k = 0; k < 3; ++k) {
    const HalfEdge w = T.twin(3 * t + k);
    if (w == kNoId || T.constrained(3 * t + k)) continue;
    const TriangleId n = mesh::tri_of(w);
    if (front_->bad(n) && !front_->dropped(n) && !front_->has_front_edge(T, n)) push_bad(n, front_->key(n));
  }
}

// Why: refinement ends only when no bad triangle is left that it did not give up on, whether or
// not the front and give_up reached every one; one sweep per new vertex count, so it cannot spin.
bool Refiner::queue_missed() {
  if (swept_at_ == stats_.steiner()) return false;
  swept_at_ = stats_.steiner();
  bool any = false;
  for (TriangleId t = 0; t < tri_.num_slots(); ++t)
    if (!tri_.dead(t) && front_->bad(t) && !front_->dropped(t)) {
      push_bad(t, front_->key(t));
      any = true;
    }
  return any;
}

// The front edge of t to build on: an edge on the front no longer than the triangle the front
// asks for there (a longer one would give a point on or inside its diametral circle; such a
// triangle waits for the circumcentre rule), the one nearest that size. *rho: the circumradius
// asked for at its midpoint.
HalfEdge Refiner::choose_front_edge(TriangleId t, double* rho) const {
  const auto& T = tri_;
  const double kr = opt_.frontal_radius * opt_.bound;
  HalfEdge best = kNoId;
  double best_err = std::numeric_limits<double>::infinity();
  for (Index k = 0; k < 3; ++k) {
    const HalfEdge h = 3 * t + k;
    if (!front_->front_edge(T, h)) continue;
    const Point2 p = T.point(T.org(h)), q = T.point(T.dst(h));
    const double fm = f_(0.5 * (p + q));
    if (!(fm > 0) || !std::isfinite(fm)) continue;
    const double r = kr * fm, len = dist(p, q);
    if (0.5 * len > kLongEdge * opt_.bound * fm) continue;
    const double err = std::fabs(len - std::sqrt(3.0) * r);
    if (err < best_err) {
      best_err = err;
      best = h;
      *rho = r;
    }
  }
  return best;
}

// One frontal split of a front triangle (RefineOptions::frontal). kWait: not R/f(c)-bad, or no
// front edge fits (it stays in the largest-first queue); kFallback: the frontal point is not
// usable, split at the circumcenter.
Refiner::Frontal Refiner::split_frontal(const BadEntry& e) {
  auto& T = tri_;
  const Point2 a = T.point(T.corner(e.t, 0)), b = T.point(T.corner(e.t, 1)), c = T.point(T.corner(e.t, 2));
  double r2;
  const Point2 cc = geom::circumcentre(a, b, c, &r2);
  const double fc = f_(cc);
  if (!(fc > 0) || !std::isfinite(fc) || !(r2 / (fc * fc) * b2_inv_ > 1)) return Frontal::kWait;
  double rho = 0;
  const HalfEdge h = choose_front_edge(e.t, &rho);
  if (h == kNoId) return split_long_front_segment(e.t) ? Frontal::kDone : Frontal::kWait;
  const Point2 p = T.point(T.org(h)), q = T.point(T.dst(h));
  const double r = std::sqrt(r2);
  FrontalPoint fp = frontal_point(p, q, cc, r, rho);
  // The size asked for where the new triangle's circumcentre falls (f was taken at the edge).
  const double fn = f_(fp.centre);
  if (fn > 0 && std::isfinite(fn)) fp = frontal_point(p, q, cc, r, opt_.frontal_radius * opt_.bound * fn);
  const Point2 x = fp.x;
  ++stats_.frontal_fallbacks;  // taken back below when the point is used or rejected
  if (predicates::incircle(a, b, c, x) <= 0) return Frontal::kFallback;
  const cdt::Location loc = cdt::locate_straight(T, e.t, x);
  if (loc.kind == cdt::LocateKind::kBlocked || loc.kind == cdt::LocateKind::kOnVertex ||
      (loc.kind == cdt::LocateKind::kOnEdge && T.constrained(loc.he)))
    return Frontal::kFallback;
  if (!ins_.build_cavity(x, loc)) return Frontal::kFallback;
  const auto& cav = ins_.cavity();
  const double fx = f_(x);
  double rx2 = std::numeric_limits<double>::infinity();  // squared insertion radius
  for (HalfEdge g : ins_.boundary()) rx2 = std::min(rx2, norm2(T.point(T.org(g)) - x));
  // The proofs ask of an inserted point what a circumcentre has: no vertex nearer than B f.
  if (std::find(cav.begin(), cav.end(), e.t) == cav.end() || !(fx > 0) ||
      rx2 < opt_.bound * opt_.bound * fx * fx) {
    ins_.abort();
    return Frontal::kFallback;
  }
  --stats_.frontal_fallbacks;
  seg_tmp_.clear();
  for (HalfEdge g : ins_.boundary())
    if (T.constrained(g) && diametral(T.point(T.org(g)), T.point(T.dst(g)), x) > 0)
      seg_tmp_.push_back({T.org(g), T.dst(g)});
  if (!seg_tmp_.empty()) {
    // Rejected: split the encroached subsegments first; the triangle stays queued (both queues).
    ins_.abort();
    ++stats_.rejected_circumcenters;
    enc_.insert(enc_.end(), seg_tmp_.begin(), seg_tmp_.end());
    front_->offer(T, e.t);
    return Frontal::kDone;
  }
  const Index v = ins_.commit(x, VertexKind::kFree);
  ++stats_.circumcenters;
  ++stats_.frontal_points;
  after_insert(v);
  return Frontal::kDone;
}

// A front triangle whose front edges are all too long: its longest subsegment is split where its
// pieces are at least B f long (so the split point has the insertion radius the proofs ask for:
// the subsegment is not encroached, its diametral disk is empty). Why: else the circumcentre rule
// would fill the domain with coarse vertices before the boundary is fine enough to start a front.
bool Refiner::split_long_front_segment(TriangleId t) {
  const auto& T = tri_;
  HalfEdge best = kNoId;
  double best_len = 0;
  for (Index k = 0; k < 3; ++k) {
    const HalfEdge h = 3 * t + k;
    if (!T.constrained(h)) continue;
    Index apex;
    int ex;
    const Point2 m = split_point(T.org(h), T.dst(h), &apex, &ex);
    const double fm = f_(m);
    const Point2 p = T.point(T.org(h)), q = T.point(T.dst(h));
    if (!(fm > 0) || !std::isfinite(fm) || std::min(dist(p, m), dist(m, q)) < opt_.bound * fm) continue;
    if (dist(p, q) > best_len) {
      best_len = dist(p, q);
      best = h;
    }
  }
  if (best == kNoId) return false;
  enc_.push_back({T.org(best), T.dst(best)});
  return true;
}

// The next front triangle, split; false when the front holds no bad triangle to split now.
bool Refiner::step_front() {
  Front::Entry f;
  while (front_->pop(&f)) {
    constexpr std::size_t kAhead = 6;  // as in step(): fetch what an entry a few pops on touches
    if (const Front::Entry* n = front_->ahead(kAhead)) tri_.prefetch(n->t, n->c);
    const auto& T = tri_;
    if (T.dead(f.t) || T.corner(f.t, 2) != f.c || !front_->bad(f.t)) continue;
    const BadEntry e = f;
    const Frontal r = split_frontal(e);
    if (r == Frontal::kWait) {
      push_bad(e.t, front_->key(e.t));  // for the circumcentre rule when the front is done
      continue;
    }
    if (r == Frontal::kFallback) split_triangle(e);
    return true;
  }
  return false;
}

}  // namespace fdr::refine
