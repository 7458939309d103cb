// The terrain PLC from a stack of surfaces on one TIN (terrain_plc.hpp).
#include "terrain/terrain_plc.hpp"
#include <algorithm>
#include <cmath>
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

// The vertex ids of every surface: a new vertex unless the surface meets the one above at v.
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

std::int32_t surface_marker(std::size_t s, std::size_t n) {
  if (s == 0) return kTopMarker;
  if (s + 1 == n) return kBaseMarker;
  return kHorizonMarker0 + static_cast<std::int32_t>(s - 1);
}

// One facet per TIN triangle and surface, except where a surface meets the one above at all three
// corners: that facet is shared, and it is a base facet when the base is among the surfaces
// meeting there (the boundary groups stay whole).
void add_surface_facets(const Tin& tin, const std::vector<std::vector<VertexId>>& ids, plc::Plc& out) {
  const std::size_t n = ids.size();
  for (const auto& t : tin.triangles) {
    std::size_t last = 0;
    for (std::size_t s = 0; s < n; ++s) {
      const std::vector<VertexId> poly{ids[s][t[0]], ids[s][t[1]], ids[s][t[2]]};
      if (s > 0 && poly[0] == ids[s - 1][t[0]] && poly[1] == ids[s - 1][t[1]] && poly[2] == ids[s - 1][t[2]]) {
        if (s + 1 == n) out.facets[last].marker = kBaseMarker;
        continue;
      }
      plc::Facet f;
      f.polygons.push_back(poly);
      f.marker = surface_marker(s, n);
      last = out.facets.size();
      out.facets.push_back(std::move(f));
    }
  }
}

void add_side_walls(const Tin& tin, const std::vector<std::vector<VertexId>>& ids, plc::Plc& out) {
  for (const auto& [a, b] : boundary_edges(tin))
    for (std::size_t s = 0; s + 1 < ids.size(); ++s) {
      std::vector<VertexId> poly{ids[s][a], ids[s][b]};
      if (ids[s + 1][b] != ids[s][b]) poly.push_back(ids[s + 1][b]);
      if (ids[s + 1][a] != ids[s][a]) poly.push_back(ids[s + 1][a]);
      if (poly.size() < 3) continue;  // the layer is pinched at both ends of the edge
      plc::Facet f;
      f.polygons.push_back(std::move(poly));
      f.marker = kSideMarker;
      out.facets.push_back(std::move(f));
    }
}

// Union-find root with path halving.
std::size_t root(std::vector<std::size_t>& parent, std::size_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

// One region point per connected part of layer s (between surfaces s and s + 1): triangles of
// positive thickness at some corner, joined across edges of positive thickness at some end (an
// edge pinched at both ends closes the layer there). The point is above the centroid of the part's
// thickest triangle, half-way between the two surfaces.
void add_layer_regions(const Tin& tin, const std::vector<Surface>& stack, std::size_t s, plc::Plc& out) {
  const std::vector<double>& up = stack[s].z;
  const std::vector<double>& lo = stack[s + 1].z;
  auto thick = [&](VertexId v) { return up[v] > lo[v]; };
  const std::size_t nt = tin.triangles.size();
  std::vector<std::size_t> parent(nt);
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  std::map<Edge, std::size_t> first;
  for (std::size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      const VertexId a = tin.triangles[t][k], b = tin.triangles[t][(k + 1) % 3];
      if (!thick(a) && !thick(b)) continue;
      const auto [it, fresh] = first.emplace(key(a, b), t);
      if (!fresh) parent[root(parent, t)] = root(parent, it->second);
    }
  std::map<std::size_t, std::pair<double, std::size_t>> best;  // part root -> (thickness, triangle)
  for (std::size_t t = 0; t < nt; ++t) {
    const auto& tr = tin.triangles[t];
    const double th = (up[tr[0]] - lo[tr[0]] + up[tr[1]] - lo[tr[1]] + up[tr[2]] - lo[tr[2]]) / 3.0;
    if (!(th > 0)) continue;
    auto [it, fresh] = best.emplace(root(parent, t), std::make_pair(th, t));
    if (!fresh && th > it->second.first) it->second = {th, t};
  }
  for (const auto& [r, tt] : best) {
    const auto& tr = tin.triangles[tt.second];
    Point3 p{0, 0, 0};
    for (VertexId v : tr) p = p + Point3{tin.xy[v].x / 3.0, tin.xy[v].y / 3.0, (up[v] + lo[v]) / 6.0};
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

TerrainPlc build_terrain_plc(const Tin& tin, const std::vector<Surface>& stack) {
  if (stack.size() < 2) throw Error(ExitCode::kInvalidGeometry, "a terrain volume needs a top and a base");
  TerrainPlc r;
  plc::Plc& p = r.plc;
  r.ids = lift_vertices(tin, stack, p);
  add_surface_facets(tin, r.ids, p);
  add_side_walls(tin, r.ids, p);
  for (std::size_t s = 0; s + 1 < stack.size(); ++s) add_layer_regions(tin, stack, s, p);
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

std::vector<double> layer_volumes(const Tin& tin, const std::vector<Surface>& stack) {
  std::vector<double> vol(stack.empty() ? 0 : stack.size() - 1, 0.0);
  for (std::size_t s = 0; s < vol.size(); ++s) {
    double sum = 0, comp = 0;  // Kahan: many small prisms
    for (const auto& t : tin.triangles) {
      double th = 0;
      for (VertexId v : t) th += stack[s].z[v] - stack[s + 1].z[v];
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
