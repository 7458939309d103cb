// The terrain PLC from a stack of surfaces on one TIN (terrain_plc.hpp).
#include "terrain/terrain_plc.hpp"
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <utility>
#include "base/error.hpp"

namespace fdr::terrain {
namespace {

using Edge = std::pair<VertexId, VertexId>;

Edge key(VertexId a, VertexId b) { return a < b ? Edge{a, b} : Edge{b, a}; }

double tri_area(const Tin& tin, const std::array<VertexId, 3>& t) {
  const Point2 a = tin.xy[t[0]], b = tin.xy[t[1]], c = tin.xy[t[2]];
  return 0.5 * std::abs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
}

// The candidate vertex ids of every stack surface: a new one unless the surface meets the one above
// at v (end_pinch_outs may leave some unused; compact_vertices drops them).
std::vector<std::vector<VertexId>> lift_vertices(const Tin& tin, const std::vector<Surface>& stack, plc::Plc& out) {
  std::vector<std::vector<VertexId>> ids(stack.size(), std::vector<VertexId>(tin.xy.size()));
  for (std::size_t s = 0; s < stack.size(); ++s)
    for (std::size_t v = 0; v < tin.xy.size(); ++v) {
      if (s > 0 && stack[s].z[v] == stack[s - 1].z[v]) {
        ids[s][v] = ids[s - 1][v];
        continue;
      }
      ids[s][v] = static_cast<VertexId>(out.points.size());
      out.points.push_back({tin.xy[v].x, tin.xy[v].y, stack[s].z[v]});
    }
  return ids;
}

// Keeps the points some facet uses (in their order) and renumbers the facets and ids.
void compact_vertices(std::vector<std::vector<VertexId>>& ids, plc::Plc& out) {
  std::vector<VertexId> to(out.points.size(), kNoVertex);
  for (const plc::Facet& f : out.facets)
    for (const auto& poly : f.polygons)
      for (VertexId v : poly) to[v] = 0;
  std::vector<Point3> kept;
  for (std::size_t v = 0; v < to.size(); ++v)
    if (to[v] != kNoVertex) {
      to[v] = static_cast<VertexId>(kept.size());
      kept.push_back(out.points[v]);
    }
  if (kept.size() == out.points.size()) return;
  out.points = std::move(kept);
  for (plc::Facet& f : out.facets)
    for (auto& poly : f.polygons)
      for (VertexId& v : poly) v = to[v];
  for (auto& row : ids)
    for (VertexId& v : row) v = to[v];
}

std::int32_t surface_marker(std::size_t s, std::size_t n) {
  if (s == 0) return kTopMarker;
  if (s + 1 == n) return kBaseMarker;
  return kHorizonMarker0 + static_cast<std::int32_t>(s - 1);
}

// One facet per TIN triangle and surface, except where a surface meets the one above at all three
// corners: that facet is shared, and it is a base facet when the base is among the surfaces
// meeting there (the boundary groups stay whole).
void add_surface_facets(const Tin& tin, const Layering& layering, const std::vector<std::vector<VertexId>>& ids,
                        plc::Plc& out) {
  const std::size_t n = ids.size();
  for (std::size_t ti = 0; ti < tin.triangles.size(); ++ti) {
    const auto& t = tin.triangles[ti];
    std::size_t last = 0;
    std::vector<VertexId> above;
    for (std::size_t s = 0; s < n; ++s) {
      const auto& row = ids[layering.at(ti, s)];
      std::vector<VertexId> poly{row[t[0]], row[t[1]], row[t[2]]};
      if (s > 0 && poly == above) {
        if (s + 1 == n) out.facets[last].marker = kBaseMarker;
        continue;
      }
      plc::Facet f;
      f.polygons.push_back(poly);
      f.marker = surface_marker(s, n);
      last = out.facets.size();
      out.facets.push_back(std::move(f));
      above = std::move(poly);
    }
  }
}

constexpr std::size_t kOutside = std::numeric_limits<std::size_t>::max();

// A TIN edge (a, b as in its first triangle t1) and the triangle on its other side (kOutside on the
// TIN's boundary), in the order of first use.
struct EdgeSides {
  VertexId a, b;
  std::size_t t1, t2;
};

std::vector<EdgeSides> edge_sides(const Tin& tin) {
  std::map<Edge, std::size_t> index;
  std::vector<EdgeSides> out;
  for (std::size_t t = 0; t < tin.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const VertexId a = tin.triangles[t][k], b = tin.triangles[t][(k + 1) % 3];
      const auto [it, fresh] = index.emplace(key(a, b), out.size());
      if (fresh) out.push_back({a, b, t, kOutside});
      else out[it->second].t2 = t;
    }
  return out;
}

// The layer holding the stack's strip r (between stack surfaces r and r + 1) over triangle t, or
// -1 outside the TIN.
long layer_of_strip(const Layering& layering, std::size_t n, std::size_t t, std::size_t r) {
  if (t == kOutside) return -1;
  std::size_t s = 0;
  while (s + 2 < n && layering.at(t, s + 1) <= r) ++s;
  return static_cast<long>(s);
}

// The vertical walls over edge e: each maximal run of the stack's strips (positive at an end of
// the edge) with the same layers on its two sides, where they differ, is one polygon up the
// column at b, down the one at a, with every vertex on the columns between.
void add_walls(const EdgeSides& e, const Layering& layering, const std::vector<std::vector<VertexId>>& ids,
               plc::Plc& out) {
  const std::size_t n = ids.size();
  const VertexId a = e.a, b = e.b;
  auto flat = [&](std::size_t r) { return ids[r][a] == ids[r + 1][a] && ids[r][b] == ids[r + 1][b]; };
  for (std::size_t r = 0; r + 1 < n;) {
    const long m1 = layer_of_strip(layering, n, e.t1, r), m2 = layer_of_strip(layering, n, e.t2, r);
    if (flat(r) || m1 == m2) {
      ++r;
      continue;
    }
    std::size_t hi = r + 1;
    while (hi + 1 < n && (flat(hi) || (layer_of_strip(layering, n, e.t1, hi) == m1 &&
                                       layer_of_strip(layering, n, e.t2, hi) == m2)))
      ++hi;
    std::vector<VertexId> poly{ids[r][a], ids[r][b]};
    for (std::size_t k = r + 1; k <= hi; ++k)
      if (ids[k][b] != poly.back()) poly.push_back(ids[k][b]);
    for (std::size_t k = hi; k > r; --k)
      if (ids[k][a] != poly.back() && ids[k][a] != poly.front()) poly.push_back(ids[k][a]);
    if (poly.size() >= 3) {
      plc::Facet f;
      f.polygons.push_back(std::move(poly));
      f.marker = e.t2 == kOutside ? kSideMarker : kHorizonMarker0 + static_cast<std::int32_t>(std::min(m1, m2));
      out.facets.push_back(std::move(f));
    }
    r = hi;
  }
}

// The side walls along the TIN's boundary, then the walls where layers end inside it (edges whose
// two triangles have different layerings).
void add_all_walls(const Tin& tin, const Layering& layering, const std::vector<std::vector<VertexId>>& ids,
                   plc::Plc& out) {
  const std::vector<EdgeSides> edges = edge_sides(tin);
  for (const EdgeSides& e : edges)
    if (e.t2 == kOutside) add_walls(e, layering, ids, out);
  if (layering.identity()) return;
  for (const EdgeSides& e : edges) {
    if (e.t2 == kOutside) continue;
    bool same = true;
    for (std::size_t s = 0; s < ids.size() && same; ++s) same = layering.at(e.t1, s) == layering.at(e.t2, s);
    if (!same) add_walls(e, layering, ids, out);
  }
}

// Union-find root with path halving.
std::size_t root(std::vector<std::size_t>& parent, std::size_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

// One region point per connected part of layer s: triangles where it has positive thickness at
// some corner, joined across edges where the stack's strips the layer spans on both sides are
// positive at some end (there is no wall between them). The point is above the centroid of the
// part's thickest triangle, half-way between the layer's two surfaces there.
void add_layer_regions(const Tin& tin, const std::vector<Surface>& stack, const Layering& layering, std::size_t s,
                       plc::Plc& out) {
  auto open = [&](VertexId a, VertexId b, std::size_t lo, std::size_t hi) {
    return lo < hi && (stack[lo].z[a] > stack[hi].z[a] || stack[lo].z[b] > stack[hi].z[b]);
  };
  const std::size_t nt = tin.triangles.size();
  std::vector<std::size_t> parent(nt);
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  std::map<Edge, std::size_t> first;
  for (std::size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      const VertexId a = tin.triangles[t][k], b = tin.triangles[t][(k + 1) % 3];
      const std::size_t lo = layering.at(t, s), hi = layering.at(t, s + 1);
      if (!open(a, b, lo, hi)) continue;
      const auto [it, fresh] = first.emplace(key(a, b), t);
      if (fresh) continue;
      const std::size_t u = it->second;
      if (open(a, b, std::max(lo, layering.at(u, s)), std::min(hi, layering.at(u, s + 1))))
        parent[root(parent, t)] = root(parent, u);
    }
  std::map<std::size_t, std::pair<double, std::size_t>> best;  // part root -> (thickness, triangle)
  for (std::size_t t = 0; t < nt; ++t) {
    double th = 0;
    for (int k = 0; k < 3; ++k)
      th += corner_z(stack, layering, tin, t, s, k) - corner_z(stack, layering, tin, t, s + 1, k);
    th /= 3.0;
    if (!(th > 0)) continue;
    auto [it, fresh] = best.emplace(root(parent, t), std::make_pair(th, t));
    if (!fresh && th > it->second.first) it->second = {th, t};
  }
  for (const auto& [r, tt] : best) {
    const std::size_t t = tt.second;
    Point3 p{0, 0, 0};
    for (int k = 0; k < 3; ++k) {
      const Point2 q = tin.xy[tin.triangles[t][k]];
      const double up = corner_z(stack, layering, tin, t, s, k), lo = corner_z(stack, layering, tin, t, s + 1, k);
      p = p + Point3{q.x / 3.0, q.y / 3.0, (up + lo) / 6.0};
    }
    out.regions.push_back({p, static_cast<double>(s + 1), -1});
  }
}

}  // namespace

std::vector<std::array<VertexId, 2>> boundary_edges(const Tin& tin) {
  std::map<Edge, int> uses;
  for (const auto& t : tin.triangles)
    for (int k = 0; k < 3; ++k) ++uses[key(t[k], t[(k + 1) % 3])];
  std::vector<std::array<VertexId, 2>> out;
  for (const auto& t : tin.triangles)
    for (int k = 0; k < 3; ++k) {
      const VertexId a = t[k], b = t[(k + 1) % 3];
      if (uses[key(a, b)] == 1) out.push_back({a, b});
    }
  return out;
}

TerrainPlc build_terrain_plc(const Tin& tin, const std::vector<Surface>& stack, const Layering& layering) {
  if (stack.size() < 2) throw Error(ExitCode::kInvalidGeometry, "a terrain volume needs a top and a base");
  if (!layering.identity() && (layering.surfaces != stack.size() || layering.on.size() != tin.triangles.size() * stack.size()))
    throw Error(ExitCode::kInternal, "terrain PLC: the layering does not fit the stack and TIN");
  TerrainPlc r;
  plc::Plc& p = r.plc;
  r.ids = lift_vertices(tin, stack, p);
  add_surface_facets(tin, layering, r.ids, p);
  add_all_walls(tin, layering, r.ids, p);
  compact_vertices(r.ids, p);
  for (std::size_t s = 0; s + 1 < stack.size(); ++s) add_layer_regions(tin, stack, layering, s, p);
  const std::size_t horizons = stack.size() - 2;
  p.marker_names.assign(static_cast<std::size_t>(kHorizonMarker0) + horizons, "");
  p.marker_names[kTopMarker] = "top";
  p.marker_names[kBaseMarker] = "base";
  p.marker_names[kSideMarker] = "side";
  for (std::size_t k = 0; k < horizons; ++k) p.marker_names[kHorizonMarker0 + k] = stack[k + 1].name;
  p.material_names.assign(stack.size(), "");
  for (std::size_t s = 0; s + 1 < stack.size(); ++s) p.material_names[s + 1] = stack[s].name + "-" + stack[s + 1].name;
  p.source = "terrain";
  return r;
}

std::vector<double> layer_volumes(const Tin& tin, const std::vector<Surface>& stack, const Layering& layering) {
  std::vector<double> vol(stack.empty() ? 0 : stack.size() - 1, 0.0);
  for (std::size_t s = 0; s < vol.size(); ++s) {
    double sum = 0, comp = 0;  // Kahan: many small prisms
    for (std::size_t ti = 0; ti < tin.triangles.size(); ++ti) {
      const auto& t = tin.triangles[ti];
      double th = 0;
      for (int k = 0; k < 3; ++k) th += corner_z(stack, layering, tin, ti, s, k) - corner_z(stack, layering, tin, ti, s + 1, k);
      const double y = tri_area(tin, t) * th / 3.0 - comp;
      const double u = sum + y;
      comp = (u - sum) - y;
      sum = u;
    }
    vol[s] = sum;
  }
  return vol;
}

}  // namespace fdr::terrain
