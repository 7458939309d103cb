// Point location by walking: visibility walk (initial insertion) and straight walk (refinement).
#include "cdt/locate.hpp"
#include "predicates/predicates.hpp"

namespace fdr::cdt {
using predicates::orient2d;
using mesh::next_he;
using mesh::prev_he;

namespace {
// Classifies p against triangle t whose three orientations are all >= 0.
Location classify_inside(const mesh::Triangulation& tri, TriangleId t, Point2 p, const int o[3]) {
  int zeros = (o[0] == 0) + (o[1] == 0) + (o[2] == 0);
  if (zeros == 0) return {LocateKind::kInTriangle, 3 * t};
  for (int k = 0; k < 3; ++k)
    if (tri.point(tri.corner(t, k)) == p) return {LocateKind::kOnVertex, 3 * t + static_cast<Index>(k)};
  for (int k = 0; k < 3; ++k)
    if (o[k] == 0) return {LocateKind::kOnEdge, 3 * t + static_cast<Index>(k)};
  return {LocateKind::kInTriangle, 3 * t};
}
}  // namespace

Location locate_visibility(const mesh::Triangulation& tri, TriangleId t, Point2 p, std::size_t* count) {
  std::uint32_t rng = 2463534242u;
  for (std::size_t steps = 0;; ++steps) {
    if (count) ++*count;
    rng ^= rng << 13; rng ^= rng >> 17; rng ^= rng << 5;
    const int r = static_cast<int>(rng % 3);
    int o[3];
    bool moved = false;
    // Why random start edge: a fixed order can cycle forever in degenerate configurations.
    for (int i = 0; i < 3; ++i) {
      const int k = (r + i) % 3;
      const HalfEdge h = 3 * t + static_cast<Index>(k);
      o[k] = orient2d(tri.point(tri.corner(t, k)), tri.point(tri.corner(t, (k + 1) % 3)), p);
      if (o[k] < 0 && tri.twin(h) != kNoId) {
        t = mesh::tri_of(tri.twin(h));
        moved = true;
        break;
      }
    }
    if (!moved) {
      for (int k = 0; k < 3; ++k)
        if (o[k] < 0) return {LocateKind::kBlocked, 3 * t + static_cast<Index>(k)};
      return classify_inside(tri, t, p, o);
    }
    if (steps > tri.num_slots() + 16) return {LocateKind::kBlocked, kNoId};
  }
}

Location locate_straight(const mesh::Triangulation& tri, TriangleId t, Point2 p, std::size_t max_steps) {
  const Point2 a = tri.point(tri.corner(t, 0)), b = tri.point(tri.corner(t, 1)), c = tri.point(tri.corner(t, 2));
  const Point2 g{(a.x + b.x + c.x) / 3.0, (a.y + b.y + c.y) / 3.0};
  HalfEdge entry = kNoId;
  for (std::size_t steps = 0; steps < max_steps; ++steps) {
    int o[3];
    bool inside = true;
    for (int k = 0; k < 3; ++k) {
      const HalfEdge h = 3 * t + static_cast<Index>(k);
      o[k] = (h == entry) ? 1 : orient2d(tri.point(tri.corner(t, k)), tri.point(tri.corner(t, (k + 1) % 3)), p);
      if (o[k] < 0) inside = false;
    }
    if (inside) {
      if (entry != kNoId) {  // the entry edge was skipped: p may lie on it
        const int k = static_cast<int>(entry % 3);
        o[k] = orient2d(tri.point(tri.corner(t, k)), tri.point(tri.corner(t, (k + 1) % 3)), p);
      }
      return classify_inside(tri, t, p, o);
    }
    // Exit edge: the one whose origin is right of (or on) line g->p and destination strictly left,
    // among edges that p lies beyond. Falls back to any edge p lies beyond (visibility step).
    HalfEdge exit = kNoId;
    int side[3];
    for (int k = 0; k < 3; ++k) side[k] = orient2d(g, p, tri.point(tri.corner(t, k)));
    for (int k = 0; k < 3; ++k) {
      const int k1 = (k + 1) % 3;
      if (o[k] < 0 && side[k] <= 0 && side[k1] > 0) { exit = 3 * t + static_cast<Index>(k); break; }
    }
    if (exit == kNoId)
      for (int k = 0; k < 3; ++k)
        if (o[k] < 0) { exit = 3 * t + static_cast<Index>(k); break; }
    if (tri.constrained(exit) || tri.twin(exit) == kNoId) return {LocateKind::kBlocked, exit};
    entry = tri.twin(exit);
    t = mesh::tri_of(entry);
  }
  return {LocateKind::kBlocked, kNoId};
}

}  // namespace fdr::cdt
