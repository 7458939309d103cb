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
      const HalfEdge n = T.twin[h];
      if (n == kNoId || T.constrained(h)) continue;
      const TriangleId u = mesh::tri_of(n);
      if (T.flags[u] & (Triangulation::kMarkA | Triangulation::kMarkB)) continue;
      const Point2 a = T.pts[T.tv[3 * u]], b = T.pts[T.tv[3 * u + 1]], c = T.pts[T.tv[3 * u + 2]];
      if (incircle(a, b, c, p) > 0) {
        T.flags[u] |= Triangulation::kMarkA;
        cavity_.push_back(u);
        stack_.push_back(u);
      } else {
        T.flags[u] |= Triangulation::kMarkB;
        rejected_.push_back(u);
      }
    }
  }
}

void Inserter::clear_marks() {
  for (TriangleId t : cavity_) tri_.flags[t] &= static_cast<std::uint8_t>(~Triangulation::kMarkA);
  for (TriangleId t : rejected_) tri_.flags[t] &= static_cast<std::uint8_t>(~Triangulation::kMarkB);
  rejected_.clear();
}

bool Inserter::build_cavity(Point2 p, Location loc) {
  auto& T = tri_;
  cavity_.clear();
  rejected_.clear();
  boundary_.clear();
  split_he_ = split_twin_ = kNoId;
  if (loc.kind == LocateKind::kOnVertex || loc.kind == LocateKind::kBlocked || loc.he == kNoId) return false;
  const TriangleId t0 = mesh::tri_of(loc.he);
  T.flags[t0] |= Triangulation::kMarkA;
  cavity_.push_back(t0);
  if (loc.kind == LocateKind::kOnEdge) {
    split_he_ = loc.he;
    split_twin_ = T.twin[loc.he];
    if (split_twin_ != kNoId) {
      const TriangleId t1 = mesh::tri_of(split_twin_);
      T.flags[t1] |= Triangulation::kMarkA;
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
        const HalfEdge n = T.twin[h];
        if (n != kNoId && (T.flags[mesh::tri_of(n)] & Triangulation::kMarkA) && !T.constrained(h)) continue;
        boundary_.push_back(h);
        if (bad == kNoId && orient2d(T.pts[T.org(h)], T.pts[T.dst(h)], p) <= 0) bad = h;
      }
    }
    if (bad == kNoId) return true;
    const HalfEdge n = T.twin[bad];
    if (n == kNoId || T.constrained(bad) || round > 64) {
      abort();
      return false;
    }
    const TriangleId u = mesh::tri_of(n);
    T.flags[u] &= static_cast<std::uint8_t>(~Triangulation::kMarkB);
    T.flags[u] |= Triangulation::kMarkA;
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
  auto& T = tri_;
  clear_marks();
  const Index v = T.add_vertex(p, kind);
  rim_.clear();
  for (HalfEdge h : boundary_) rim_.push_back({T.org(h), T.dst(h), T.twin[h], T.constrained(h)});
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
  if (!T.region.empty())
    for (HalfEdge h : boundary_) rim_region_.push_back(T.region[mesh::tri_of(h)]);
  for (TriangleId t : cavity_) T.kill_triangle(t);
  new_tris_.clear();
  by_start_.clear();
  for (const Rim& r : rim_) {
    const TriangleId t = T.new_triangle(r.x, r.y, v);
    T.link(3 * t, r.outer);
    if (r.cons) T.set_constrained(3 * t, true);
    new_tris_.push_back(t);
    by_start_.push_back({r.x, t});
  }
  if (!T.region.empty()) {
    if (T.region.size() < T.num_slots()) T.region.resize(T.num_slots(), -1);
    for (std::size_t k = 0; k < new_tris_.size(); ++k) T.region[new_tris_[k]] = rim_region_[k];
  }
  std::sort(by_start_.begin(), by_start_.end());
  for (TriangleId t : new_tris_) {
    const Index y = T.tv[3 * t + 1];
    auto it = std::lower_bound(by_start_.begin(), by_start_.end(), std::make_pair(y, TriangleId{0}));
    if (it != by_start_.end() && it->first == y) T.link(3 * t + 1, 3 * it->second + 2);
  }
  if (split_cons) {
    // Both halves of a split subsegment stay constrained and belong to the same input segment.
    const auto key = mesh::edge_key(split_a, split_b);
    auto it = T.seg_of.find(key);
    const Index sid = it != T.seg_of.end() ? it->second : kNoId;
    if (it != T.seg_of.end()) T.seg_of.erase(it);
    T.seg_of[mesh::edge_key(split_a, v)] = sid;
    T.seg_of[mesh::edge_key(v, split_b)] = sid;
    for (TriangleId t : new_tris_) {
      const Index x = T.tv[3 * t], y = T.tv[3 * t + 1];
      if (y == split_a || y == split_b) T.set_constrained(3 * t + 1, true);
      if (x == split_a || x == split_b) T.set_constrained(3 * t + 2, true);
    }
  }
  cavity_.clear();
  return v;
}

}  // namespace fdr::cdt
