// Quality smoothing of free Steiner vertices with exact acceptance tests (see smooth.hpp).
#include "refine/smooth.hpp"
#include "refine/smooth_fan.hpp"

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <utility>
#include <vector>

#include "base/point_cells.hpp"
#include "base/step_laps.hpp"
#include "base/parallel.hpp"
#include "base/threads.hpp"
#include "base/triangle_geometry.hpp"
#include "predicates/predicates.hpp"

namespace fdr::refine {
namespace {

using mesh::next_he;
using mesh::prev_he;

constexpr std::uint32_t kAnyBlock = 0xffffffffu;  // serial phase: no block restriction
constexpr std::uint32_t kNoBlock = 0xfffffffeu;   // super or dead vertices: in no block

// What every worker reads (and the dirty flags, which a worker writes only for its own block's
// vertices in the parallel phase).
struct Shared {
  mesh::Triangulation& t;
  const sizing::SizingField& f;
  SmoothOptions o;
  double floor_key = 0;              // geom::min_angle_sin2 of --min-angle
  // Per vertex, its block in each of the two blockings (see smooth(): the edges of the second lie
  // inside the blocks of the first, so the vertices the first defers mostly lie inside one of the
  // second).
  std::vector<std::uint32_t> block, block2;
  std::vector<char> dirty;           // per vertex
  // Pairs of vertices across a constraint (the other side of a thin strip of land, of a
  // breakline): a segment vertex and a vertex within f of it that is not its mesh neighbour, both
  // ways; v's partners are hidden[hidden_at[v] .. hidden_at[v + 1]). Empty when there are none.
  std::vector<std::uint32_t> hidden_at;
  std::vector<Index> hidden;
};

// Interleaves the bits of x and y (x in the even bits).
std::uint64_t morton(std::uint32_t x, std::uint32_t y) {
  auto spread = [](std::uint64_t v) {
    v = (v | (v << 16)) & 0x0000ffff0000ffffull;
    v = (v | (v << 8)) & 0x00ff00ff00ff00ffull;
    v = (v | (v << 4)) & 0x0f0f0f0f0f0f0f0full;
    v = (v | (v << 2)) & 0x3333333333333333ull;
    v = (v | (v << 1)) & 0x5555555555555555ull;
    return v;
  };
  return spread(x) | (spread(y) << 1);
}

// One thread's state: tries vertices of one block (or, in the serial phase, any vertex).
class Smoother {
 public:
  enum class Result { kRejected, kKept, kDeferred };

  explicit Smoother(Shared& s)
      : sh_(s), t_(s.t), f_(s.f), o_(s.o), floor_key_(s.floor_key), lipschitz_(s.f.lipschitz()) {}

  // Tries to move v. With block != kAnyBlock, v is tried only if every triangle of its star and
  // of every flip lies inside that block (all three vertices in it); otherwise nothing changes
  // and the result is kDeferred. Triangles with vertices of two blocks are then never changed,
  // and a vertex whose star has one never moves, so what a block does depends on nothing another
  // block does at the same time.
  Result try_move(Index v, std::uint32_t block, const std::vector<std::uint32_t>* blocks = nullptr) {
    block_ = block;
    blocks_ = blocks ? blocks : &sh_.block;
    deferred_ = false;
    const bool ok = try_vertex(v);
    if (deferred_) return Result::kDeferred;
    return ok ? Result::kKept : Result::kRejected;
  }
  const std::vector<TriangleId>& touched() const { return touched_; }

 private:
  // The star of v: half-edges h leaving v (org(h) == v), counter-clockwise. False if the star
  // is open (v on the boundary of the mesh) or a neighbour is a super vertex.
  bool star(Index v, std::vector<HalfEdge>& hs) const {
    hs.clear();
    open_ = false;
    // Counter-clockwise from vhe[v]; only a fan that turns out open (v on the boundary of the
    // mesh) is walked again from its clockwise end.
    HalfEdge h0 = t_.vertex_edge(v);
    HalfEdge h = h0;
    for (std::size_t guard = 0; guard < 1024; ++guard) {
      if (t_.kind(t_.dst(h)) == mesh::VertexKind::kSuper) return false;
      hs.push_back(h);
      const HalfEdge back = t_.twin(prev_he(h));
      if (back == kNoId) { open_ = true; break; }
      h = back;
      if (h == h0) return in_block(hs);
    }
    if (!open_) return false;
    hs.clear();
    for (std::size_t guard = 0; guard < 1024; ++guard) {  // to the clockwise end of the fan
      const HalfEdge tw = t_.twin(h0);
      if (tw == kNoId) break;
      h0 = next_he(tw);
    }
    h = h0;
    for (std::size_t guard = 0; guard < 1024; ++guard) {
      if (t_.kind(t_.dst(h)) == mesh::VertexKind::kSuper) return false;
      hs.push_back(h);
      const HalfEdge back = t_.twin(prev_he(h));
      if (back == kNoId) return in_block(hs);
      h = back;
    }
    return false;
  }

  // In the parallel phase: every star triangle has its three vertices in the block (else the
  // vertex is deferred to the serial phase).
  bool in_block(const std::vector<HalfEdge>& hs) const {
    if (block_ == kAnyBlock) return true;
    for (HalfEdge h : hs)
      if ((*blocks_)[t_.dst(h)] != block_ || (*blocks_)[t_.apex(h)] != block_) {
        deferred_ = true;
        return false;
      }
    if (!sh_.hidden_at.empty() && !hs.empty()) {  // their positions are read by improved()
      const Index v = t_.org(hs[0]);
      for (std::uint32_t k = sh_.hidden_at[v]; k < sh_.hidden_at[v + 1]; ++k)
        if ((*blocks_)[sh_.hidden[k]] != block_) {
          deferred_ = true;
          return false;
        }
    }
    return true;
  }

  // A segment vertex slides along its input segment: the line through that segment's input
  // endpoints, strictly between its two neighbours on it. False if v is not such a vertex (two
  // constrained spokes of one input segment).
  bool slide_line(Index v, Point2* a, Point2* b, double* t_lo, double* t_hi) const {
    Index nb[2];
    int n = 0;
    std::size_t seg = static_cast<std::size_t>(-1);
    auto consider = [&](HalfEdge h) {
      if (!t_.constrained(h)) return true;
      if (n == 2) return false;
      const Index u = t_.dst(h);
      const Index s = t_.segment_of(v, u);
      if (n == 1 && s != seg) return false;
      seg = s;
      nb[n++] = u;
      return true;
    };
    for (HalfEdge h : hs_)
      if (!consider(h)) return false;
    if (open_ && !hs_.empty()) {  // the last edge of an open fan (v -> apex of the last triangle)
      const HalfEdge last = prev_he(hs_.back());
      if (t_.constrained(last)) {
        const Index u = t_.org(last);
        const Index s = t_.segment_of(v, u);
        if (n == 2 || (n == 1 && s != seg)) return false;
        seg = s;
        nb[n++] = u;
      }
    }
    if (n != 2 || seg >= t_.input_segments().size()) return false;
    *a = t_.point(t_.input_segments()[seg].a);
    *b = t_.point(t_.input_segments()[seg].b);
    const Point2 d = *b - *a;
    const double l2 = norm2(d);
    if (!(l2 > 0)) return false;
    const double t0 = dot(t_.point(nb[0]) - *a, d) / l2, t1 = dot(t_.point(nb[1]) - *a, d) / l2;
    const double lo = std::min(t0, t1), hi = std::max(t0, t1);
    // Keep a margin of a tenth of the neighbour distance on each side.
    *t_lo = lo + 0.1 * (hi - lo);
    *t_hi = hi - 0.1 * (hi - lo);
    return *t_hi > *t_lo;
  }

  bool try_vertex(Index v) {
    if (!star(v, hs_)) return false;
    star_before();
    const bool on_segment = t_.kind(v) == mesh::VertexKind::kSegment;
    Point2 la, lb;
    double t_lo = 0, t_hi = 0;
    if (on_segment) {
      if (!slide_line(v, &la, &lb, &t_lo, &t_hi)) return false;
    } else if (open_) {
      return false;
    }
    const Point2 p0 = t_.point(v);
    // The star's summed quality with v at p, in the present topology: an attempt whose star
    // does not gain is skipped before any flip (Lawson flips rarely rescue it).
    auto star_sum = [&](Point2 p) {
      double sum = 0;
      for (HalfEdge h : hs_) sum += geom::mean_ratio_quality(p, t_.point(t_.dst(h)), t_.point(t_.apex(h)));
      return sum;
    };
    const double sum0 = star_sum(p0);
    {
      // First a step up the gradient of the star's summed quality (what the smoothing raises),
      // at 0.3, 0.1, 0.03 of the mean spoke length; then the ODT target (below). Why: the gradient
      // step keeps raising the mean quality where ODT alone has converged.
      Point2 g{0, 0};
      double lsum = 0;
      for (HalfEdge h : hs_) {
        const Point2 a = t_.point(t_.dst(h)), b = t_.point(t_.apex(h));
        const double A = 0.5 * geom::cross2(p0, a, b);
        const double S = norm2(a - p0) + norm2(b - p0) + norm2(a - b);
        const Point2 gA{0.5 * (a.y - b.y), 0.5 * (b.x - a.x)};
        const Point2 gS = 2.0 * (2.0 * p0 - a - b);
        g = g + (1.0 / (S * S)) * (S * gA - A * gS);
        lsum += std::sqrt(norm2(a - p0));
      }
      if (on_segment) { const Point2 d = lb - la; g = (dot(g, d) / norm2(d)) * d; }
      const double gl = std::sqrt(norm2(g));
      if (gl > 0 && std::isfinite(gl)) {
        const double L = lsum / hs_.size();
        for (double step : {0.3, 0.1, 0.03}) {
          Point2 p = p0 + (step * L / gl) * g;
          if (on_segment) {
            const Point2 d = lb - la;
            const double t = std::clamp(dot(p - la, d) / norm2(d), t_lo, t_hi);
            p = la + t * d;
          }
          if (p == p0 || !std::isfinite(p.x) || !std::isfinite(p.y)) break;
          if (!(star_sum(p) > sum0)) continue;
          if (attempt(v, p0, p)) return true;
          if (deferred_) return false;
          if (!flips_.empty()) {
            if (!star(v, hs_)) return false;
            star_before();
          }
        }
      }
    }
    // Then the ODT target (computed only now: most vertices took a gradient step).
    Point2 acc{0, 0};
    double wsum = 0;
    for (HalfEdge h : hs_) {
      const Point2 a = t_.point(t_.dst(h)), b = t_.point(t_.apex(h));
      const double ar = 0.5 * geom::cross2(p0, a, b);
      acc = acc + ar * geom::circumcentre(p0, a, b);
      wsum += ar;
    }
    if (!(wsum > 0)) return false;
    Point2 target = (1.0 / wsum) * acc;
    if (on_segment) {  // projected on the segment's line, within the neighbours' span
      const Point2 d = lb - la;
      const double t = std::clamp(dot(target - la, d) / norm2(d), t_lo, t_hi);
      target = la + t * d;
    }
    for (double step : {1.0, 0.5, 0.25}) {
      Point2 p = p0 + step * (target - p0);
      if (on_segment) {
        const Point2 d = lb - la;
        p = la + (dot(p - la, d) / norm2(d)) * d;
      }
      if (p == p0 || !std::isfinite(p.x) || !std::isfinite(p.y)) return false;
      if (!(star_sum(p) > sum0)) continue;
      if (attempt(v, p0, p)) return true;
      if (deferred_) return false;
      // An undone attempt restores the same triangles, but its flips may have renumbered their
      // half-edges: take the star again (unless there were none).
      if (!flips_.empty()) {
        if (!star(v, hs_)) return false;
        star_before();
      }
    }
    return false;
  }

  // Moves v to p, restores the constrained Delaunay property by Lawson flips, and keeps the
  // result only if the touched triangles are better (see smooth.hpp); else undoes everything.
  bool attempt(Index v, Point2 p0, Point2 p) {
    flips_.clear();
    // The move itself must keep every star triangle counter-clockwise (p in the star's kernel).
    for (HalfEdge h : hs_)
      if (predicates::orient2d(p, t_.point(t_.dst(h)), t_.point(t_.apex(h))) <= 0) return false;
    // The star's triangles as touch() would record them, from the values star_before() kept
    // (the same numbers in the same order: v is back at p0 after every undone attempt).
    touched_.clear();
    for (HalfEdge h : hs_) touched_.push_back(mesh::tri_of(h));
    before_min_ = star_min_;
    before_sum_ = star_sum_;
    before_angle_ = star_angle_;
    before_len2_ = star_len2_;
    before_lens_.assign(star_lens_.begin(), star_lens_.end());
    t_.set_point(v, p);
    moved_ = v;
    moved_from_ = p0;
    stack_.clear();
    for (HalfEdge h : hs_) {
      stack_.push_back(h);
      stack_.push_back(next_he(h));
    }
    bool ok = true;
    while (!stack_.empty()) {
      const HalfEdge e = stack_.back();
      stack_.pop_back();
      if (t_.constrained(e)) continue;
      const HalfEdge g = t_.twin(e);
      if (g == kNoId) continue;
      const Point2 a = t_.point(t_.org(e)), b = t_.point(t_.dst(e)), c = t_.point(t_.apex(e)), d = t_.point(t_.apex(g));
      if (predicates::incircle(a, b, c, d) <= 0) continue;
      if (predicates::orient2d(c, a, d) <= 0 || predicates::orient2d(d, b, c) <= 0) { ok = false; break; }
      if (block_ != kAnyBlock && (*blocks_)[t_.apex(g)] != block_) {  // the flip leaves the block
        ok = false;
        deferred_ = true;
        break;
      }
      if (flips_.size() >= 64) { ok = false; break; }
      touch(mesh::tri_of(e));
      touch(mesh::tri_of(g));
      const HalfEdge nd = flip(e);
      flips_.push_back({t_.org(nd), t_.dst(nd)});
      const TriangleId t1 = mesh::tri_of(nd), t2 = mesh::tri_of(t_.twin(nd));
      stack_.push_back(3 * t1);
      stack_.push_back(3 * t1 + 1);
      stack_.push_back(3 * t2);
      stack_.push_back(3 * t2 + 1);
    }
    if (ok) ok = improved();
    if (!ok) {
      // Undone in reverse order, each by its vertices: undoing a flip puts the pair back with
      // the two triangles exchanged between their slots, so a half-edge id kept from an
      // earlier flip may no longer name that flip's diagonal.
      for (std::size_t k = flips_.size(); k-- > 0;) flip(find_half_edge(flips_[k].first, flips_[k].second));
      t_.set_point(v, p0);
    }
    return ok;
  }

  void touch(TriangleId t) {
    // A short list (the star's triangles and at most two per flip): a scan beats a per-slot
    // stamp array, whose random accesses missed the cache.
    if (std::find(touched_.begin(), touched_.end(), t) != touched_.end()) return;
    touched_.push_back(t);
    add_before(t, before_min_, before_sum_, before_angle_, before_len2_, &before_lens_);
  }

  // Adds triangle t (as it is now) to the worst quality, summed quality, smallest angle key and
  // shortest squared edge of the triangles before a move.
  void add_before(TriangleId t, double& qmin, double& qsum, double& angle, double& len2,
                  std::vector<double>* lens) const {
    const Point2 a = t_.point(t_.corner(t, 0)), b = t_.point(t_.corner(t, 1)), c = t_.point(t_.corner(t, 2));
    const double q = geom::mean_ratio_quality(a, b, c);
    qmin = std::min(qmin, q);
    qsum += q;
    angle = std::min(angle, geom::min_angle_sin2(a, b, c));
    const double l0 = norm2(b - a), l1 = norm2(c - b), l2 = norm2(a - c);
    len2 = std::min({len2, l0, l1, l2});
    lens->insert(lens->end(), {l0, l1, l2});
  }

  // The star's triangles before any move, once per star (not once per attempt: up to six
  // attempts per vertex).
  void star_before() {
    star_min_ = 1e300;
    star_sum_ = 0;
    star_angle_ = 1e300;
    star_len2_ = 1e300;
    star_lens_.clear();
    for (HalfEdge h : hs_) add_before(mesh::tri_of(h), star_min_, star_sum_, star_angle_, star_len2_, &star_lens_);
  }

  // The touched triangles after the move: valid, R/f(c) <= B, no encroached subsegment, worst
  // quality not lower, summed quality higher, min angle not below min(before, --min-angle).
  bool improved() const {
    // Cheap tests first (orientation, quality sum and worst, angles, shortest edge): most
    // attempts fail there, before any encroachment test or evaluation of f.
    double nmin = 1e300, nsum = 0, nlen2 = 1e300;
    const double floor_angle = std::min(before_angle_, floor_key_);
    for (TriangleId t : touched_) {
      const Point2 a = t_.point(t_.corner(t, 0)), b = t_.point(t_.corner(t, 1)), c = t_.point(t_.corner(t, 2));
      // Without flips the touched triangles are the star's, whose orientation attempt() tested.
      if (!flips_.empty() && predicates::orient2d(a, b, c) <= 0) return false;
      const double q = geom::mean_ratio_quality(a, b, c);
      nmin = std::min(nmin, q);
      nsum += q;
      nlen2 = std::min({nlen2, norm2(b - a), norm2(c - b), norm2(a - c)});
      if (geom::min_angle_sin2(a, b, c) < floor_angle) return false;
    }
    // The worst touched triangle may get worse only while it stays above 0.8 (a 40-70-70 triangle):
    // the sum is what the smoothing raises.
    if (!(nmin >= std::min(before_min_, 0.8) && nsum > before_sum_)) return false;
    // Nor may the shortest touched edge get shorter, unless it stays above f/2 at the moved
    // vertex: a short edge sets the model's time step.
    // Nor may more touched edges be shorter than f/2 than before (each counted once per touched
    // triangle; the touched region's outline does not change): else a move could shorten a second
    // edge below f/2 next to one that already was.
    double fp = -1;  // f(p) at the moved vertex p once needed
    if (nlen2 < before_len2_) {
      fp = f_(t_.point(moved_));
      if (!(nlen2 >= 0.25 * fp * fp)) return false;
    } else {
      fp = f_(t_.point(moved_));
      const double thr = 0.25 * fp * fp;
      if (nlen2 < thr) {
        std::size_t nb = 0, na = 0;
        for (double l : before_lens_) nb += l < thr;
        for (TriangleId t : touched_) {
          const Point2 a = t_.point(t_.corner(t, 0)), b = t_.point(t_.corner(t, 1)), c = t_.point(t_.corner(t, 2));
          na += (norm2(b - a) < thr) + (norm2(c - b) < thr) + (norm2(a - c) < thr);
        }
        if (na > nb) return false;
      }
    }
    const Point2 p = t_.point(moved_);
    // Nor may it come nearer to a vertex across a constraint (Shared::hidden), unless it stays
    // above f/2 from it: the report's nn (Theorem 4.4) is over all vertices.
    if (!sh_.hidden_at.empty())
      for (std::uint32_t k = sh_.hidden_at[moved_]; k < sh_.hidden_at[moved_ + 1]; ++k) {
        const Point2 u = t_.point(sh_.hidden[k]);
        const double dn = norm2(p - u);
        if (!(dn < norm2(moved_from_ - u))) continue;
        if (!(fp >= 0)) fp = f_(p);
        if (!(dn >= 0.25 * fp * fp)) return false;
      }
    for (TriangleId t : touched_) {
      const Point2 a = t_.point(t_.corner(t, 0)), b = t_.point(t_.corner(t, 1)), c = t_.point(t_.corner(t, 2));
      for (int k = 0; k < 3; ++k) {
        const HalfEdge h = 3 * t + static_cast<HalfEdge>(k);
        if (t_.constrained(h) && predicates::encroaches(t_.point(t_.org(h)), t_.point(t_.dst(h)), t_.point(t_.apex(h))))
          return false;
      }
      double r2 = 0;
      const Point2 cc = geom::circumcentre(a, b, c, &r2);
      if (lipschitz_ >= 0) {
        // f is L-Lipschitz: f(cc) >= f(p) - L |cc - p| at the moved vertex p, so R <= B (f(p) -
        // L |cc - p|) implies R <= B f(cc) without evaluating f there (one evaluation per move
        // instead of one per triangle). The factor 1 - 1e-9 covers the rounding of both sides
        // (relative errors near 1e-15); only this sufficient test uses it, the test below is
        // the one refinement makes.
        if (!(fp >= 0)) fp = f_(p);
        const double d = std::sqrt(norm2(cc - p)), R = std::sqrt(r2);
        if (R + o_.bound * lipschitz_ * d <= o_.bound * fp * (1 - 1e-9)) continue;
      }
      const double fc = f_(cc);
      if (!(fc > 0) || !std::isfinite(fc) || r2 > o_.bound * o_.bound * fc * fc) return false;
    }
    return true;
  }

  // The half-edge from u to w (an interior edge of the triangulation, found around u).
  HalfEdge find_half_edge(Index u, Index w) const {
    const HalfEdge h0 = t_.vertex_edge(u);
    HalfEdge h = h0;
    for (std::size_t guard = 0; guard < 4096; ++guard) {  // counter-clockwise
      if (t_.dst(h) == w) return h;
      const HalfEdge back = t_.twin(prev_he(h));
      if (back == kNoId || back == h0) break;
      h = back;
    }
    h = h0;
    for (std::size_t guard = 0; guard < 4096; ++guard) {  // clockwise
      const HalfEdge tw = t_.twin(h);
      if (tw == kNoId) break;
      h = next_he(tw);
      if (h == h0) break;
      if (t_.dst(h) == w) return h;
    }
    throw std::logic_error("smooth: flipped edge not found while undoing a move");
  }

  // Flips the edge of half-edge e (a->b in triangle (a,b,c), twin b->a in (b,a,d)) into the
  // diagonal c-d; returns the new half-edge d->c. Flipping that half-edge again restores the
  // pair (in the same two slots).
  //
  //        c                 c
  //       / \               /|\   .
  //      a---b     ->      a | b
  //       \ /               \|/   .
  //        d                 d
  HalfEdge flip(HalfEdge e) {
    const HalfEdge g = t_.twin(e);
    const TriangleId t1 = mesh::tri_of(e), t2 = mesh::tri_of(g);
    const Index a = t_.org(e), b = t_.dst(e), c = t_.apex(e), d = t_.apex(g);
    const HalfEdge h1 = next_he(e), h2 = prev_he(e);  // b->c, c->a
    const HalfEdge g1 = next_he(g), g2 = prev_he(g);  // a->d, d->b
    const HalfEdge th1 = t_.twin(h1), th2 = t_.twin(h2), tg1 = t_.twin(g1), tg2 = t_.twin(g2);
    const bool ch1 = t_.constrained(h1), ch2 = t_.constrained(h2), cg1 = t_.constrained(g1), cg2 = t_.constrained(g2);
    // t1 = (c, a, d), t2 = (d, b, c)
    t_.set_corners(t1, c, a, d);
    t_.set_corners(t2, d, b, c);
    t_.clear_constraints(t1);
    t_.set_constrained(3 * t1, ch2);
    t_.set_constrained(3 * t1 + 1, cg1);
    t_.clear_constraints(t2);
    t_.set_constrained(3 * t2, cg2);
    t_.set_constrained(3 * t2 + 1, ch1);
    t_.link(3 * t1, th2);
    t_.link(3 * t1 + 1, tg1);
    t_.link(3 * t2, tg2);
    t_.link(3 * t2 + 1, th1);
    t_.link(3 * t1 + 2, 3 * t2 + 2);
    t_.set_vertex_edge(c, 3 * t1);
    t_.set_vertex_edge(a, 3 * t1 + 1);
    t_.set_vertex_edge(d, 3 * t2);
    t_.set_vertex_edge(b, 3 * t2 + 1);
    return 3 * t1 + 2;
  }

  Shared& sh_;
  mesh::Triangulation& t_;
  const sizing::SizingField& f_;
  const SmoothOptions& o_;
  std::vector<HalfEdge> hs_, stack_;
  std::vector<std::pair<Index, Index>> flips_;  // new diagonals (org, dst) in flip order
  mutable bool open_ = false;  // the last star() was an open fan
  std::vector<TriangleId> touched_;
  double before_min_ = 0, before_sum_ = 0, before_angle_ = 0, before_len2_ = 0;  // angles as geom::min_angle_sin2
  double star_min_ = 0, star_sum_ = 0, star_angle_ = 0, star_len2_ = 0;  // the same over the star (star_before)
  std::vector<double> before_lens_, star_lens_;  // squared edge lengths of the touched / star triangles
  double floor_key_ = 0;  // geom::min_angle_sin2 of --min-angle
  double lipschitz_ = -1;  // of f, when known (else negative)
  Index moved_ = 0;  // the vertex of the current attempt
  Point2 moved_from_{0, 0};  // its position before
  std::uint32_t block_ = kAnyBlock;  // the block of the current try
  const std::vector<std::uint32_t>* blocks_ = nullptr;  // the blocking it belongs to (Shared::block or block2)
  mutable bool deferred_ = false;  // the current try needs a triangle outside block_
};

// The two blockings of the live vertices (Shared::block, block2) and the movable vertices of each
// block of the first, in index order. Each blocking cuts a Morton order of the vertices at whole
// cells of a quadtree level (at least half as many cells as vertices, at most 2^10 a side): a
// vertex's block is the number of live vertices in the cells before its own divided by the block
// size, so a block is a run of cells (a cell of more vertices is a block of its own), found by
// counting, without a sort. Why Morton: neighbours in the mesh are then mostly neighbours in
// memory. The second blocking takes the cells of the level above of the positions shifted by
// S = 0b0101...01: blocks of either are runs of quadtree cells, and S mod 2^k is about a third or
// two thirds of 2^k at every level k, so the edges of the second lie well inside the blocks of
// the first (shifting the cut along the first order would leave every edge between blocks that
// are far apart in that order where it is). Inside a block the vertices go in index order
// (refinement's insertion order), which smooths better than Morton order. The blocks depend only
// on the mesh, never on the thread count.
struct Blocking {
  Box2 box;                              // of the live vertices
  std::size_t nblocks = 0, nblocks2 = 0;
  std::vector<std::vector<Index>> free;  // movable vertices of each block of the first, index order
  std::size_t candidates = 0;
};

bool live(const mesh::Triangulation& tri, Index v) {
  return tri.vertex_edge(v) != kNoId && tri.kind(v) != mesh::VertexKind::kSuper;
}

Blocking make_blocks(const mesh::Triangulation& tri, std::size_t block_vertices, Shared& sh) {
  Blocking bl;
  const std::size_t kBlock = std::max<std::size_t>(1, block_vertices);
  const std::size_t n = tri.num_vertices();
  std::size_t nlive = 0;
  for (Index v = 0; v < n; ++v)
    if (live(tri, v)) {
      bl.box.add(tri.point(v));
      ++nlive;
    }
  int level = 2;  // cells per side 2^level
  while (level < 10 && 2 * (std::size_t{1} << (2 * level)) < nlive) ++level;
  std::vector<std::uint32_t> count((std::size_t{1} << (2 * level)) + 1);
  std::vector<std::uint32_t> cell(n);
  const Box2& box = bl.box;
  // Cuts the blocking whose cell of a vertex at grid coordinates (x, y) in [0, 1] is key(x, y).
  auto cut = [&](std::vector<std::uint32_t>& block, const auto& key) {
    std::fill(count.begin(), count.end(), 0u);
    const double w = box.width() > 0 ? 1.0 / box.width() : 0.0, h = box.height() > 0 ? 1.0 / box.height() : 0.0;
    for (Index v = 0; v < n; ++v) {
      if (!live(tri, v)) continue;
      const double x = std::clamp((tri.point(v).x - box.lo.x) * w, 0.0, 1.0);
      const double y = std::clamp((tri.point(v).y - box.lo.y) * h, 0.0, 1.0);
      cell[v] = key(x, y);
      ++count[cell[v] + 1];
    }
    for (std::size_t c = 1; c < count.size(); ++c) count[c] += count[c - 1];
    std::uint32_t last = 0;
    block.assign(n, kNoBlock);
    for (Index v = 0; v < n; ++v)
      if (live(tri, v)) {
        block[v] = static_cast<std::uint32_t>(count[cell[v]] / kBlock);
        last = std::max(last, block[v]);
      }
    return static_cast<std::size_t>(last) + 1;
  };
  const auto side = static_cast<double>((std::uint32_t{1} << level) - 1);
  bl.nblocks = cut(sh.block, [side](double x, double y) {
    return static_cast<std::uint32_t>(morton(static_cast<std::uint32_t>(x * side), static_cast<std::uint32_t>(y * side)));
  });
  const std::uint32_t shift = 0x55555555u & ((std::uint32_t{1} << (level - 1)) - 1);
  const auto half = static_cast<double>((std::uint32_t{1} << (level - 1)) - 1);
  bl.nblocks2 = cut(sh.block2, [half, shift](double x, double y) {
    return static_cast<std::uint32_t>(morton(static_cast<std::uint32_t>(x * half) + shift,
                                             static_cast<std::uint32_t>(y * half) + shift));
  });
  bl.free.resize(bl.nblocks);
  for (Index v = 0; v < n; ++v)
    if (live(tri, v) && (tri.kind(v) == mesh::VertexKind::kFree || tri.kind(v) == mesh::VertexKind::kSegment)) {
      bl.free[sh.block[v]].push_back(v);
      ++bl.candidates;
    }
  return bl;
}

// The vertices of the star of v, both ways from vhe[v] (with repeats).
void star_vertices(const mesh::Triangulation& tri, Index v, std::vector<Index>& nbr) {
  nbr.clear();
  const HalfEdge h0 = tri.vertex_edge(v);
  for (HalfEdge h = h0, guard = 0; guard < 1024; ++guard) {
    nbr.push_back(tri.dst(h));
    nbr.push_back(tri.apex(h));
    const HalfEdge tw = tri.twin(prev_he(h));
    if (tw == kNoId || tw == h0) break;
    h = tw;
  }
  for (HalfEdge g = h0, guard = 0; guard < 1024; ++guard) {
    const HalfEdge tw = tri.twin(g);
    if (tw == kNoId) break;
    g = next_he(tw);
    if (g == h0) break;
    nbr.push_back(tri.dst(g));
    nbr.push_back(tri.apex(g));
  }
}

// Shared::hidden: for every segment vertex, the vertices within f of it that are not its mesh
// neighbours. Why: such a vertex lies across a constraint, where no test of a move sees it, and a
// slide along the segment could bring the two nearer than Theorem 4.4 allows. Found once: both
// may move a little, which only the rule in improved() needs to follow (it reads their positions).
void find_hidden_pairs(const mesh::Triangulation& tri, const sizing::SizingField& f, const Box2& box, Shared& sh,
                       StepLaps& lap) {
  const std::size_t n = tri.num_vertices();
  // f at the segment vertices; the cells as long as its median there.
  std::vector<std::pair<Index, double>> seg;
  for (Index v = 0; v < n; ++v)
    if (tri.vertex_edge(v) != kNoId && tri.kind(v) == mesh::VertexKind::kSegment) seg.push_back({v, f(tri.point(v))});
  std::vector<double> fs;  // the usable values (NaN has no order)
  fs.reserve(seg.size());
  for (const auto& sv : seg)
    if (sv.second > 0 && std::isfinite(sv.second)) fs.push_back(sv.second);
  const auto mid = fs.begin() + static_cast<std::ptrdiff_t>(fs.size() / 2);
  if (!fs.empty()) std::nth_element(fs.begin(), mid, fs.end());
  const PointCells cells(tri.points(), [&](Index v) { return live(tri, v); }, box, fs.empty() ? 0.0 : *mid);
  fs = {};
  lap("point cells");
  std::vector<Index> nbr;
  std::vector<std::pair<Index, Index>> pairs;  // both ways: either of the two may move
  for (const auto& [v, fv] : seg) {
    star_vertices(tri, v, nbr);
    cells.for_each_within(tri.point(v), fv * fv, [&](Index u) {
      if (u != v && std::find(nbr.begin(), nbr.end(), u) == nbr.end()) {
        pairs.push_back({v, u});
        pairs.push_back({u, v});
      }
    });
  }
  if (pairs.empty()) return;
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  sh.hidden_at.assign(n + 1, 0);
  for (const auto& pr : pairs) ++sh.hidden_at[pr.first + 1];
  for (std::size_t k = 0; k < n; ++k) sh.hidden_at[k + 1] += sh.hidden_at[k];
  sh.hidden.reserve(pairs.size());
  for (const auto& pr : pairs) sh.hidden.push_back(pr.second);
}

// The sweeps. Each: first every block on its own (concurrently when f may be evaluated from
// several threads), each trying its vertices whose star and flips stay inside it; then the
// vertices deferred because they did not, in the blocks of the second blocking (most of them lie
// inside one), again concurrently; then, on one thread, those deferred again, in block order.
// Same result for any thread count.
class Sweeps {
 public:
  Sweeps(Shared& sh, const Blocking& bl, SmoothStats& st)
      : sh_(sh), tri_(sh.t), bl_(bl), st_(st),
        threads_(sh.f.thread_safe() ? static_cast<unsigned>(std::max<std::size_t>(
                                          1, std::min<std::size_t>(max_threads(), bl.nblocks)))
                                    : 1u),
        deferred_(bl.nblocks), in_block2_(bl.nblocks2), deferred2_(bl.nblocks2),
        moved_in_(std::max(bl.nblocks, bl.nblocks2)), seg_moved_in_(moved_in_.size()) {
    for (unsigned k = 0; k < threads_; ++k) workers_.emplace_back(sh);
  }

  // One sweep; returns the number of moves.
  std::size_t sweep(StepLaps& lap) {
    run_blocks(bl_.nblocks, [&](Smoother& w, std::size_t b) { sweep_list(w, bl_.free[b], b, sh_.block, deferred_[b]); });
    std::size_t moved = tally(bl_.nblocks);
    lap("parallel sweep");
    for (auto& l : in_block2_) l.clear();
    for (std::size_t b = 0; b < bl_.nblocks; ++b) {
      for (Index v : deferred_[b]) in_block2_[sh_.block2[v]].push_back(v);
      st_.shifted += deferred_[b].size();  // each still dirty: tried there
    }
    run_blocks(bl_.nblocks2,
               [&](Smoother& w, std::size_t b) { sweep_list(w, in_block2_[b], b, sh_.block2, deferred2_[b]); });
    moved += tally(bl_.nblocks2);
    lap("shifted sweep");
    moved += serial_sweep();
    lap("serial sweep");
    return moved;
  }

 private:
  // A kept move makes the vertices of every triangle it touched dirty (tried again).
  void touched_dirty(const Smoother& w) {
    for (TriangleId t : w.touched())
      for (int k = 0; k < 3; ++k) sh_.dirty[tri_.org(3 * t + static_cast<TriangleId>(k))] = 1;
  }
  // Tries the vertices of `list` (block b of `blocks`): the moved ones counted, the deferred ones
  // listed in `out`.
  void sweep_list(Smoother& w, const std::vector<Index>& list, std::size_t b, const std::vector<std::uint32_t>& blocks,
                  std::vector<Index>& out) {
    out.clear();
    moved_in_[b] = seg_moved_in_[b] = 0;
    for (Index v : list) {
      if (!sh_.dirty[v]) continue;
      sh_.dirty[v] = 0;
      const Smoother::Result r = w.try_move(v, static_cast<std::uint32_t>(b), &blocks);
      if (r == Smoother::Result::kDeferred) {
        sh_.dirty[v] = 1;
        out.push_back(v);
      } else if (r == Smoother::Result::kKept) {
        ++moved_in_[b];
        if (tri_.kind(v) == mesh::VertexKind::kSegment) ++seg_moved_in_[b];
        touched_dirty(w);
      }
    }
  }
  // Runs sweep(worker, b) for the blocks [0, count), concurrently when threads allow.
  template <class Sweep>
  void run_blocks(std::size_t count, const Sweep& sweep) {
    if (threads_ <= 1) {
      for (std::size_t b = 0; b < count; ++b) sweep(workers_[0], b);
      return;
    }
    parallel_chunks(count, [&](std::size_t b, unsigned w) { sweep(workers_[w], b); }, threads_);
  }
  std::size_t tally(std::size_t count) {
    std::size_t moved = 0;
    for (std::size_t b = 0; b < count; ++b) {
      moved += moved_in_[b];
      st_.segment_moves += seg_moved_in_[b];
    }
    return moved;
  }
  // The vertices both blockings deferred, on this thread in block order.
  std::size_t serial_sweep() {
    std::size_t moved = 0;
    for (std::size_t b = 0; b < bl_.nblocks2; ++b)
      for (Index v : deferred2_[b]) {
        if (!sh_.dirty[v]) continue;
        sh_.dirty[v] = 0;
        ++st_.deferred;
        if (workers_[0].try_move(v, kAnyBlock) != Smoother::Result::kKept) continue;
        ++moved;
        if (tri_.kind(v) == mesh::VertexKind::kSegment) ++st_.segment_moves;
        touched_dirty(workers_[0]);
      }
    return moved;
  }

  Shared& sh_;
  mesh::Triangulation& tri_;
  const Blocking& bl_;
  SmoothStats& st_;
  unsigned threads_;
  std::vector<Smoother> workers_;
  // Per block: the vertices deferred by the first blocking, those of them (grouped by their block
  // of the second) tried there, and those deferred again.
  std::vector<std::vector<Index>> deferred_, in_block2_, deferred2_;
  std::vector<std::size_t> moved_in_, seg_moved_in_;
};

}  // namespace

namespace {

// The sweeps of smooth() (up to `passes`), added to st: over every vertex, or with first_new > 0
// only over the vertices from first_new on and their neighbours (what the fan insertions changed).
void sweep_passes(mesh::Triangulation& tri, const sizing::SizingField& f, const SmoothOptions& options, int passes,
                  SmoothStats& st, Index first_new = 0) {
  StepLaps lap(debug::Aid::kSmooth, "smooth");  // developer aid (base/step_laps.hpp)
  tri.rebuild_vertex_map();
  lap("vertex map");
  Shared sh{tri, f, options, 0.0, {}, {}, {}, {}, {}};
  const double sn = std::sin(std::clamp(options.min_angle_deg, 0.0, 60.0) * geom::kRadPerDeg);
  sh.floor_key = sn * sn;
  const Blocking bl = make_blocks(tri, options.block_vertices, sh);
  st.candidates = bl.candidates;
  lap("blocks");
  find_hidden_pairs(tri, f, bl.box, sh, lap);
  lap("hidden pairs");
  // A vertex whose star nothing has touched since it last failed would fail again: it is
  // retried only after a move changed a triangle around it. Why: after the first sweep most of a
  // converged mesh is clean, and each try costs up to six attempts with flips and f evaluations.
  sh.dirty.assign(tri.num_vertices(), first_new > 0 ? 0 : 1);
  if (first_new > 0) {
    std::vector<Index> nbr;
    for (Index v = first_new; v < tri.num_vertices(); ++v) {
      if (!live(tri, v)) continue;
      sh.dirty[v] = 1;
      star_vertices(tri, v, nbr);
      for (Index u : nbr) sh.dirty[u] = 1;
    }
  }
  Sweeps sweeps(sh, bl, st);
  for (int pass = 0; pass < passes; ++pass) {
    const std::size_t moved = sweeps.sweep(lap);
    st.moves += moved;
    ++st.passes;
    if (lap.on()) std::fprintf(stderr, "smooth pass %d: %zu moves\n", pass, moved);
    if (moved * 200 < st.candidates) break;  // converged: under 0.5 % still moving
  }
}

}  // namespace

SmoothStats smooth(mesh::Triangulation& tri, const sizing::SizingField& f, const SmoothOptions& options) {
  SmoothStats st;
  sweep_passes(tri, f, options, options.passes, st);
  if (options.fan_insertions && options.passes > 0) {
    FanOptions fo;
    fo.bound = options.bound;
    fo.min_angle_deg = options.min_angle_deg;
    const auto first_new = static_cast<Index>(tri.num_vertices());
    st.fan_vertices = insert_fan_vertices(tri, f, fo);
    if (st.fan_vertices > 0) sweep_passes(tri, f, options, 2, st, first_new);
  }
  return st;
}

}  // namespace fdr::refine
