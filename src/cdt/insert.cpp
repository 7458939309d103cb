// Bowyer-Watson insertion: cavity search by exact incircle, star-shape repair, fan re-triangulation.
#include "cdt/insert.hpp"
#include <algorithm>
#include "predicates/predicates.hpp"

namespace fdr::cdt {
using mesh::Triangulation;
using predicates::incircle;
using predicates::orient2d;

void Inserter::grow(TriangleId seed, Point2 p) {
  auto& T = tri_;
  stack_.push_back(seed);
  while (!stack_.empty()) {
    const TriangleId t = stack_.back();
    stack_.pop_back();
    for (int k = 0; k < 3; ++k) {
      const HalfEdge h = 3 * t + static_cast<Index>(k);
      if (h == split_he_ || h == split_twin_) continue;
      const HalfEdge n = T.twin(h);
      if (n == kNoId || T.constrained(h)) continue;
      const TriangleId u = mesh::tri_of(n);
      if (T.marked(u, Triangulation::kMarkA | Triangulation::kMarkB)) continue;
      const Point2 a = T.point(T.corner(u, 0)), b = T.point(T.corner(u, 1)), c = T.point(T.corner(u, 2));
      if (incircle(a, b, c, p) > 0) {
        T.mark(u, Triangulation::kMarkA);
        cavity_.push_back(u);
        stack_.push_back(u);
      } else {
        T.mark(u, Triangulation::kMarkB);
        rejected_.push_back(u);
      }
    }
  }
}

void Inserter::clear_marks() {
  for (TriangleId t : cavity_) tri_.unmark(t, Triangulation::kMarkA);
  for (TriangleId t : rejected_) tri_.unmark(t, Triangulation::kMarkB);
  rejected_.clear();
}

// Flips the edge of half-edge h (and its twin): triangles (a,b,c) + (b,a,d) become (c,a,d) +
// (d,b,c), i.e. the diagonal a-b is replaced by c-d. Caller guarantees a strictly convex quad.
//
//          c                    c
//        /   \                / | \   .
//       a --- b      ->      a  |  b
//        \   /                \ | /
//          d                    d
void flip_edge(mesh::Triangulation& T, HalfEdge h) {
  const HalfEdge g = T.twin(h);
  const TriangleId t1 = mesh::tri_of(h), t2 = mesh::tri_of(g);
  const Index a = T.org(h), b = T.dst(h), c = T.apex(h), d = T.apex(g);
  const HalfEdge o_bc = T.twin(mesh::next_he(h)), o_ca = T.twin(mesh::prev_he(h));
  const HalfEdge o_ad = T.twin(mesh::next_he(g)), o_db = T.twin(mesh::prev_he(g));
  const bool c_bc = T.constrained(mesh::next_he(h)), c_ca = T.constrained(mesh::prev_he(h));
  const bool c_ad = T.constrained(mesh::next_he(g)), c_db = T.constrained(mesh::prev_he(g));
  // t1 = (c, a, d): edges c->a, a->d, d->c.  t2 = (d, b, c): edges d->b, b->c, c->d.
  T.set_corners(t1, c, a, d);
  T.set_corners(t2, d, b, c);
  T.clear_constraints(t1);
  T.clear_constraints(t2);
  T.link(3 * t1, o_ca);     T.set_constrained(3 * t1, c_ca);
  T.link(3 * t1 + 1, o_ad); T.set_constrained(3 * t1 + 1, c_ad);
  T.link(3 * t2, o_db);     T.set_constrained(3 * t2, c_db);
  T.link(3 * t2 + 1, o_bc); T.set_constrained(3 * t2 + 1, c_bc);
  T.link(3 * t1 + 2, 3 * t2 + 2);
  T.set_vertex_edge(a, 3 * t1 + 1);
  T.set_vertex_edge(d, 3 * t1 + 2);
  T.set_vertex_edge(b, 3 * t2 + 1);
  T.set_vertex_edge(c, 3 * t2 + 2);
}

bool Inserter::build_cavity(Point2 p, Location loc) {
  auto& T = tri_;
  cavity_.clear();
  rejected_.clear();
  boundary_.clear();
  split_he_ = split_twin_ = kNoId;
  needs_flips_ = false;
  if (loc.kind == LocateKind::kOnVertex || loc.kind == LocateKind::kBlocked || loc.he == kNoId) return false;
  const TriangleId t0 = mesh::tri_of(loc.he);
  T.mark(t0, Triangulation::kMarkA);
  cavity_.push_back(t0);
  if (loc.kind == LocateKind::kOnEdge) {
    // A rounded split point a hair off the edge may lie outside the circumcircle of the triangle
    // across it, which is destroyed anyway: the fan is then repaired by flips (commit).
    needs_flips_ = orient2d(T.point(T.org(loc.he)), T.point(T.dst(loc.he)), p) != 0;
    split_he_ = loc.he;
    split_twin_ = T.twin(loc.he);
    if (split_twin_ != kNoId) {
      const TriangleId t1 = mesh::tri_of(split_twin_);
      T.mark(t1, Triangulation::kMarkA);
      cavity_.push_back(t1);
      grow(t1, p);
    }
  }
  grow(t0, p);
  // Why a repair loop: with exact predicates the Delaunay cavity is star-shaped, but a vertex
  // placed "on" an edge by rounding (a segment split point) can sit a hair off it; absorbing the
  // triangle behind any edge that does not see p keeps every new triangle positively oriented.
  for (int round = 0;; ++round) {
    boundary_.clear();
    HalfEdge bad = kNoId;
    for (TriangleId t : cavity_) {
      for (int k = 0; k < 3; ++k) {
        const HalfEdge h = 3 * t + static_cast<Index>(k);
        if (h == split_he_ || h == split_twin_) continue;
        const HalfEdge n = T.twin(h);
        if (n != kNoId && T.marked(mesh::tri_of(n), Triangulation::kMarkA) && !T.constrained(h)) continue;
        boundary_.push_back(h);
        if (bad == kNoId && orient2d(T.point(T.corner(t, k)), T.point(T.corner(t, (k + 1) % 3)), p) <= 0) bad = h;
      }
    }
    if (bad == kNoId) return true;
    const HalfEdge n = T.twin(bad);
    if (n == kNoId || T.constrained(bad) || round > 64) {
      abort();
      return false;
    }
    const TriangleId u = mesh::tri_of(n);
    needs_flips_ = true;
    T.unmark(u, Triangulation::kMarkB);
    T.mark(u, Triangulation::kMarkA);
    cavity_.push_back(u);
    grow(u, p);
  }
}

void Inserter::abort() {
  clear_marks();
  cavity_.clear();
  boundary_.clear();
}

Index Inserter::commit(Point2 p, mesh::VertexKind kind) {
  const Index v = tri_.add_vertex(p, kind);
  commit_vertex(v);
  return v;
}

void Inserter::commit_vertex(Index v) {
  auto& T = tri_;
  clear_marks();
  rim_.clear();
  for (HalfEdge h : boundary_) rim_.push_back({T.org(h), T.dst(h), T.twin(h), T.constrained(h)});
  Index split_a = kNoId, split_b = kNoId;
  bool split_cons = false;
  if (split_he_ != kNoId) {
    split_a = T.org(split_he_);
    split_b = T.dst(split_he_);
    split_cons = T.constrained(split_he_);
  }
  // A new triangle inherits the region of the cavity triangle that owned its rim edge (a split
  // constrained edge can separate two regions inside one cavity).
  rim_region_.clear();
  if (T.has_regions())
    for (HalfEdge h : boundary_) rim_region_.push_back(T.region(mesh::tri_of(h)));
  for (TriangleId t : cavity_) T.kill_triangle(t);
  new_tris_.clear();
  for (const Rim& r : rim_) {
    const TriangleId t = T.new_triangle(r.x, r.y, v);
    T.link(3 * t, r.outer);
    if (r.cons) T.set_constrained(3 * t, true);
    new_tris_.push_back(t);
  }
  if (T.has_regions())
    for (std::size_t k = 0; k < new_tris_.size(); ++k) T.set_region(new_tris_[k], rim_region_[k]);
  // Each rim vertex starts one rim edge: its vertex edge, set to that triangle's first half-edge,
  // finds the neighbour of every new triangle's edge y -> v in constant time (a rim vertex
  // starting none, an end of a split boundary edge, keeps an edge of another triangle).
  for (TriangleId t : new_tris_) T.set_vertex_edge(T.corner(t, 0), 3 * t);
  for (TriangleId t : new_tris_) {
    const HalfEdge h = T.vertex_edge(T.corner(t, 1));
    if (h % 3 == 0 && T.corner(mesh::tri_of(h), 2) == v && !T.dead(mesh::tri_of(h)))
      T.link(3 * t + 1, h + 2);
  }
  if (split_cons) {
    // Both halves of a split subsegment stay constrained and belong to the same input segment.
    T.split_segment(split_a, split_b, v);
    for (TriangleId t : new_tris_) {
      const Index x = T.corner(t, 0), y = T.corner(t, 1);
      if (y == split_a || y == split_b) T.set_constrained(3 * t + 1, true);
      if (x == split_a || x == split_b) T.set_constrained(3 * t + 2, true);
    }
  }
  cavity_.clear();
  if (needs_flips_) restore_delaunay();
}

// Why: the cavity of a point placed "on" an edge by rounding, or grown by the repair loop, can
// hold a triangle whose circumcircle does not contain p; the fan is then not constrained
// Delaunay. Lawson flips over every unconstrained edge of the new triangles and of the triangles
// they flip restore it (the flip algorithm terminates on any triangulation). Flipped triangles
// join new_tris_ for re-evaluation.
void Inserter::restore_delaunay() {
  auto& T = tri_;
  std::vector<std::pair<Index, Index>> stack;
  for (TriangleId t : new_tris_)
    for (int k = 0; k < 3; ++k) stack.push_back({T.corner(t, k), T.org(3 * t + (k + 1) % 3)});
  const std::size_t cap = 16 * (T.num_slots() + 64);
  for (std::size_t guard = 0; !stack.empty() && guard < cap; ++guard) {
    const auto [u, w] = stack.back();
    stack.pop_back();
    const HalfEdge e = T.find_edge(u, w);
    if (e == kNoId || T.constrained(e) || T.twin(e) == kNoId) continue;
    const Index a = T.org(e), b = T.dst(e), c = T.apex(e), d = T.apex(T.twin(e));
    if (incircle(T.point(a), T.point(b), T.point(c), T.point(d)) <= 0) continue;
    // Convex iff c-d separates a and b strictly (always so when d is inside the circle).
    if (orient2d(T.point(c), T.point(d), T.point(a)) * orient2d(T.point(c), T.point(d), T.point(b)) >= 0) continue;
    const TriangleId t1 = mesh::tri_of(e), t2 = mesh::tri_of(T.twin(e));
    flip_edge(T, e);
    new_tris_.push_back(t1);
    new_tris_.push_back(t2);
    stack.push_back({a, c});
    stack.push_back({c, b});
    stack.push_back({b, d});
    stack.push_back({d, a});
  }
  std::sort(new_tris_.begin(), new_tris_.end());
  new_tris_.erase(std::unique(new_tris_.begin(), new_tris_.end()), new_tris_.end());
}

}  // namespace fdr::cdt
