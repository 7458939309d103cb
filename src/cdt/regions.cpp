// Region removal after the segments are in: components across unconstrained edges, their nesting
// depth, which of them go (parity, seeds, hull), regional attributes, and the removal itself.
#include <cmath>
#include <deque>
#include <sstream>
#include "base/error.hpp"
#include "cdt/locate.hpp"
#include "cdt/steps.hpp"

namespace fdr::cdt {
using mesh::Triangulation;
using mesh::VertexKind;

namespace {


bool has_super_corner(const Triangulation& T, TriangleId t) {
  for (int k = 0; k < 3; ++k)
    if (T.kind(T.corner(t, k)) == VertexKind::kSuper) return true;
  return false;
}

TriangleId first_live(const Triangulation& T) {
  TriangleId t = 0;
  while (T.dead(t)) ++t;
  return t;
}

CdtOptions::Regions resolved_mode(const pslg::Pslg& in, CdtOptions::Regions mode) {
  if (mode != CdtOptions::Regions::kAuto) return mode;
  if (in.segments.empty()) return CdtOptions::Regions::kNone;
  if (!in.holes.empty()) return CdtOptions::Regions::kSeeds;
  return CdtOptions::Regions::kParity;
}

// The component hole seed h removes; throws when the seed is not strictly inside the domain.
Index hole_component(const Triangulation& T, const pslg::Pslg& in, const CdtOptions& opt, CdtOptions::Regions mode,
                     const Components& c, const std::vector<int>& depth, std::size_t h) {
  const Point2 hp = in.holes[h];
  auto hole_error = [&](const std::string& what) {
    throw Error(ExitCode::kInvalidGeometry,
                opt.source + ": hole " + std::to_string(h) + " seed at " + point_text(T.origin + hp) + " " + what);
  };
  if (!std::isfinite(hp.x) || !std::isfinite(hp.y)) hole_error("has a non-finite coordinate");
  const Location loc = locate_visibility(T, first_live(T), hp);
  if (loc.he == kNoId || loc.kind == LocateKind::kBlocked)
    hole_error("lies outside the domain (outside the convex hull of the vertices)");
  if (loc.kind == LocateKind::kOnVertex) hole_error("lies on vertex " + std::to_string(T.org(loc.he)));
  if (loc.kind == LocateKind::kOnEdge && T.constrained(loc.he)) {
    const Index s = T.segment_of(T.org(loc.he), T.dst(loc.he));
    hole_error("lies on segment " + (s != kNoId ? std::to_string(s) : std::string("(a constrained edge)")) +
               " (a seed must be strictly inside the region to remove)");
  }
  const TriangleId t = mesh::tri_of(loc.he);
  const Index k = c.of_slot[t];
  if (has_super_corner(T, t) || (mode == CdtOptions::Regions::kSeeds && depth[k] <= 0))
    hole_error(mode == CdtOptions::Regions::kHull ? "lies outside the domain (outside the convex hull of the vertices)"
                                                  : "lies outside the domain (in no region enclosed by segments)");
  return k;
}

}  // namespace

Components find_components(const Triangulation& T) {
  const std::size_t nt = T.num_slots();
  Components c;
  c.of_slot.assign(nt, kNoId);
  std::vector<TriangleId> stack;
  for (TriangleId t0 = 0; t0 < nt; ++t0) {
    if (T.dead(t0) || c.of_slot[t0] != kNoId) continue;
    const Index id = c.size();
    c.adjacent.emplace_back();
    c.touches_super.push_back(false);
    c.of_slot[t0] = id;
    stack.push_back(t0);
    while (!stack.empty()) {
      const TriangleId t = stack.back();
      stack.pop_back();
      if (has_super_corner(T, t)) c.touches_super[id] = true;
      for (int k = 0; k < 3; ++k) {
        const HalfEdge h = 3 * t + static_cast<Index>(k);
        const HalfEdge w = T.twin(h);
        if (w == kNoId || T.constrained(h)) continue;
        const TriangleId u = mesh::tri_of(w);
        if (c.of_slot[u] == kNoId) { c.of_slot[u] = id; stack.push_back(u); }
      }
    }
  }
  for (TriangleId t = 0; t < nt; ++t) {
    if (T.dead(t)) continue;
    for (int k = 0; k < 3; ++k) {
      const HalfEdge h = 3 * t + static_cast<Index>(k);
      const HalfEdge w = T.twin(h);
      if (w == kNoId || !T.constrained(h) || c.of_slot[mesh::tri_of(w)] == c.of_slot[t]) continue;
      // Breaklines are interior constraints: crossing one does not change the depth.
      const Index s = T.segment_of(T.org(h), T.dst(h));
      const bool breakline = s < T.input_segments().size() && T.input_segments()[s].marker == pslg::kBreaklineMarker;
      c.adjacent[c.of_slot[t]].push_back({c.of_slot[mesh::tri_of(w)], breakline ? 0 : 1});
    }
  }
  return c;
}

std::vector<int> nesting_depth(const Components& c) {
  // 0-1 breadth-first search from the components that touch the super-triangle.
  std::vector<int> depth(c.size(), -1);
  std::deque<Index> q;
  for (Index k = 0; k < c.size(); ++k)
    if (c.touches_super[k]) { depth[k] = 0; q.push_back(k); }
  while (!q.empty()) {
    const Index k = q.front();
    q.pop_front();
    for (const auto& [j, step] : c.adjacent[k]) {
      if (depth[j] >= 0 && depth[j] <= depth[k] + step) continue;
      depth[j] = depth[k] + step;
      if (step == 0) q.push_front(j); else q.push_back(j);
    }
  }
  return depth;
}

std::vector<bool> components_to_remove(const Triangulation& T, const pslg::Pslg& in, const CdtOptions& opt,
                                       const Components& c, const std::vector<int>& depth) {
  const auto mode = resolved_mode(in, opt.regions);
  std::vector<bool> remove(c.size(), false);
  for (Index k = 0; k < c.size(); ++k) {
    if (mode == CdtOptions::Regions::kParity) remove[k] = depth[k] < 0 || depth[k] % 2 == 0;
    else if (mode == CdtOptions::Regions::kHull) remove[k] = false;  // super triangles go anyway
    else remove[k] = depth[k] == 0 || depth[k] < 0;
  }
  if (mode == CdtOptions::Regions::kSeeds || mode == CdtOptions::Regions::kHull)
    for (std::size_t h = 0; h < in.holes.size(); ++h) remove[hole_component(T, in, opt, mode, c, depth, h)] = true;
  return remove;
}

void assign_regions(Triangulation& T, const pslg::Pslg& in, const Components& c) {
  // Triangle semantics: a seed marks the whole region bounded by segments around it; a later
  // seed in the same region wins; seeds outside every triangle are ignored.
  std::vector<std::int32_t> region_of_comp(c.size(), -1);
  const TriangleId start = first_live(T);
  for (std::size_t r = 0; r < in.regions.size(); ++r) {
    const Point2 rp = in.regions[r].seed;
    if (!std::isfinite(rp.x) || !std::isfinite(rp.y)) continue;
    const Location loc = locate_visibility(T, start, rp);
    if (loc.he == kNoId || loc.kind == LocateKind::kBlocked) continue;
    region_of_comp[c.of_slot[mesh::tri_of(loc.he)]] = static_cast<std::int32_t>(r);
  }
  T.init_regions();
  for (TriangleId t = 0; t < T.num_slots(); ++t)
    if (!T.dead(t)) T.set_region(t, region_of_comp[c.of_slot[t]]);
}

void remove_components(Triangulation& T, const Components& c, const std::vector<bool>& remove, CdtStats* stats) {
  const std::size_t nt = T.num_slots();
  auto removed = [&](TriangleId t) { return remove[c.of_slot[t]] || has_super_corner(T, t); };
  // An input segment with an edge between two removed triangles lies (partly) outside the
  // domain, e.g. a boundary segment between two even-depth regions (parity) or between a hole and
  // the exterior: it is dropped, so checkers and refinement ignore it.
  for (TriangleId t = 0; t < nt; ++t) {
    if (T.dead(t) || !removed(t)) continue;
    for (int k = 0; k < 3; ++k) {
      const HalfEdge h = 3 * t + static_cast<Index>(k);
      if (!T.constrained(h) || T.twin(h) == kNoId || !removed(mesh::tri_of(T.twin(h)))) continue;
      const Index s = T.segment_of(T.org(h), T.dst(h));
      if (s < T.input_segments().size()) T.drop_input_segment(s);
    }
  }
  for (TriangleId t = 0; t < nt; ++t) {
    if (T.dead(t) || !removed(t)) continue;
    for (int k = 0; k < 3; ++k) {
      const HalfEdge w = T.twin(3 * t + static_cast<Index>(k));
      if (w != kNoId) T.set_twin(w, kNoId);
    }
    T.kill_triangle(t);
    if (stats) ++stats->removed_triangles;
  }
  // A removed region leaves an unconstrained boundary edge only for kNone (convex hull): such
  // edges become constrained so that refinement treats the hull as a boundary.
  for (TriangleId t = 0; t < nt; ++t) {
    if (T.dead(t)) continue;
    for (int k = 0; k < 3; ++k) {
      const HalfEdge h = 3 * t + static_cast<Index>(k);
      if (T.twin(h) == kNoId && !T.constrained(h)) {
        T.set_constrained(h, true);
        T.set_segment(T.org(h), T.dst(h), kNoId);
      }
    }
  }
}

void remove_regions(Triangulation& T, const pslg::Pslg& in, const CdtOptions& opt, CdtStats* stats) {
  const Components c = find_components(T);
  const std::vector<int> depth = nesting_depth(c);
  const std::vector<bool> remove = components_to_remove(T, in, opt, c, depth);
  if (!in.regions.empty()) assign_regions(T, in, c);
  remove_components(T, c, remove, stats);
}

}  // namespace fdr::cdt
