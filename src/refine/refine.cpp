// Functional Delaunay Refinement (Chen-style FDR paper, Section 3) on a constrained Delaunay
// triangulation: rule 1 (encroached subsegments, split at midpoints or concentric shells) before
// rule 3 (B-bad triangles by R/f(c), split at circumcenters unless that encroaches a subsegment).
#include "refine/refine.hpp"
#include "base/triangle_geometry.hpp"
#include <algorithm>
#include <utility>
#include <cmath>
#include <numbers>
#include <cstdlib>
#include <span>
#include <sstream>
#include "base/error.hpp"
#include "base/kd_tree.hpp"
#include "base/parallel.hpp"
#include "cdt/locate.hpp"
#include "predicates/predicates.hpp"

namespace fdr::refine {
using mesh::Triangulation;
using mesh::VertexKind;
using predicates::diametral;

namespace {
// Queue order: largest R/f(c) first, by buckets. One bucket per doubling of (R/f(c))^2 (a factor
// sqrt(2) in R/f(c)), except the last doubling before the bound, 1 < (R/f(c))^2 <= 2, which is split
// into kFineSub buckets. Why: where the final vertices go is decided there; coarse buckets there
// make clearly more triangles than the exact largest-first order, fine buckets everywhere cost
// refinement time for little gain.
constexpr int kFineSub = 4;
constexpr int kBuckets = 2048 + kFineSub;

std::string pt(Point2 p) {
  std::ostringstream s;
  s.precision(15);
  s << "(" << p.x << ", " << p.y << ")";
  return s.str();
}

int bucket_of(double key2) {
  if (!(key2 <= 1e300)) return kBuckets - 1;  // inf (R/f overflows) or NaN: most urgent
  int e;
  const double m = std::frexp(key2, &e);  // key2 = m * 2^e, m in [0.5, 1)
  const int idx = e <= 1 ? static_cast<int>((m - 0.5) * (2.0 * kFineSub)) : kFineSub + (e - 2);
  return idx < 0 ? 0 : (idx >= kBuckets ? kBuckets - 1 : idx);
}
}  // namespace

Refiner::Refiner(Triangulation& tri, const sizing::SizingField& f, const RefineOptions& opt)
    : tri_(tri), f_(f), opt_(opt), ins_(tri), queue_(kBuckets) {
  if (!(opt_.bound > 0) || !std::isfinite(opt_.bound))
    throw Error(ExitCode::kUsage, "bound B must be a positive number");
  b2_inv_ = 1.0 / (opt_.bound * opt_.bound);
  zframe_ = MortonFrame::of(std::span<const Point2>(tri_.points().data(), tri_.points().size()));
  mark_clusters();
  if (opt_.frontal) {
    if (!(opt_.frontal_radius > 0 && opt_.frontal_radius < 1))
      throw Error(ExitCode::kUsage, "the frontal radius must lie in (0, 1) (a fraction of B f)");
    front_ = std::make_unique<Front>(zframe_);
  }
  if (opt_.min_angle_deg > 0) {
    if (opt_.min_angle_deg >= 60) throw Error(ExitCode::kUsage, "--min-angle must be below 60 degrees");
    const double s = std::sin(opt_.min_angle_deg * std::numbers::pi / 180.0);
    rho2_inv_ = 4.0 * s * s;  // R/l > 1/(2 sin theta)  <=>  (R^2/l^2) * 4 sin^2 > 1
    off_cot_ = 1.0 / std::tan(0.5 * opt_.min_angle_deg * std::numbers::pi / 180.0);
  }
}

// Input segments that meet another at an input vertex at less than 60 degrees (a cluster). Each
// pair of segments at a vertex is tested once (the flags are an "or": their order is immaterial).
void Refiner::mark_clusters() {
  const auto& segs = tri_.input_segments();
  in_cluster_.assign(segs.size(), false);
  std::vector<std::pair<Index, Index>> at_vertex;  // (vertex, segment), sorted
  at_vertex.reserve(2 * segs.size());
  for (Index s = 0; s < segs.size(); ++s) {
    at_vertex.push_back({segs[s].a, s});
    at_vertex.push_back({segs[s].b, s});
  }
  std::sort(at_vertex.begin(), at_vertex.end());
  for (std::size_t lo = 0, hi = 0; lo < at_vertex.size(); lo = hi) {
    while (hi < at_vertex.size() && at_vertex[hi].first == at_vertex[lo].first) ++hi;
    for (std::size_t i = lo; i < hi; ++i)
      for (std::size_t j = i + 1; j < hi; ++j)
        if (cluster_pair(at_vertex[i].second, at_vertex[j].second))
          in_cluster_[at_vertex[i].second] = in_cluster_[at_vertex[j].second] = true;
  }
}

bool Refiner::shell_apex_equal(Index p, Index q) const {
  const Shell* sp = shell_of(p);
  const Shell* sq = shell_of(q);
  return sp != nullptr && sq != nullptr && sp->apex == sq->apex && sp->exp == sq->exp;
}

const Refiner::Shell* Refiner::shell_of(Index v) const {
  const Index i = tri_.segment_vertex_index(v);
  return i < shell_.size() && shell_[i].apex != kNoId ? &shell_[i] : nullptr;
}

double Refiner::badness(TriangleId t, bool* exempt) const {
  const auto& T = tri_;
  const Point2 a = T.point(T.corner(t, 0)), b = T.point(T.corner(t, 1)), c = T.point(T.corner(t, 2));
  const double bx = b.x - a.x, by = b.y - a.y, cx = c.x - a.x, cy = c.y - a.y;
  const double b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
  const double inv = 0.5 / (bx * cy - by * cx);
  const double ux = (cy * b2 - by * c2) * inv, uy = (bx * c2 - cx * b2) * inv;
  const double r2 = ux * ux + uy * uy;
  const Point2 cc{a.x + ux, a.y + uy};
  double fc = f_(cc);
  if (!(fc > 0) || !std::isfinite(fc)) {
    // Circumcenters of boundary triangles can fall outside the domain, where a user's f may be
    // undefined; the triangle's centroid is always inside, so judge the triangle there instead.
    const Point2 g{(a.x + b.x + c.x) / 3.0, (a.y + b.y + c.y) / 3.0};
    fc = f_(g);
    if (!(fc > 0) || !std::isfinite(fc))
      throw Error(ExitCode::kInvalidSpacing, "spacing f" + pt(T.origin + g) + " = " + std::to_string(fc) +
                                                 " is not a positive finite number inside the domain");
  }
  const double kf = r2 / (fc * fc) * b2_inv_;
  double key = kf;
  if (exempt) *exempt = false;
  if (rho2_inv_ > 0) {
    const double ex = c.x - b.x, ey = c.y - b.y;
    const double e2 = ex * ex + ey * ey;
    // Shortest edge and the vertex opposite it (where the smallest angle is).
    double l2 = b2;
    int opp = 2;  // edge a-b is opposite c
    if (c2 < l2) { l2 = c2; opp = 1; }
    if (e2 < l2) { l2 = e2; opp = 0; }
    const double ka = r2 / l2 * rho2_inv_;
    if (ka > 1 && ka > kf) {
      // Why exempt: an angle forced by two input segments (or by two shell vertices around the
      // same input apex) cannot be improved by splitting; Triangle leaves these alone too.
      const Index vo = T.corner(t, opp);
      const HalfEdge h_in = 3 * t + static_cast<Index>((opp + 2) % 3);  // edge ending at vo
      const HalfEdge h_out = 3 * t + static_cast<Index>(opp);           // edge leaving vo
      const Index p = T.org(3 * t + (opp + 1) % 3), q = T.org(3 * t + (opp + 2) % 3);
      const bool input_angle = T.kind(vo) == VertexKind::kInput && T.constrained(h_in) && T.constrained(h_out);
      if (input_angle || shell_apex_equal(p, q)) {
        if (exempt) *exempt = true;
        return kf > 1 ? kf : 0;
      }
      key = ka;
    }
  }
  if (!opt_.region_max_area.empty()) {  // regional area constraint
    const std::int32_t r = T.region(t);
    if (r >= 0 && static_cast<std::size_t>(r) < opt_.region_max_area.size() && opt_.region_max_area[r] > 0) {
      const double area = 0.5 * std::fabs(bx * cy - by * cx);
      if (area > opt_.region_max_area[r]) key = std::max(key, std::max(area / opt_.region_max_area[r], 1.0 + 1e-9));
    }
  }
  return key > 1 ? key : 0;
}

Refiner::~Refiner() = default;

void Refiner::push_bad(TriangleId t, double key2) {
  // Morton code of the first corner (the triangle is in cache now), for the queue's spatial order.
  queue_.push(bucket_of(key2), {t, tri_.corner(t, 2), zframe_.code(tri_.point(tri_.corner(t, 0)))});
}

void Refiner::evaluate(TriangleId t) {
  ++stats_.triangles_tested;
  bool exempt = false;
  const double k = badness(t, &exempt);
  if (front_) {
    front_->set_key(t, k > 1 ? k : 0);  // queued by queue_fresh
    return;
  }
  if (k > 1) push_bad(t, k);
}

// Why: two segments meeting at a small input angle encroach each other's subsegments all the
// way into the apex (the strip between them is thinner than any subsegment), which never ends.
// A vertex on a segment of the same small-angle cluster (sharing an input endpoint at less than
// 60 degrees) therefore does not count as encroaching; triangles there are still refined until
// R/f(c) <= B, which is bounded because f is.
bool Refiner::cluster_pair(Index s1i, Index s2i) const {
  if (s1i == kNoId || s2i == kNoId || s1i == s2i) return false;
  const auto& T = tri_;
  const auto& s1 = T.input_segments()[s1i];
  const auto& s2 = T.input_segments()[s2i];
  Index apex = kNoId, o1 = kNoId, o2 = kNoId;
  if (s1.a == s2.a) { apex = s1.a; o1 = s1.b; o2 = s2.b; }
  else if (s1.a == s2.b) { apex = s1.a; o1 = s1.b; o2 = s2.a; }
  else if (s1.b == s2.a) { apex = s1.b; o1 = s1.a; o2 = s2.b; }
  else if (s1.b == s2.b) { apex = s1.b; o1 = s1.a; o2 = s2.a; }
  if (apex == kNoId) return false;
  const Point2 u = T.point(o1) - T.point(apex), w = T.point(o2) - T.point(apex);
  const double cross = std::fabs(u.x * w.y - u.y * w.x), d = dot(u, w);
  return d > 0 && cross < std::sqrt(3.0) * d;  // angle < 60 degrees
}

bool Refiner::same_cluster(Index v, Index a, Index b) const {
  return cluster_pair(tri_.segment_of_vertex(v), tri_.segment_of(a, b));
}

void Refiner::check_encroached_edges(TriangleId t) {
  const auto& T = tri_;
  for (int k = 0; k < 3; ++k) {
    const HalfEdge h = 3 * t + static_cast<Index>(k);
    if (!T.constrained(h)) continue;
    const Index a = T.org(h), b = T.dst(h), c = T.apex(h);
    if (diametral(T.point(a), T.point(b), T.point(c)) > 0 && !same_cluster(c, a, b)) enc_.push_back({a, b});
  }
}

void Refiner::reserve(double expected_triangles) {
  if (!(expected_triangles > 0) || expected_triangles > 4e9) return;
  // Why: growing by doubling would briefly hold old and new arrays (3x peak memory).
  const auto nt = static_cast<std::size_t>(expected_triangles * 1.1) + 64;
  tri_.reserve(nt, nt / 2 + 64);
  if (front_) front_->reserve(nt);
}

void Refiner::init() {
  for (TriangleId t = 0; t < tri_.num_slots(); ++t) {
    if (tri_.dead(t)) continue;
    check_encroached_edges(t);
    evaluate(t);
  }
  if (front_) {
    std::vector<TriangleId> live;
    for (TriangleId t = 0; t < tri_.num_slots(); ++t)
      if (!tri_.dead(t)) live.push_back(t);
    queue_fresh(live, kNoId);
  }
}


Point2 Refiner::split_point(Index a, Index b, Index* apex, int* shell_exp) const {
  const auto& T = tri_;
  const Point2 pa = T.point(a), pb = T.point(b);
  const bool ia = T.kind(a) == VertexKind::kInput, ib = T.kind(b) == VertexKind::kInput;
  *apex = kNoId;
  if (ia != ib) {
    // Concentric shells (Ruppert; Shewchuk's Triangle): split at a power-of-two distance from
    // the input vertex, so that segments sharing it are split on the same circles and cannot
    // encroach each other forever at a small angle.
    const double len = dist(pa, pb);
    *apex = ia ? a : b;
    const Point2 o = ia ? pa : pb, q = ia ? pb : pa;
    *shell_exp = static_cast<int>(std::lround(std::log2(len * 0.5)));
    const double s = std::ldexp(1.0, *shell_exp) / len;
    return {o.x + s * (q.x - o.x), o.y + s * (q.y - o.y)};
  }
  return {0.5 * (pa.x + pb.x), 0.5 * (pa.y + pb.y)};
}

void Refiner::split_subsegment(Index a, Index b) {
  auto& T = tri_;
  const HalfEdge h = T.find_subsegment(a, b);
  if (h == kNoId) return;  // a stale entry: the subsegment was split meanwhile
  const Point2 pa = T.point(a), pb = T.point(b);
  Index apex = kNoId;
  int shell_exp = 0;
  const Point2 m = split_point(a, b, &apex, &shell_exp);
  if (m == pa || m == pb)
    throw Error(ExitCode::kWorkLimit, "cannot split subsegment " + pt(T.origin + pa) + "-" + pt(T.origin + pb) +
                                          " further: the spacing is below floating-point resolution there");
  if (!ins_.build_cavity(m, {cdt::LocateKind::kOnEdge, h})) {
    // A rounded split point off the segment's line fell behind a neighbouring constraint: the
    // geometry is at floating-point resolution there (a resolution limit, not a bug).
    if (predicates::orient2d(pa, pb, m) != 0)
      throw Error(ExitCode::kWorkLimit, "cannot split subsegment " + pt(T.origin + pa) + "-" + pt(T.origin + pb) +
                                            ": its rounded midpoint falls behind a neighbouring constraint (the input "
                                            "has features near floating-point resolution there)");
    throw Error(ExitCode::kInternal, "could not split subsegment at " + pt(T.origin + m));
  }
  const Index v = ins_.commit(m, VertexKind::kSegment);
  if (apex != kNoId) {
    const Index i = T.segment_vertex_index(v);
    if (shell_.size() <= i) shell_.resize(i + 1);
    shell_[i] = {apex, shell_exp};
  }
  ++stats_.segment_splits;
  for (TriangleId t : ins_.new_triangles()) {
    check_encroached_edges(t);
    evaluate(t);
  }
  if (front_) queue_fresh(ins_.new_triangles(), v);
}

// Why the give-up rule: a triangle that is bad only by the --min-angle criterion next to a
// small input angle can ask for subsegment splits forever (each split makes a smaller skinny
// triangle). As in Shewchuk's "Terminator", such a triangle may split a subsegment of a
// small-angle cluster only if the pieces are no shorter than its own shortest edge; otherwise it
// is left (counted as exempt). Subsegments outside clusters are always split (Ruppert's case).
// Triangles bad by R/f(c) > B are always split: that is the FDR guarantee.
bool Refiner::may_split_for(const BadEntry& e, const std::vector<std::pair<Index, Index>>& segs) const {
  const auto& T = tri_;
  const Index ea = T.org(3 * e.t), eb = T.org(3 * e.t + 1), ec = e.c;
  const Point2 a = T.point(ea), b = T.point(eb), c = T.point(ec);
  double r2;
  const Point2 cc = geom::circumcentre(a, b, c, &r2);
  const double fc = f_(cc);
  if (!(fc > 0) || r2 / (fc * fc) * b2_inv_ > 1) return true;  // R/f-bad (or f undefined there)
  // A triangle spanning the strip between two segments of a small-angle cluster is skinny
  // because of the input; it is left alone (refining it would march into the apex forever).
  const Index sa = T.segment_of_vertex(ea), sb = T.segment_of_vertex(eb), sc = T.segment_of_vertex(ec);
  if (cluster_pair(sa, sb) || cluster_pair(sb, sc) || cluster_pair(sc, sa)) return false;
  const double lmin = std::sqrt(std::min({norm2(b - a), norm2(c - b), norm2(a - c)}));
  for (const auto& [p, q] : segs) {
    const Index s = T.segment_of(p, q);
    if (s == kNoId || !in_cluster_[s]) continue;
    Index apex;
    int ex;
    const Point2 m = split_point(p, q, &apex, &ex);
    if (std::min(dist(T.point(p), m), dist(m, T.point(q))) < lmin) return false;
  }
  return true;
}

// Whether the smallest angle of (a, b, c) is below angle_split_floor_deg: sin(theta) = l / (2R).
bool Refiner::below_floor(Point2 a, Point2 b, Point2 c) const {
  if (!(opt_.angle_split_floor_deg > 0)) return false;
  double r2;
  geom::circumcentre(a, b, c, &r2);
  const double l2 = std::min({norm2(b - a), norm2(c - b), norm2(a - c)});
  const double s = std::sin(opt_.angle_split_floor_deg * std::numbers::pi / 180.0);
  return l2 < 4.0 * s * s * r2;
}

// Whether (a, b, c) is bad only by the angle bound (not R/f(c)-bad, no area constraints).
bool Refiner::angle_only(Point2 a, Point2 b, Point2 c) const {
  if (!(rho2_inv_ > 0) || !opt_.region_max_area.empty()) return false;
  double r2;
  const Point2 cc = geom::circumcentre(a, b, c, &r2);
  const double fc = f_(cc);
  return fc > 0 && std::isfinite(fc) && !(r2 / (fc * fc) * b2_inv_ > 1);
}

// Where a bad triangle is split. R/f(c)-bad (the FDR rule) or over its region's area: its
// circumcenter. Bad only by the --min-angle bound: Ungor's off-center when it is nearer than the
// circumcenter, the point on the shortest edge's bisector from which that edge is seen at a little
// more than the bound angle (the new triangle on that edge is then good). Why: the circumcenter of
// a skinny triangle lies far beyond its short edge, often across a narrow channel next to the
// other bank, where it encroaches and splits bank segments; the off-center refines only as far as
// the angle needs (Triangle 1.6 does the same by default). The FDR bound is untouched: no
// R/f(c)-bad triangle is split anywhere but at its circumcenter.
Point2 Refiner::steiner_point(Point2 a, Point2 b, Point2 c, bool angle_bad_only) const {
  const Point2 cc = geom::circumcentre(a, b, c);
  if (!angle_bad_only || !opt_.off_centers) return cc;
  Point2 p = a, q = b;
  double l2 = norm2(b - a);
  if (norm2(c - b) < l2) { l2 = norm2(c - b); p = b; q = c; }
  if (norm2(a - c) < l2) { l2 = norm2(a - c); p = c; q = a; }
  const Point2 m{0.5 * (p.x + q.x), 0.5 * (p.y + q.y)};
  const double dm = dist(m, cc);
  const double h = kOffCenter * 0.5 * std::sqrt(l2) * off_cot_;
  if (!(dm > h)) return cc;
  return m + (h / dm) * (cc - m);
}

void Refiner::split_triangle(const BadEntry& e) {
  auto& T = tri_;
  const Point2 a = T.point(T.org(3 * e.t)), b = T.point(T.org(3 * e.t + 1)), c = T.point(e.c);
  const bool angle = angle_only(a, b, c);  // bad only by the angle bound
  const Point2 cc = steiner_point(a, b, c, angle);
  const cdt::Location loc = cdt::locate_straight(T, e.t, cc);
  seg_tmp_.clear();
  if (loc.kind == cdt::LocateKind::kBlocked) {
    if (loc.he == kNoId) throw Error(ExitCode::kInternal, "point location failed near " + pt(T.origin + cc));
    // The circumcenter lies beyond a subsegment; it encroaches the first one crossed.
    seg_tmp_.push_back({T.org(loc.he), T.dst(loc.he)});
  } else if (loc.kind == cdt::LocateKind::kOnVertex) {
    ++stats_.stuck;
    give_up(e.t);
    return;
  } else if (loc.kind == cdt::LocateKind::kOnEdge && T.constrained(loc.he)) {
    seg_tmp_.push_back({T.org(loc.he), T.dst(loc.he)});
  } else {
    if (!ins_.build_cavity(cc, loc)) {
      ++stats_.stuck;
      give_up(e.t);
      return;
    }
    for (HalfEdge h : ins_.boundary())
      if (T.constrained(h) && diametral(T.point(T.org(h)), T.point(T.dst(h)), cc) > 0)
        seg_tmp_.push_back({T.org(h), T.dst(h)});
    if (seg_tmp_.empty()) {
      const Index v = ins_.commit(cc, VertexKind::kFree);
      ++stats_.circumcenters;
      after_insert(v);
      return;
    }
    ins_.abort();
  }
  // Rejected: split the encroached subsegments instead, then retry the triangle.
  ++stats_.rejected_circumcenters;
  // Angle-only splits yield to the spacing at the boundary (RefineOptions::angle_split_min_f).
  if (opt_.angle_split_min_f > 0 && angle && !below_floor(a, b, c)) {
    for (const auto& [p, q] : seg_tmp_) {
      Index apex;
      int ex;
      const Point2 m = split_point(p, q, &apex, &ex);
      if (std::min(dist(T.point(p), m), dist(m, T.point(q))) < opt_.angle_split_min_f * f_(m)) {
        ++stats_.exempt_small_angle;
        give_up(e.t);
        return;
      }
    }
  }
  if (!may_split_for(e, seg_tmp_)) {
    ++stats_.exempt_small_angle;
    give_up(e.t);
    return;
  }
  enc_.insert(enc_.end(), seg_tmp_.begin(), seg_tmp_.end());
  const double k = badness(e.t);
  if (k > 1) push_bad(e.t, k);
}

void Refiner::after_insert(Index v) {
  for (TriangleId t : ins_.new_triangles()) evaluate(t);
  if (front_) queue_fresh(ins_.new_triangles(), v);
}

RefineLeftovers Refiner::leftovers(bool with_r_over_f) const {
  const auto& T = tri_;
  if (!with_r_over_f && !(rho2_inv_ > 0)) return {};  // no angle test: nothing to count
  auto count = [&](TriangleId lo, TriangleId hi, RefineLeftovers& r) {
    for (TriangleId t = lo; t < hi; ++t) {
      if (T.dead(t)) continue;
      const Point2 a = T.point(T.corner(t, 0)), b = T.point(T.corner(t, 1)), c = T.point(T.corner(t, 2));
      double r2;
      const Point2 cc = geom::circumcentre(a, b, c, &r2);
      // Bad by R/f(c) first (those are not counted as bad by angle); without that count, f only
      // where the angle test holds (a raster spacing at every circumcentre costs more than the
      // whole count).
      const auto rf_bad = [&] {
        const double fc = f_(cc);
        return fc > 0 && r2 / (fc * fc) * b2_inv_ > 1;
      };
      if (with_r_over_f && rf_bad()) { ++r.r_over_f_bad; continue; }
      if (rho2_inv_ > 0) {
        const double l2 = std::min({norm2(b - a), norm2(c - b), norm2(a - c)});
        if (r2 / l2 * rho2_inv_ > 1 && (with_r_over_f || !rf_bad())) ++r.angle_bad;
      }
    }
  };
  // Two halves at once when f may be evaluated from two threads (counts: the same sums).
  const TriangleId n = T.num_slots();
  RefineLeftovers r, r2;
  if (max_threads() > 1 && f_.thread_safe() && n >= 65536) {
    run_beside([&] { count(n / 2, n, r2); }, [&] { count(0, n / 2, r); });
    r.r_over_f_bad += r2.r_over_f_bad;
    r.angle_bad += r2.angle_bad;
  } else {
    count(0, n, r);
  }
  return r;
}

bool Refiner::step() {
  if (stats_.steiner() >= opt_.max_steiner)
    throw Error(ExitCode::kWorkLimit, "Steiner point cap reached (--max-steiner " + std::to_string(opt_.max_steiner) +
                                          "); the spacing function asks for more vertices than allowed");
  while (!enc_.empty()) {
    const auto [a, b] = enc_.back();
    enc_.pop_back();
    const std::uint64_t before = stats_.segment_splits;
    split_subsegment(a, b);
    if (stats_.segment_splits != before) return true;
  }
  if (!conforming_done_) record_conforming();  // no encroached subsegment left: this is M_c
  if (front_ && step_front()) return true;
  BadEntry e;
  while (queue_.pop(&e)) {
    // The entries a few places down the bucket are known now: fetch what they will touch first.
    constexpr std::size_t kAhead = 6;
    if (const BadEntry* n = queue_.ahead(kAhead)) tri_.prefetch(n->t, n->c);
    const auto& T = tri_;
    // Stale entry: the triangle was destroyed (and its slot maybe reused). During refinement every
    // triangle is made by Inserter::commit with the new vertex as third corner, so slot and third
    // corner identify a triangle (the CDT's own triangles are never made again).
    if (T.dead(e.t) || T.org(3 * e.t + 2) != e.c) continue;
    split_triangle(e);
    return true;
  }
  if (front_ && queue_missed()) return true;
  return !enc_.empty();
}

// D of the conforming mesh (see RefineStats): the exact nearest other vertex of every vertex
// (all vertices, across constraints and land too, as the paper's nn), by a 2-d tree (clustered
// inputs, such as features 1e-12 of the domain, defeat a uniform grid).
void Refiner::record_conforming() {
  conforming_done_ = true;
  const Triangulation& T = tri_;
  std::vector<Point2> pts;
  for (std::size_t v = 0; v < T.num_vertices(); ++v)
    if (T.kind(v) != VertexKind::kSuper && T.vertex_edge(v) != kNoId) pts.push_back(T.point(v));
  stats_.conforming_vertices = pts.size();
  if (pts.size() < 2) return;
  const KdTree tree(pts);
  double best_ratio = std::numeric_limits<double>::infinity();
  Point2 at{0, 0};
  for (std::size_t k = 0; k < tree.size(); ++k) {
    const Point2 p = pts[tree.id_at(k)];
    const double fv = f_(p);
    if (!(fv > 0)) continue;
    const double ratio = std::sqrt(tree.nearest_sq_at(k)) / fv;
    // ties: the smaller point (the tree's order is not the input's)
    if (ratio < best_ratio || (ratio == best_ratio && (p.x < at.x || (p.x == at.x && p.y < at.y)))) {
      best_ratio = ratio;
      at = p;
    }
  }
  if (std::isfinite(best_ratio)) {
    stats_.conforming_D = best_ratio;
    stats_.conforming_D_at = T.origin + at;
  }
}

void Refiner::run() {
  std::uint64_t tick = 0, last_steiner = stats_.steiner(), idle = 0;
  while (step()) {
    // Never hang: every action either inserts a vertex or retires a queue entry; a long run of
    // actions without an insertion means a bug, reported instead of spinning.
    if (stats_.steiner() != last_steiner) {
      last_steiner = stats_.steiner();
      idle = 0;
    } else if (++idle > 8 * tri_.num_slots() + 100000) {
      throw Error(ExitCode::kInternal, "refinement made no progress (" + std::to_string(idle) + " steps without a new vertex)");
    }
    if (opt_.progress && (++tick & 4095) == 0) {
      const double frac = opt_.expected_steiner > 0 ? std::min(0.99, stats_.steiner() / opt_.expected_steiner) : 0.0;
      if (!opt_.progress(frac, "refine")) throw Error(ExitCode::kCancelled, "cancelled during refinement");
    }
  }
}

double estimate_triangles(const Triangulation& T, const sizing::SizingField& f, double bound) {
  // Calibration: FDR at bound B produces about kC / (B f)^2 triangles per unit area (measured on
  // the paper's square cases).
  const double kC = 1.5;  // measured/estimated = 0.95..1.1 on f1, f2 (B = 0.5..1.41), constant f
  double total = 0;
  struct Tri { Point2 a, b, c; int depth; };
  std::vector<Tri> stack;
  for (TriangleId t = 0; t < T.num_slots(); ++t) {
    if (T.dead(t)) continue;
    stack.push_back({T.point(T.corner(t, 0)), T.point(T.corner(t, 1)), T.point(T.corner(t, 2)), 0});
    // Why adaptive: a coarse CDT triangle may span a wide range of f; subdivide where the
    // estimate inside one piece is large, so the sum tracks the integral of 1/f^2.
    while (!stack.empty()) {
      Tri q = stack.back();
      stack.pop_back();
      const double area = 0.5 * std::fabs((q.b.x - q.a.x) * (q.c.y - q.a.y) - (q.b.y - q.a.y) * (q.c.x - q.a.x));
      const Point2 g{(q.a.x + q.b.x + q.c.x) / 3, (q.a.y + q.b.y + q.c.y) / 3};
      const double fg0 = f(g);
      if (!(fg0 > 0) || !std::isfinite(fg0)) {
        std::ostringstream m;
        m.precision(15);
        m << "spacing f(" << T.origin.x + g.x << ", " << T.origin.y + g.y << ") = " << fg0
          << " is not a positive finite number inside the domain";
        throw Error(ExitCode::kInvalidSpacing, m.str());
      }
      const double fg = fg0 * bound;
      const double n = kC * area / (fg * fg);
      bool split = n > 4 && q.depth < 16 && total < 1e12;
      if (split) {
        // Only where f varies across the piece; where it is nearly constant the estimate holds.
        const double fa = f(q.a), fb = f(q.b), fc = f(q.c);
        const double lo = std::min({fa, fb, fc, fg / bound}), hi = std::max({fa, fb, fc, fg / bound});
        split = !(hi <= 1.25 * lo);
      }
      if (split) {
        const Point2 ab = 0.5 * (q.a + q.b), bc = 0.5 * (q.b + q.c), ca = 0.5 * (q.c + q.a);
        stack.push_back({q.a, ab, ca, q.depth + 1});
        stack.push_back({ab, q.b, bc, q.depth + 1});
        stack.push_back({ca, bc, q.c, q.depth + 1});
        stack.push_back({ab, bc, ca, q.depth + 1});
      } else {
        total += n;
      }
    }
  }
  return total;
}

}  // namespace fdr::refine
