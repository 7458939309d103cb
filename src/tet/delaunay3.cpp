// Delaunay3: point location and Bowyer-Watson insertion.
#include "base/prefetch.hpp"
#include "tet/delaunay3.hpp"
#include <algorithm>
#include <cmath>
#include <sstream>
#include "base/error.hpp"
#include "predicates/predicates.hpp"
#include "predicates/predicates3d.hpp"
#include "tet/spatial_sort.hpp"

namespace fdr::tet {
namespace {
using predicates::insphere;
using predicates::orient3d;

bool collinear(Point3 a, Point3 b, Point3 c) {
  // Collinear in 3D exactly when the three coordinate-plane projections are.
  return predicates::orient2d({a.x, a.y}, {b.x, b.y}, {c.x, c.y}) == 0 &&
         predicates::orient2d({a.y, a.z}, {b.y, b.z}, {c.y, c.z}) == 0 &&
         predicates::orient2d({a.z, a.x}, {b.z, b.x}, {c.z, c.x}) == 0;
}

// The face opposite position j, oriented as the boundary of a positive tetrahedron ((-1)^j times
// the other positions in increasing order) and rotated to start at position i: (i, x, y), as
// kDirEdge[i][j] = {x, y}. A neighbour sharing that face sees it as (i', y', x').
constexpr int kDirEdge[4][4][2] = {
    {{0, 0}, {3, 2}, {1, 3}, {2, 1}},
    {{2, 3}, {0, 0}, {3, 0}, {0, 2}},
    {{3, 1}, {0, 3}, {0, 0}, {1, 0}},
    {{1, 2}, {2, 0}, {0, 1}, {0, 0}},
};
}  // namespace

void Delaunay3::require_finite(Point3 p) const {
  if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) return;
  std::ostringstream os;
  os << "Delaunay tetrahedralization: the point after vertex " << pts_.size() << " has a non-finite coordinate ("
     << p.x << ", " << p.y << ", " << p.z << ")";
  throw Error(ExitCode::kInvalidGeometry, os.str());
}

VertexId Delaunay3::add_vertex(Point3 p) {
  pts_.push_back(p);
  vtet_.push_back(kNoId);
  vlocal_.push_back(kNoId);
  return static_cast<VertexId>(pts_.size() - 1);
}

void Delaunay3::reserve(std::size_t vertices) {
  pts_.reserve(vertices);
  vtet_.reserve(vertices);
  vlocal_.reserve(vertices);
  // About 6.75 tetrahedra per vertex, plus the hull's ghosts and the free slots.
  cells_.reserve(vertices * 7 + 1024);
  in_cavity_.reserve(cells_.capacity());
}

BulkInsertion Delaunay3::insert_all(std::span<const Point3> pts) {
  BulkInsertion out;
  for (const Point3& p : pts) require_finite(p);  // before any change
  out.vertex_of.assign(pts.size(), kNoId);
  pts_.reserve(pts_.size() + pts.size());
  vtet_.reserve(vtet_.size() + pts.size());
  vlocal_.reserve(vlocal_.size() + pts.size());
  // About 6.75 tetrahedra per point in random position, plus the hull's ghosts: room for 7 per
  // point spares the copy that growing the array would make at its largest.
  cells_.reserve(cells_.size() + pts.size() * 7 + 1024);
  in_cavity_.reserve(cells_.capacity());
  const std::vector<Index> order = brio_order(pts);
  for (std::size_t k = 0; k < order.size(); ++k) {
    // The order jumps across the input: fetch a few points ahead.
    if (k + 8 < order.size()) {
      fdr::prefetch(&pts[order[k + 8]]);
      fdr::prefetch_for_write(&out.vertex_of[order[k + 8]]);
    }
    const Index i = order[k];
    const Insertion r = insert(pts[i], kNoId, nullptr);
    out.vertex_of[i] = r.vertex;
    if (r.duplicate) out.duplicates.push_back(i);
  }
  std::sort(out.duplicates.begin(), out.duplicates.end());
  return out;
}

Insertion Delaunay3::insert(Point3 p, TetId hint, std::vector<TetId>* created) {
  require_finite(p);
  if (dug_live_) throw Error(ExitCode::kInternal, "Delaunay3::insert while a dug cavity waits");
  if (dim_ < 3) return insert_low_dim(p, created);
  const TetId t = locate(p, hint);
  if (!is_ghost(t))
    for (const VertexId v : cells_[t].v)
      if (pts_[v] == p) return {v, true};
  const VertexId v = add_vertex(p);
  insert_vertex(v, t, created);
  return {v, false};
}

Insertion Delaunay3::insert_low_dim(Point3 p, std::vector<TetId>* created) {
  if (const auto it = pending_at_.find({p.x, p.y, p.z}); it != pending_at_.end()) return {it->second, true};
  const VertexId v = add_vertex(p);
  pending_.push_back(v);
  pending_at_.emplace(std::array<double, 3>{p.x, p.y, p.z}, v);
  if (dim_ < 0) {
    span_[0] = v;
    dim_ = 0;
  } else if (dim_ == 0) {
    span_[1] = v;
    dim_ = 1;
  } else if (dim_ == 1) {
    if (!collinear(pts_[span_[0]], pts_[span_[1]], p)) {
      span_[2] = v;
      dim_ = 2;
    }
  } else if (orient3d(pts_[span_[0]], pts_[span_[1]], pts_[span_[2]], p) != 0) {
    build_first_tet(span_[0], span_[1], span_[2], v);
    std::vector<VertexId> rest;
    for (const VertexId u : pending_)
      if (u != span_[0] && u != span_[1] && u != span_[2] && u != v) rest.push_back(u);
    pending_ = {};
    pending_at_ = {};
    for (const VertexId u : rest) insert_vertex(u, locate(pts_[u], last_), nullptr);
    if (created)
      for (TetId t = 0; t < cells_.size(); ++t)
        if (alive(t)) created->push_back(t);
  }
  return {v, false};
}

void Delaunay3::build_first_tet(VertexId a, VertexId b, VertexId c, VertexId d) {
  if (orient3d(pts_[a], pts_[b], pts_[c], pts_[d]) < 0) std::swap(a, b);
  const std::array<VertexId, 4> v{a, b, c, d};
  cells_.resize(5);
  in_cavity_.resize(5, 0);
  cells_[0].v = v;
  for (int i = 0; i < 4; ++i) {
    // The ghost on the face opposite v[i]: v[i] replaced by the infinite vertex, then one swap
    // (the infinite vertex to position 3) to turn the face outward.
    std::array<VertexId, 4> g = v;
    g[i] = kInfinite;
    if (i != 3) std::swap(g[i], g[3]);
    else std::swap(g[0], g[1]);
    cells_[1 + i].v = g;
  }
  // Five tetrahedra: pair their faces by vertex sets.
  auto face = [&](TetId t, int i) {
    std::array<VertexId, 3> f{};
    for (int m = 0, k = 0; m < 4; ++m)
      if (m != i) f[k++] = cells_[t].v[m];
    std::sort(f.begin(), f.end());
    return f;
  };
  for (TetId t = 0; t < 5; ++t)
    for (int i = 0; i < 4; ++i)
      for (TetId u = 0; u < 5; ++u)
        for (int j = 0; j < 4; ++j)
          if (u != t && face(t, i) == face(u, j)) cells_[t].n[i] = 4 * u + static_cast<Index>(j);
  for (const VertexId u : v) vtet_[u] = 0;
  finite_ = 1;
  last_ = 0;
  dim_ = 3;
}

TetId Delaunay3::locate(Point3 p, TetId hint) const {
  if (dim_ < 3) return kNoId;
  TetId t = (hint == kNoId || hint >= cells_.size() || !alive(hint)) ? last_ : hint;
  if (is_ghost(t)) t = neighbour(t, 3);
  return walk(p, t);
}

TetId Delaunay3::walk(Point3 p, TetId t) const {
  // A visibility walk: cross any face that p lies strictly beyond. In a Delaunay
  // tetrahedralization it cannot cycle whatever face is tried first; the rotating first face
  // only keeps the walk from favouring one direction.
  int from = -1;
  std::uint32_t turn = 0;
  for (std::size_t steps = 0;; ++steps) {
    if (steps > cells_.size()) return scan(p);
    const Cell& c = cells_[t];
    const Point3 q[4] = {pts_[c.v[0]], pts_[c.v[1]], pts_[c.v[2]], pts_[c.v[3]]};
    const int s = static_cast<int>(turn++ & 3);
    int next = -1;
    for (int k = 0; k < 4; ++k) {
      const int i = (s + k) & 3;
      if (i == from) continue;
      Point3 r[4] = {q[0], q[1], q[2], q[3]};
      r[i] = p;
      if (orient3d(r[0], r[1], r[2], r[3]) < 0) {
        next = i;
        break;
      }
    }
    if (next < 0) return t;
    t = c.n[next] >> 2;
    from = static_cast<int>(c.n[next] & 3);
    if (is_ghost(t)) return t;
  }
}

TetId Delaunay3::scan(Point3 p) const {
  // Every tetrahedron in turn: a safety net should a walk ever run longer than there are
  // tetrahedra (it cannot cycle in a Delaunay tetrahedralization).
  for (TetId t = 0; t < cells_.size(); ++t) {
    if (!alive(t)) continue;
    const auto& v = cells_[t].v;
    if (is_ghost(t)) {
      if (orient3d(pts_[v[0]], pts_[v[1]], pts_[v[2]], p) > 0) return t;
      continue;
    }
    bool inside = true;
    for (int i = 0; i < 4 && inside; ++i) {
      Point3 r[4] = {pts_[v[0]], pts_[v[1]], pts_[v[2]], pts_[v[3]]};
      r[i] = p;
      inside = orient3d(r[0], r[1], r[2], r[3]) >= 0;
    }
    if (inside) return t;
  }
  return last_;
}

bool Delaunay3::conflict(TetId t, Point3 p) const {
  const Cell& c = cells_[t];
  if (c.v[3] != kInfinite)
    return insphere(pts_[c.v[0]], pts_[c.v[1]], pts_[c.v[2]], pts_[c.v[3]], p) > 0;
  // A ghost conflicts when p lies strictly beyond its hull face, or on the face's plane inside
  // the face's circumcircle, which is where the plane cuts the finite neighbour's circumsphere.
  const int o = orient3d(pts_[c.v[0]], pts_[c.v[1]], pts_[c.v[2]], p);
  if (o != 0) return o > 0;
  const Cell& f = cells_[c.n[3] >> 2];
  return insphere(pts_[f.v[0]], pts_[f.v[1]], pts_[f.v[2]], pts_[f.v[3]], p) > 0;
}

void Delaunay3::insert_vertex(VertexId v, TetId start, std::vector<TetId>* created) {
  dig_cavity(start, pts_[v], v);
  fill_cavity(v, created);
}

Insertion Delaunay3::dig(Point3 p, TetId located) {
  require_finite(p);
  if (dim_ < 3 || dug_live_ || located == kNoId || located >= cells_.size() || !alive(located))
    throw Error(ExitCode::kInternal, "Delaunay3::dig: no tetrahedron to start from, or a cavity already dug");
  if (!is_ghost(located))
    for (const VertexId v : cells_[located].v)
      if (pts_[v] == p) return {v, true};
  // The new vertex's id is the next one, fixed now: the new tetrahedra are described with it.
  dig_cavity(located, p, static_cast<VertexId>(pts_.size()));
  dug_ = p;
  dug_live_ = true;
  return {};
}

Insertion Delaunay3::insert_dug(std::vector<TetId>* created) {
  if (!dug_live_) throw Error(ExitCode::kInternal, "Delaunay3::insert_dug without a cavity dug");
  dug_live_ = false;
  const VertexId v = add_vertex(dug_);
  fill_cavity(v, created);
  return {v, false};
}

void Delaunay3::abandon() {
  if (!dug_live_) return;
  dug_live_ = false;
  clear_cavity_marks();
  cavity_.clear();
  ball_.clear();
}

void Delaunay3::clear_cavity_marks() {
  for (const TetId t : cavity_) in_cavity_[t] = 0;
  for (const NewCell& nc : ball_) in_cavity_[nc.outside >> 2] = 0;
}

void Delaunay3::dig_cavity(TetId start, Point3 p, VertexId v) {
  // The cavity: the tetrahedra whose circumspheres strictly hold p, grown across faces from the
  // one that holds p (they form a connected, star-shaped set). Each face to a tetrahedron
  // outside it becomes a new tetrahedron with p. Marks: 1 in the cavity, 2 tested and outside
  // (a tetrahedron next to several cavity ones is tested once).
  cavity_.clear();
  ball_.clear();
  in_cavity_[start] = 1;
  cavity_.push_back(start);
  for (const Index c : cells_[start].n) {
    fdr::prefetch(&cells_[c >> 2]);
    fdr::prefetch(&in_cavity_[c >> 2]);
  }
  for (std::size_t k = 0; k < cavity_.size(); ++k) {
    const TetId t = cavity_[k];
    for (int i = 0; i < 4; ++i) {
      const Index code = cells_[t].n[i];
      const TetId nb = code >> 2;
      std::uint8_t& mark = in_cavity_[nb];
      if (mark == 1) continue;
      if (mark == 0) {
        if (conflict(nb, p)) {
          mark = 1;
          cavity_.push_back(nb);
          // Its neighbours are tested when its turn comes: start fetching them now, since they
          // may lie anywhere in the array and the test would wait for memory.
          for (const Index c : cells_[nb].n) {
            fdr::prefetch(&cells_[c >> 2]);
            fdr::prefetch(&in_cavity_[c >> 2]);
          }
          continue;
        }
        mark = 2;
      }
      NewCell nc{cells_[t].v, code, i};
      nc.v[i] = v;
      ball_.push_back(nc);
    }
  }
}

TetId Delaunay3::new_slot() {
  if (!free_.empty()) {
    const TetId t = free_.back();
    free_.pop_back();
    return t;
  }
  cells_.push_back(Cell{});
  in_cavity_.push_back(0);
  return static_cast<TetId>(cells_.size() - 1);
}

void Delaunay3::fill_cavity(VertexId v, std::vector<TetId>* created) {
  ball_ids_.clear();
  std::size_t reused = 0;
  clear_cavity_marks();
  for (const TetId t : cavity_)
    if (!is_ghost(t)) --finite_;
  for (const NewCell& nc : ball_) {
    const TetId id = reused < cavity_.size() ? cavity_[reused++] : new_slot();
    Cell& c = cells_[id];
    c.v = nc.v;
    c.n[nc.i] = nc.outside;
    cells_[nc.outside >> 2].n[nc.outside & 3] = 4 * id + static_cast<Index>(nc.i);
    ball_ids_.push_back(id);
    if (c.v[3] != kInfinite) {
      ++finite_;
      last_ = id;
    }
  }
  vtet_[v] = ball_ids_.back();
  for (; reused < cavity_.size(); ++reused) {
    cells_[cavity_[reused]].v.fill(kNoId);
    free_.push_back(cavity_[reused]);
  }
  link_new_faces(ball_ids_);
  if (created) created->insert(created->end(), ball_ids_.begin(), ball_ids_.end());
}

void Delaunay3::link_new_faces(std::span<const TetId> ids) {
  // The faces through the new vertex pair up across the edges of the cavity's boundary: the
  // face opposite position j of a new tetrahedron holds the new vertex and one boundary edge,
  // and exactly one other new tetrahedron holds that edge with the new vertex, in the opposite
  // direction (the two induce opposite orientations on their shared face). The boundary's
  // vertices get small local numbers, so that a directed edge is a cell of a small square table;
  // the first new tetrahedron to meet a vertex becomes its vertex tetrahedron.
  local_verts_.clear();
  auto local = [&](VertexId u, TetId id) -> Index {
    if (u == kInfinite) return 0;
    if (vlocal_[u] == kNoId) {
      local_verts_.push_back(u);
      vlocal_[u] = static_cast<Index>(local_verts_.size());
      vtet_[u] = id;
    }
    return vlocal_[u];
  };
  if (++stamp_ == 0) {  // the stamps wrapped around: forget every old one
    std::fill(edge_dense_.begin(), edge_dense_.end(), DenseSlot{});
    stamp_ = 1;
  }
  constexpr Index n = kMaxDenseLocals;
  bool dense = true;
  for (std::size_t k = 0; k < ids.size() && dense; ++k) {
    const TetId id = ids[k];
    const int i = ball_[k].i;
    const auto& v = cells_[id].v;
    for (int j = 0; j < 4 && dense; ++j) {
      if (j == i) continue;
      const Index a = local(v[kDirEdge[i][j][0]], id), b = local(v[kDirEdge[i][j][1]], id);
      if (a >= n || b >= n) {
        dense = false;
        break;
      }
      const DenseSlot& other = edge_dense_[b * n + a];
      if (other.stamp == stamp_) {
        cells_[id].n[j] = other.code;
        cells_[other.code >> 2].n[other.code & 3] = 4 * id + static_cast<Index>(j);
      } else {
        edge_dense_[a * n + b] = {stamp_, 4 * id + static_cast<Index>(j)};
      }
    }
  }
  if (!dense) {
    // A cavity with too many boundary vertices for the table (degenerate inputs): start over.
    link_by_hash(ids);
    for (const TetId id : ids)
      for (const VertexId u : cells_[id].v)
        if (u != kInfinite) vtet_[u] = id;
  }
  for (const VertexId u : local_verts_) vlocal_[u] = kNoId;
}

void Delaunay3::link_by_hash(std::span<const TetId> ids) {
  // The same pairing for large cavities (degenerate inputs), keyed by the directed edge's
  // local numbers in an open-addressing table.
  std::size_t cap = 64;
  int shift = 64 - 6;
  while (cap < 4 * ids.size()) {
    cap *= 2;
    --shift;
  }
  if (edge_table_.size() < cap) edge_table_.assign(cap, EdgeSlot{});
  const std::size_t mask = cap - 1;
  edge_used_.clear();
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const TetId id = ids[k];
    const int i = ball_[k].i;
    const auto& v = cells_[id].v;
    for (int j = 0; j < 4; ++j) {
      if (j == i) continue;
      const VertexId x = v[kDirEdge[i][j][0]], y = v[kDirEdge[i][j][1]];
      const VertexId a = std::min(x, y), b = std::max(x, y);
      const std::uint64_t mix = (std::uint64_t(a) * 0x9E3779B97F4A7C15ull) ^ (std::uint64_t(b) * 0xC2B2AE3D27D4EB4Full);
      std::size_t h = static_cast<std::size_t>(mix >> shift);
      for (;; h = (h + 1) & mask) {
        EdgeSlot& slot = edge_table_[h];
        if (slot.a == a && slot.b == b) {
          const Index other = slot.code;
          cells_[id].n[j] = other;
          cells_[other >> 2].n[other & 3] = 4 * id + static_cast<Index>(j);
          break;
        }
        if (slot.a == kNoId) {
          slot = {a, b, 4 * id + static_cast<Index>(j)};
          edge_used_.push_back(h);
          break;
        }
      }
    }
  }
  for (const std::size_t h : edge_used_) edge_table_[h].a = kNoId;
}

}  // namespace fdr::tet
