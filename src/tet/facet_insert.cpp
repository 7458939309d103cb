// Boundary's facet triangulations: the walk to a point and Bowyer-Watson insertion in a facet's
// plane (boundary.hpp).
#include <algorithm>
#include "plc/facet_frame.hpp"
#include "predicates/predicates.hpp"
#include "tet/boundary.hpp"

namespace fdr::tet {
namespace {

bool same_edge(VertexId u, VertexId w, std::array<VertexId, 2> e) {
  return (u == e[0] && w == e[1]) || (u == e[1] && w == e[0]);
}

}  // namespace

int Boundary::orient_in_facet(std::uint32_t f, VertexId a, VertexId b, Point3 p) const {
  const plc::FacetFrame& fr = ft_.frames[f];
  const int o = predicates::orient2d(plc::project(dt_.point(a), fr.drop_axis), plc::project(dt_.point(b), fr.drop_axis),
                                     plc::project(p, fr.drop_axis));
  return fr.flip ? -o : o;
}

bool Boundary::in_circle(std::uint32_t t, Point3 p) const {
  const SubfacetTri& s = tris_[t];
  return plc::incircle_in_plane(dt_.point(s.v[0]), dt_.point(s.v[1]), dt_.point(s.v[2]), p,
                                ft_.frames[s.facet].off_plane) > 0;
}

FacetLocation Boundary::locate_in_facet(std::uint32_t t, Point3 p) const {
  const std::uint32_t f = tris_[t].facet;
  // A visibility walk; the bound on steps only guards against a cycle on a triangulation that is
  // not Delaunay (rounded points), where the last triangle reached is returned.
  for (std::size_t step = 0; step < tris_.size() + 8; ++step) {
    const SubfacetTri& s = tris_[t];
    bool moved = false;
    for (int j = 0; j < 3 && !moved; ++j) {
      const int k = static_cast<int>((j + step) % 3);
      const VertexId u = s.v[k], w = s.v[(k + 1) % 3];
      if (orient_in_facet(f, u, w, p) >= 0) continue;
      const std::uint32_t n = across(f, u, w);
      if (n == UINT32_MAX || is_subsegment(u, w)) return {UINT32_MAX, {u, w}};
      t = n;
      moved = true;
    }
    if (!moved) return {t, {kNoId, kNoId}};
  }
  return {t, {kNoId, kNoId}};
}

void Boundary::insert_in_facet(std::uint32_t seed, VertexId v) { insert_with_cavity({seed}, 1, v, {kNoId, kNoId}); }

bool Boundary::in_cavity(std::uint32_t t) const { return t < cav_mark_.size() && cav_mark_[t] == cav_stamp_; }

void Boundary::insert_with_cavity(std::vector<std::uint32_t> cavity, std::size_t forced, VertexId v,
                                  std::array<VertexId, 2> split_edge) {
  const std::uint32_t f = tris_[cavity[0]].facet;
  const Point3 p = dt_.point(v);
  // Membership by stamp per triangle slot: a cavity can hold thousands of triangles where a facet
  // is refined toward a small feature, and a search of the list per test made that quadratic.
  if (cav_mark_.size() < tris_.size()) cav_mark_.resize(tris_.size() * 3 / 2 + 16, 0);
  if (++cav_stamp_ == 0) {  // wrapped: stale marks would read as members
    std::fill(cav_mark_.begin(), cav_mark_.end(), 0);
    cav_stamp_ = 1;
  }
  for (std::uint32_t t : cavity) cav_mark_[t] = cav_stamp_;
  // Grow across edges that are not subsegments into triangles whose circle holds p, up to the cap:
  // beyond it the facet's triangulation stays non-Delaunay around p (counted, see capped_cavities).
  bool capped = false;
  for (std::size_t k = 0; k < cavity.size(); ++k) {
    const auto tv = tris_[cavity[k]].v;
    for (int e = 0; e < 3; ++e) {
      const VertexId u = tv[e], w = tv[(e + 1) % 3];
      if (same_edge(u, w, split_edge) || is_subsegment(u, w)) continue;
      const std::uint32_t n = across(f, u, w);
      if (n == UINT32_MAX || in_cavity(n) || !in_circle(n, p)) continue;
      if (cavity.size() >= kMaxFacetCavity) {
        capped = true;
        continue;
      }
      cav_mark_[n] = cav_stamp_;
      cavity.push_back(n);
    }
  }
  if (capped) ++capped_cavities_;
  // Keep the cavity star-shaped from p: a triangle (not forced) with a boundary edge that p does
  // not see strictly from inside leaves it (rounded points may break the empty-circle property).
  // Removing a triangle only adds boundary edges, so the triangles kept are the largest such set
  // whatever the order of removal: passes until none leaves, the survivors in their order.
  for (bool changed = true; changed;) {
    changed = false;
    for (std::size_t k = forced; k < cavity.size(); ++k) {
      const auto tv = tris_[cavity[k]].v;
      for (int e = 0; e < 3; ++e) {
        const VertexId u = tv[e], w = tv[(e + 1) % 3];
        const std::uint32_t n = across(f, u, w);
        if (n != UINT32_MAX && in_cavity(n)) continue;
        if (orient_in_facet(f, u, w, p) <= 0) {
          cav_mark_[cavity[k]] = cav_stamp_ - 1;
          changed = true;
          break;
        }
      }
    }
    if (changed)
      cavity.erase(std::remove_if(cavity.begin() + static_cast<std::ptrdiff_t>(forced), cavity.end(),
                                  [&](std::uint32_t t) { return !in_cavity(t); }),
                   cavity.end());
  }
  std::vector<std::array<VertexId, 2>> edges;
  for (std::uint32_t t : cavity) {
    const auto tv = tris_[t].v;
    for (int e = 0; e < 3; ++e) {
      const VertexId u = tv[e], w = tv[(e + 1) % 3];
      if (same_edge(u, w, split_edge)) continue;
      const std::uint32_t n = across(f, u, w);
      if (n != UINT32_MAX && in_cavity(n)) continue;
      edges.push_back({u, w});
    }
  }
  for (std::uint32_t t : cavity) kill_tri(t);
  for (const auto& e : edges) add_tri({e[0], e[1], v}, f);
}

}  // namespace fdr::tet
