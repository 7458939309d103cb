// Boundary loops of a triangle mesh (walk of the half-edges without twin) split into open and
// wall runs; shared by every writer that carries boundaries.
#include "io/boundaries.hpp"

#include <algorithm>
#include <string>
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

namespace {

// Half-edges h = 3 t + k grouped by their tail vertex (compressed rows of (head, h), the head
// stored beside h so that a row is read without touching the triangles): the twin of a -> b is
// found among the few half-edges leaving b, with no hashing. For meshes without the mesher's
// adjacency (a mesh read from a file).
struct HalfEdgeRows {
  struct Out {
    Index head;
    Index he;
  };
  std::vector<std::size_t> start;
  std::vector<Out> out_he;
  std::size_t find(Index a, Index b) const {  // the half-edge a -> b, or SIZE_MAX
    const Out* b0 = out_he.data() + start[a];
    const Out* b1 = out_he.data() + start[a + 1];
    const Out* it = std::lower_bound(b0, b1, b, [](const Out& x, Index key) { return x.head < key; });
    return it != b1 && it->head == b ? it->he : SIZE_MAX;
  }
};

// Fills `rows` and returns the boundary half-edges in increasing order (triangle order); fails
// on an edge used twice in the same direction.
std::vector<std::size_t> build_rows(const mesh::MeshView& m, const std::string& path, HalfEdgeRows& rows) {
  using Out = HalfEdgeRows::Out;
  const std::size_t nt = m.triangles.size(), nv = m.vertices.size();
  std::vector<std::size_t>& start = rows.start;
  std::vector<Out>& out_he = rows.out_he;
  start.assign(nv + 1, 0);
  out_he.resize(3 * nt);
  // Row v also lists the tails of the half-edges entering v (as many as leave it: one of each
  // per triangle at v), sorted: v -> w has a twin iff w is among them, decided row by row with
  // no lookup in another row.
  std::vector<Index> in_tail(3 * nt);
  std::vector<std::size_t> bnd;
  for (const auto& tr : m.triangles)
    for (Index v : tr) ++start[v + 1];
  for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  {
    // One cursor array for both fills (the rows' ends, counted down): less memory at the peak.
    std::vector<std::size_t> fill(start.begin() + 1, start.end());
    for (std::size_t t = nt; t-- > 0;)
      for (std::size_t k = 3; k-- > 0;) out_he[--fill[m.triangles[t][k]]] = {m.triangles[t][(k + 1) % 3], static_cast<Index>(3 * t + k)};
    std::copy(start.begin() + 1, start.end(), fill.begin());
    for (std::size_t t = nt; t-- > 0;)
      for (std::size_t k = 3; k-- > 0;) in_tail[--fill[m.triangles[t][(k + 1) % 3]]] = m.triangles[t][k];
  }
  // Each row sorted by head vertex (then h: filled in h order, and the sorts are stable):
  // lookups by binary search, duplicates side by side.
  for (std::size_t v = 0; v < nv; ++v) {
    Out* b0 = out_he.data() + start[v];
    Out* b1 = out_he.data() + start[v + 1];
    Index* i0 = in_tail.data() + start[v];
    Index* i1 = in_tail.data() + start[v + 1];
    auto by_head = [](const Out& x, const Out& y) { return x.head < y.head; };
    if (b1 - b0 <= 32) {
      for (Out* i = b0 + 1; i < b1; ++i)  // insertion sorts: a vertex has a handful of half-edges
        for (Out* j = i; j > b0 && by_head(*j, *(j - 1)); --j) std::swap(*j, *(j - 1));
      for (Index* i = i0 + 1; i < i1; ++i)
        for (Index* j = i; j > i0 && *j < *(j - 1); --j) std::swap(*j, *(j - 1));
    } else {
      std::stable_sort(b0, b1, by_head);
      std::sort(i0, i1);
    }
    for (Out* it = b0; it != b1 && it + 1 != b1; ++it)
      if (it->head == (it + 1)->head)
        detail::fail_output(path, "invalid mesh: edge " + std::to_string(v) + "-" + std::to_string(it->head) +
                                      " is used twice in the same direction (overlapping or inverted triangles)");
    // v -> w is a boundary half-edge iff no half-edge w -> v: a merge of the two sorted lists.
    const Index* in = i0;
    for (const Out* it = b0; it != b1; ++it) {
      while (in != i1 && *in < it->head) ++in;
      if (in == i1 || *in != it->head) bnd.push_back(it->he);
    }
  }
  std::sort(bnd.begin(), bnd.end());
  return bnd;
}

// Signed area, outer flag, and the start of the loop: its south-west-most node, then forward to
// the start of an open run if the loop mixes kinds (so that runs never wrap around).
void place_loop_start(const mesh::MeshView& m, BoundaryLoop& loop) {
  // Shoelace relative to the first node, for accuracy far from the origin.
  const Point2 o = m.vertices[loop.nodes[0]];
  double a2 = 0;
  for (std::size_t k = 0; k < loop.nodes.size(); ++k) {
    const Point2 p = m.vertices[loop.nodes[k]] - o, q = m.vertices[loop.nodes[(k + 1) % loop.nodes.size()]] - o;
    a2 += p.x * q.y - p.y * q.x;
  }
  loop.signed_area = 0.5 * a2;
  loop.outer = loop.signed_area > 0;
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
}

// The loops through the boundary half-edges `bnd` (increasing), each from its first unused
// half-edge; twin(h) is the half-edge opposite h, or SIZE_MAX on the boundary.
template <class Twin>
std::vector<BoundaryLoop> walk_loops(const mesh::MeshView& m, const std::string& path,
                                     const std::vector<std::size_t>& bnd, Twin twin) {
  const std::size_t nt = m.triangles.size();
  auto tail = [&](std::size_t h) { return m.triangles[h / 3][h % 3]; };
  auto head = [&](std::size_t h) { return m.triangles[h / 3][(h % 3 + 1) % 3]; };
  auto next_in_tri = [](std::size_t h) { return 3 * (h / 3) + (h % 3 + 1) % 3; };
  // Index in bnd of a boundary half-edge (bnd is increasing: a binary search, no hash table).
  auto pos_of = [&](std::size_t h) {
    const auto it = std::lower_bound(bnd.begin(), bnd.end(), h);
    if (it == bnd.end() || *it != h) detail::fail_output(path, "invalid mesh: boundary walk leaves the boundary");
    return static_cast<std::size_t>(it - bnd.begin());
  };
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

  std::vector<BoundaryLoop> loops;
  std::vector<char> used(bnd.size(), 0);
  std::size_t steps = 0;
  for (std::size_t i0 = 0; i0 < bnd.size(); ++i0) {
    if (used[i0]) continue;
    BoundaryLoop loop;
    std::size_t h = bnd[i0];
    for (;;) {
      const std::size_t i = pos_of(h);
      if (used[i]) break;
      used[i] = 1;
      if (++steps > bnd.size()) detail::fail_output(path, "invalid mesh: boundary walk does not close");
      loop.nodes.push_back(tail(h));
      loop.edge_open.push_back(open_edges.count(undirected_key(tail(h), head(h))) ? 1 : 0);
      h = successor(h);
    }
    if (h != bnd[i0])
      detail::fail_output(path, "invalid mesh: boundary walk from vertex " + std::to_string(tail(bnd[i0])) +
                                    " does not return to its start");
    place_loop_start(m, loop);
    loops.push_back(std::move(loop));
  }
  return loops;
}

// The runs of out.loops: a loop of one kind is one closed run; a mixed loop starts at a run
// boundary (place_loop_start), so its runs never wrap around.
void split_runs(Boundaries& out) {
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
}

}  // namespace

Boundaries extract_boundaries(const mesh::MeshView& m, const std::string& path) {
  Boundaries out;
  const std::size_t nt = m.triangles.size();
  // With the mesher's adjacency (MeshView::neighbours) the twin of a half-edge is one array read
  // (a mesh from the mesher is valid by construction); a mesh read from a file has none.
  if (m.neighbours.size() == 3 * nt) {
    std::vector<std::size_t> bnd;  // boundary half-edges in triangle order (deterministic)
    for (std::size_t h = 0; h < 3 * nt; ++h)
      if (m.neighbours[h] == kNoId) bnd.push_back(h);
    out.loops = walk_loops(m, path, bnd, [&m](std::size_t h) {
      return m.neighbours[h] == kNoId ? SIZE_MAX : static_cast<std::size_t>(m.neighbours[h]);
    });
  } else {
    HalfEdgeRows rows;
    const std::vector<std::size_t> bnd = build_rows(m, path, rows);
    out.loops = walk_loops(m, path, bnd, [&m, &rows](std::size_t h) {
      const auto& tr = m.triangles[h / 3];
      return rows.find(tr[(h % 3 + 1) % 3], tr[h % 3]);  // head -> tail
    });
  }
  std::stable_sort(out.loops.begin(), out.loops.end(), [&](const BoundaryLoop& a, const BoundaryLoop& b) {
    if (a.outer != b.outer) return a.outer;
    return sw_less(m, a.nodes[0], b.nodes[0]);
  });
  split_runs(out);
  return out;
}

const Boundaries& BoundaryCache::get(const mesh::MeshView& m, const std::string& path) {
  std::lock_guard<std::mutex> lock(mu_);
  if (!done_) {
    b_ = extract_boundaries(m, path);
    done_ = true;
  }
  return b_;
}

const Boundaries& boundaries_for(const mesh::MeshView& m, const std::string& path, BoundaryCache* cache,
                                 Boundaries& own) {
  if (cache) return cache->get(m, path);
  own = extract_boundaries(m, path);
  return own;
}

}  // namespace fdr::io
