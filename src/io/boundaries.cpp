// Boundary loops of a triangle mesh (walk of the half-edges without twin) split into open and
// wall runs; shared by every writer that carries boundaries.
#include "io/boundaries.hpp"

#include <algorithm>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include "base/error.hpp"
#include "io/detail.hpp"

namespace fdr::io {

namespace {

std::uint64_t directed_key(Index a, Index b) {
  return (static_cast<std::uint64_t>(a) << 32) ^ static_cast<std::uint64_t>(b);
}
std::uint64_t undirected_key(Index a, Index b) { return a < b ? directed_key(a, b) : directed_key(b, a); }

// Order of start nodes: south-west first (x + y), then x, then index.
bool sw_less(const mesh::MeshView& m, Index a, Index b) {
  const Point2 p = m.vertices[a], q = m.vertices[b];
  const double sp = p.x + p.y, sq = q.x + q.y;
  if (sp != sq) return sp < sq;
  if (p.x != q.x) return p.x < q.x;
  return a < b;
}

}  // namespace

std::vector<Index> Boundaries::ordered_nodes() const {
  std::vector<Index> out;
  for (const auto& l : loops) out.insert(out.end(), l.nodes.begin(), l.nodes.end());
  return out;
}

std::vector<char> Boundaries::open_nodes(std::size_t num_vertices) const {
  std::vector<char> open(num_vertices, 0);
  for (const auto& r : runs)
    if (r.kind == BoundaryKind::kOpen)
      for (Index v : r.nodes) open[v] = 1;
  return open;
}

Index pinch_node(const Boundaries& b, std::size_t num_vertices) {
  std::vector<char> seen(num_vertices, 0);
  for (const auto& l : b.loops)
    for (Index v : l.nodes) {
      if (seen[v]) return v;
      seen[v] = 1;
    }
  return kNoId;
}

Boundaries extract_boundaries(const mesh::MeshView& m, const std::string& path) {
  Boundaries out;
  const std::size_t nt = m.triangles.size();
  const std::size_t nv = m.vertices.size();
  auto tail = [&](std::size_t h) { return m.triangles[h / 3][h % 3]; };
  auto head = [&](std::size_t h) { return m.triangles[h / 3][(h % 3 + 1) % 3]; };
  auto next_in_tri = [](std::size_t h) { return 3 * (h / 3) + (h % 3 + 1) % 3; };
  // Half-edges h = 3 t + k grouped by their tail vertex (compressed rows): the twin of a -> b is
  // found among the few half-edges leaving b, with no hashing.
  std::vector<std::size_t> start(nv + 1, 0), out_he(3 * nt);
  for (std::size_t h = 0; h < 3 * nt; ++h) ++start[tail(h) + 1];
  for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  {
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::size_t h = 0; h < 3 * nt; ++h) out_he[fill[tail(h)]++] = h;
  }
  // Each row sorted by head vertex: lookups by binary search, duplicates side by side.
  for (std::size_t v = 0; v < nv; ++v) {
    auto b0 = out_he.begin() + static_cast<std::ptrdiff_t>(start[v]);
    auto b1 = out_he.begin() + static_cast<std::ptrdiff_t>(start[v + 1]);
    std::sort(b0, b1, [&](std::size_t x, std::size_t y) { return head(x) < head(y); });
    for (auto it = b0; it != b1 && it + 1 != b1; ++it)
      if (head(*it) == head(*(it + 1)))
        detail::fail_output(path, "invalid mesh: edge " + std::to_string(v) + "-" + std::to_string(head(*it)) +
                                      " is used twice in the same direction (overlapping or inverted triangles)");
  }
  auto find_half = [&](Index a, Index b) -> std::size_t {  // the half-edge a -> b, or SIZE_MAX
    auto b0 = out_he.begin() + static_cast<std::ptrdiff_t>(start[a]);
    auto b1 = out_he.begin() + static_cast<std::ptrdiff_t>(start[a + 1]);
    auto it = std::lower_bound(b0, b1, b, [&](std::size_t x, Index key) { return head(x) < key; });
    return it != b1 && head(*it) == b ? *it : SIZE_MAX;
  };
  auto twin = [&](std::size_t h) { return find_half(head(h), tail(h)); };

  // Boundary half-edges in triangle order (deterministic).
  std::vector<std::size_t> bnd;
  for (std::size_t h = 0; h < 3 * nt; ++h)
    if (twin(h) == SIZE_MAX) bnd.push_back(h);
  std::unordered_map<std::size_t, std::size_t> pos;  // half-edge -> index in bnd
  pos.reserve(bnd.size() * 2 + 1);
  for (std::size_t i = 0; i < bnd.size(); ++i) pos.emplace(bnd[i], i);

  // Why: the boundary edge after u->v is found by turning around v through the triangles from
  // the one left of u->v until an edge without twin appears; unlike "the other boundary edge at
  // v" this stays correct at pinch nodes, where v has several boundary edges.
  auto successor = [&](std::size_t h) {
    std::size_t cur = next_in_tri(h);  // v -> w in the same triangle
    for (std::size_t guard = 0; guard <= nt; ++guard) {
      const std::size_t tw = twin(cur);
      if (tw == SIZE_MAX) return cur;
      cur = next_in_tri(tw);  // w -> v in the neighbour, then v -> x
    }
    detail::fail_output(path, "invalid mesh: cannot close the boundary around vertex " + std::to_string(head(h)));
  };

  std::unordered_set<std::uint64_t> open_edges;
  for (const auto& e : m.edges)
    if (e.marker == static_cast<std::int32_t>(mesh::EdgeKind::kOpen)) open_edges.insert(undirected_key(e.a, e.b));

  std::vector<char> used(bnd.size(), 0);
  std::size_t steps = 0;
  for (std::size_t i0 = 0; i0 < bnd.size(); ++i0) {
    if (used[i0]) continue;
    BoundaryLoop loop;
    std::size_t h = bnd[i0];
    for (;;) {
      const std::size_t i = pos.at(h);
      if (used[i]) break;
      used[i] = 1;
      if (++steps > bnd.size())
        detail::fail_output(path, "invalid mesh: boundary walk does not close");
      loop.nodes.push_back(tail(h));
      loop.edge_open.push_back(open_edges.count(undirected_key(tail(h), head(h))) ? 1 : 0);
      h = successor(h);
    }
    if (h != bnd[i0])
      detail::fail_output(path, "invalid mesh: boundary walk from vertex " + std::to_string(tail(bnd[i0])) +
                                    " does not return to its start");
    // Signed area (shoelace relative to the first node, for accuracy far from the origin).
    const Point2 o = m.vertices[loop.nodes[0]];
    double a2 = 0;
    for (std::size_t k = 0; k < loop.nodes.size(); ++k) {
      const Point2 p = m.vertices[loop.nodes[k]] - o, q = m.vertices[loop.nodes[(k + 1) % loop.nodes.size()]] - o;
      a2 += p.x * q.y - p.y * q.x;
    }
    loop.signed_area = 0.5 * a2;
    loop.outer = loop.signed_area > 0;
    // Start: south-west-most node, then forward to the start of an open run if the loop mixes kinds.
    const std::size_t k = loop.nodes.size();
    std::size_t s = 0;
    for (std::size_t j = 1; j < k; ++j)
      if (sw_less(m, loop.nodes[j], loop.nodes[s])) s = j;
    bool any_open = false, any_wall = false;
    for (char c : loop.edge_open) (c ? any_open : any_wall) = true;
    if (any_open && any_wall) {
      for (std::size_t d = 0; d < k; ++d) {
        const std::size_t j = (s + d) % k;
        if (loop.edge_open[j] && !loop.edge_open[(j + k - 1) % k]) {
          s = j;
          break;
        }
      }
    }
    std::rotate(loop.nodes.begin(), loop.nodes.begin() + static_cast<std::ptrdiff_t>(s), loop.nodes.end());
    std::rotate(loop.edge_open.begin(), loop.edge_open.begin() + static_cast<std::ptrdiff_t>(s), loop.edge_open.end());
    out.loops.push_back(std::move(loop));
  }
  std::stable_sort(out.loops.begin(), out.loops.end(), [&](const BoundaryLoop& a, const BoundaryLoop& b) {
    if (a.outer != b.outer) return a.outer;
    return sw_less(m, a.nodes[0], b.nodes[0]);
  });

  for (std::size_t li = 0; li < out.loops.size(); ++li) {
    const BoundaryLoop& l = out.loops[li];
    const std::size_t k = l.nodes.size();
    const BoundaryKind wall = l.outer ? BoundaryKind::kLand : BoundaryKind::kIsland;
    auto kind_of = [&](std::size_t e) { return l.edge_open[e] ? BoundaryKind::kOpen : wall; };
    bool uniform = true;
    for (std::size_t e = 1; e < k; ++e) uniform = uniform && l.edge_open[e] == l.edge_open[0];
    if (uniform) {
      out.runs.push_back({kind_of(0), li, true, l.nodes});
      continue;
    }
    // Loops with both kinds start at a run boundary (see above), so runs never wrap around.
    std::size_t e = 0;
    while (e < k) {
      BoundaryRun r;
      r.kind = kind_of(e);
      r.loop = li;
      r.nodes.push_back(l.nodes[e]);
      while (e < k && kind_of(e) == r.kind) {
        r.nodes.push_back(l.nodes[(e + 1) % k]);
        ++e;
      }
      out.runs.push_back(std::move(r));
    }
  }
  return out;
}

}  // namespace fdr::io
