// Internals shared by the io writers and readers: boundary chains, marker names, number formatting.
#include "io/detail.hpp"
#include "base/triangle_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

namespace fdr::io::detail {

// ---------------------------------------------------------------- names

std::string kind_name(std::int32_t marker) {
  switch (static_cast<mesh::EdgeKind>(marker)) {
    case mesh::EdgeKind::kNone: return "none";
    case mesh::EdgeKind::kLand: return "land";
    case mesh::EdgeKind::kIsland: return "island";
    case mesh::EdgeKind::kOpen: return "open";
    case mesh::EdgeKind::kBreakline: return "breakline";
  }
  return "marker" + std::to_string(marker);
}

bool kind_from_name(std::string_view name, std::int32_t& marker) {
  static const char* const kNames[] = {"none", "land", "island", "open", "breakline"};
  for (int k = 0; k < 5; ++k) {
    if (name == kNames[k]) {
      marker = k;
      return true;
    }
  }
  return false;
}

std::string to_lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string file_name(const std::string& path) {
  auto slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

std::string lower_extension(const std::string& path) {
  std::string name = file_name(path);
  auto dot = name.find_last_of('.');
  if (dot == std::string::npos || dot == 0) return "";
  return to_lower(name.substr(dot));
}

// ---------------------------------------------------------------- validation and geometry

void validate_for_output(const mesh::MeshView& m, const std::string& path) {
  const std::size_t n = m.vertices.size();
  auto bad = [&](const std::string& why) { fail_output(path, "invalid mesh: " + why); };
  if (!m.z.empty() && m.z.size() != n) bad("z has " + std::to_string(m.z.size()) + " values for " + std::to_string(n) + " vertices");
  if (!m.f.empty() && m.f.size() != n) bad("f has " + std::to_string(m.f.size()) + " values for " + std::to_string(n) + " vertices");
  if (!m.vertex_marker.empty() && m.vertex_marker.size() != n)
    bad("vertex_marker has " + std::to_string(m.vertex_marker.size()) + " values for " + std::to_string(n) + " vertices");
  for (std::size_t v = 0; v < n; ++v) {
    Point2 w = m.world(static_cast<Index>(v));
    if (!std::isfinite(w.x) || !std::isfinite(w.y)) bad("vertex " + std::to_string(v) + " has a non-finite coordinate");
  }
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const auto& tr = m.triangles[t];
    for (Index v : tr)
      if (v >= n) bad("triangle " + std::to_string(t) + " references vertex " + std::to_string(v) + " of " + std::to_string(n));
    if (tr[0] == tr[1] || tr[1] == tr[2] || tr[0] == tr[2]) bad("triangle " + std::to_string(t) + " repeats a vertex");
  }
  for (std::size_t e = 0; e < m.edges.size(); ++e) {
    const auto& ed = m.edges[e];
    if (ed.a >= n || ed.b >= n) bad("edge " + std::to_string(e) + " references a vertex out of range");
    if (ed.a == ed.b) bad("edge " + std::to_string(e) + " is degenerate (both ends vertex " + std::to_string(ed.a) + ")");
  }
}

std::vector<std::pair<std::string, std::string>> metadata_rows(const WriteOptions& o) {
  std::vector<std::pair<std::string, std::string>> rows = o.metadata;
  bool has_title = false, has_b = false;
  for (const auto& [k, v] : o.metadata) {
    has_title |= k == "title";
    has_b |= k == "bound_B";
  }
  if (!has_title && !o.title.empty()) rows.emplace_back("title", o.title);
  if (!has_b && o.bound_B > 0 && std::isfinite(o.bound_B)) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", o.bound_B);
    rows.emplace_back("bound_B", buf);
  }
  return rows;
}

double triangle_area(const mesh::MeshView& m, std::size_t t) {
  const auto& tr = m.triangles[t];
  return 0.5 * geom::cross2(m.vertices[tr[0]], m.vertices[tr[1]], m.vertices[tr[2]]);
}

double triangle_min_angle_deg(const mesh::MeshView& m, std::size_t t) {
  const auto& tr = m.triangles[t];
  return geom::min_angle_deg(m.vertices[tr[0]], m.vertices[tr[1]], m.vertices[tr[2]]);
}

double triangle_quality(const mesh::MeshView& m, std::size_t t) {
  const auto& tr = m.triangles[t];
  return geom::mean_ratio_quality(m.vertices[tr[0]], m.vertices[tr[1]], m.vertices[tr[2]]);
}

double triangle_quality(const mesh::MeshView& m, std::size_t t, const WriteOptions& o) {
  return o.triangle_quality ? (*o.triangle_quality)[t] : triangle_quality(m, t);
}

double circumradius(const mesh::MeshView& m, std::size_t t, Point2& centre) {
  const auto& tr = m.triangles[t];
  const Point2 a = m.vertices[tr[0]], b = m.vertices[tr[1]], c = m.vertices[tr[2]];
  if (geom::cross2(a, b, c) == 0) {  // the writers place a degenerate triangle's centre at its first corner
    centre = a;
    return std::numeric_limits<double>::infinity();
  }
  double r2 = 0;
  centre = geom::circumcentre(a, b, c, &r2);
  return std::sqrt(r2);
}

std::vector<double> nearest_neighbour_distance(const mesh::MeshView& m) {
  std::vector<double> nn(m.vertices.size(), std::numeric_limits<double>::infinity());
  for (const auto& tr : m.triangles) {
    for (int k = 0; k < 3; ++k) {
      Index a = tr[k], b = tr[(k + 1) % 3];
      double d = dist(m.vertices[a], m.vertices[b]);
      nn[a] = std::min(nn[a], d);
      nn[b] = std::min(nn[b], d);
    }
  }
  return nn;
}

// ---------------------------------------------------------------- chains

namespace {
struct PairHash {
  std::size_t operator()(const std::pair<Index, Index>& p) const {
    return std::hash<std::uint64_t>()(static_cast<std::uint64_t>(p.first) * 0x9E3779B97F4A7C15ull ^ p.second);
  }
};
using EdgeKey = std::pair<Index, Index>;
EdgeKey key_of(Index a, Index b) { return a < b ? EdgeKey{a, b} : EdgeKey{b, a}; }
}  // namespace

void edges_from_chain(mesh::MeshView& m, const std::vector<Index>& nodes, bool closed,
                      std::int32_t marker, std::int32_t part) {
  for (std::size_t i = 0; i + 1 < nodes.size(); ++i) m.edges.push_back({nodes[i], nodes[i + 1], marker, part});
  if (closed && nodes.size() > 2) m.edges.push_back({nodes.back(), nodes.front(), marker, part});
}

std::vector<Chain> build_chains(const mesh::MeshView& m) {
  std::vector<Chain> out;
  if (m.edges.empty()) return out;
  // Which side the mesh lies on, per constrained edge: +1 when a triangle uses min->max,
  // -1 when one uses max->min, 0 when both (interior) or none.
  std::unordered_map<EdgeKey, int, PairHash> side;
  side.reserve(m.edges.size() * 2);
  // Only triangle edges whose both ends are on constrained edges can be constrained: a flag per
  // vertex spares the hash lookup for the (many) other edges.
  std::vector<char> on_edge(m.vertices.size(), 0);
  for (const auto& e : m.edges) {
    side.emplace(key_of(e.a, e.b), 0);
    if (e.a < on_edge.size()) on_edge[e.a] = 1;
    if (e.b < on_edge.size()) on_edge[e.b] = 1;
  }
  for (const auto& tr : m.triangles) {
    for (int k = 0; k < 3; ++k) {
      Index a = tr[k], b = tr[(k + 1) % 3];
      if (a >= on_edge.size() || b >= on_edge.size() || !on_edge[a] || !on_edge[b]) continue;
      auto it = side.find(key_of(a, b));
      if (it == side.end()) continue;
      // Encode: bit 0 = used min->max, bit 1 = used max->min.
      it->second |= (a < b) ? 1 : 2;
    }
  }
  auto dir_of = [&](Index u, Index v) {  // +1: mesh on the left of u->v; -1: on the right; 0 unknown
    int s = side.at(key_of(u, v));
    if (s == 1) return u < v ? 1 : -1;
    if (s == 2) return u < v ? -1 : 1;
    return 0;
  };

  std::vector<std::size_t> order(m.edges.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) {
    const auto &a = m.edges[i], &b = m.edges[j];
    return a.marker != b.marker ? a.marker < b.marker : a.part < b.part;
  });

  for (std::size_t g0 = 0; g0 < order.size();) {
    std::size_t g1 = g0;
    while (g1 < order.size() && m.edges[order[g1]].marker == m.edges[order[g0]].marker &&
           m.edges[order[g1]].part == m.edges[order[g0]].part)
      ++g1;
    // Group edges in input order (order[] is stable within a group).
    std::vector<std::size_t> group(order.begin() + g0, order.begin() + g1);
    std::unordered_map<Index, std::vector<std::size_t>> adj;  // vertex -> positions in group
    std::unordered_map<Index, std::size_t> cursor, rem;
    for (std::size_t i = 0; i < group.size(); ++i) {
      const auto& e = m.edges[group[i]];
      adj[e.a].push_back(i);
      adj[e.b].push_back(i);
      ++rem[e.a];
      ++rem[e.b];
    }
    std::vector<char> used(group.size(), 0);
    // Walk from `start` along unused edges (earliest-listed first) until stuck.
    auto walk = [&](Index start) {
      Chain c;
      c.marker = m.edges[group[0]].marker;
      c.part = m.edges[group[0]].part;
      c.nodes.push_back(start);
      std::size_t first_edge = group.size();
      Index cur = start;
      for (;;) {
        auto& lst = adj[cur];
        auto& cu = cursor[cur];
        while (cu < lst.size() && used[lst[cu]]) ++cu;
        if (cu == lst.size()) break;
        std::size_t i = lst[cu];
        used[i] = 1;
        if (first_edge == group.size()) first_edge = i;
        const auto& e = m.edges[group[i]];
        Index nxt = e.a == cur ? e.b : e.a;
        --rem[cur];
        --rem[nxt];
        cur = nxt;
        c.nodes.push_back(cur);
      }
      if (c.nodes.size() > 2 && c.nodes.back() == c.nodes.front()) {
        c.nodes.pop_back();
        c.closed = true;
      }
      // Orientation: keep the mesh on the left if the boundary edges say so; interior chains
      // follow the stored direction of their first edge.
      int agree = 0, disagree = 0;
      std::size_t k = c.nodes.size();
      std::size_t steps = c.closed ? k : k - 1;
      for (std::size_t s = 0; s < steps; ++s) {
        int d = dir_of(c.nodes[s], c.nodes[(s + 1) % k]);
        if (d > 0) ++agree;
        if (d < 0) ++disagree;
      }
      bool reverse = disagree > agree;
      if (agree == 0 && disagree == 0) reverse = m.edges[group[first_edge]].a != c.nodes[0];
      if (reverse) {
        if (c.closed) std::reverse(c.nodes.begin() + 1, c.nodes.end());
        else std::reverse(c.nodes.begin(), c.nodes.end());
      }
      out.push_back(std::move(c));
    };
    // Paths first: a walk from a vertex of odd remaining degree ends at another such vertex,
    // so after one ordered pass only even degrees (cycles) remain.
    for (std::size_t i = 0; i < group.size(); ++i) {
      for (Index v : {m.edges[group[i]].a, m.edges[group[i]].b})
        if (rem[v] % 2 == 1) walk(v);
    }
    for (std::size_t i = 0; i < group.size(); ++i)
      if (!used[i]) walk(m.edges[group[i]].a);
    g0 = g1;
  }
  return out;
}

}  // namespace fdr::io::detail
