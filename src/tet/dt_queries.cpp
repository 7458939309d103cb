#include "tet/dt_queries.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include "base/parallel.hpp"
#include "predicates/predicates3d.hpp"

namespace fdr::tet {
namespace {

// Visited tetrahedra are marked with a stamp per call, in marks that live as long as the thread
// (a walk's cost stays proportional to what it visits).
thread_local std::vector<std::uint32_t> marks;
thread_local std::uint32_t stamp_now = 0;

std::uint32_t* next_marks(const Delaunay3& dt) {
  if (marks.size() < dt.tet_slots()) marks.resize(dt.tet_slots() + dt.tet_slots() / 2, 0);
  if (++stamp_now == 0) {
    std::fill(marks.begin(), marks.end(), 0);
    stamp_now = 1;
  }
  return marks.data();
}
std::uint32_t mark_stamp() { return stamp_now; }

bool holds(const std::array<VertexId, 4>& v, VertexId x) {
  return v[0] == x || v[1] == x || v[2] == x || v[3] == x;
}

// The tetrahedra around v, breadth first from dt.vertex_tet(v), into out; the walk stops at the
// first tetrahedron for which stop(t) holds and returns it (kNoId when none does).
template <class Stop>
TetId walk_star(const Delaunay3& dt, VertexId v, std::vector<TetId>& out, Stop stop) {
  out.clear();
  if (dt.dimension() < 3) return kNoId;
  const TetId t0 = dt.vertex_tet(v);
  if (t0 == kNoId) return kNoId;
  std::uint32_t* mark = next_marks(dt);
  const std::uint32_t stamp = mark_stamp();
  out.push_back(t0);
  mark[t0] = stamp;
  for (std::size_t k = 0; k < out.size(); ++k) {
    const TetId t = out[k];
    if (stop(t)) return t;
    const auto& tv = dt.vertices(t);
    for (int i = 0; i < 4; ++i) {
      if (tv[i] == v) continue;  // the face opposite v does not hold v
      const TetId n = dt.neighbour(t, i);
      if (mark[n] != stamp) {
        mark[n] = stamp;
        out.push_back(n);
      }
    }
  }
  return kNoId;
}

}  // namespace

void vertex_star(const Delaunay3& dt, VertexId v, std::vector<TetId>& out) {
  walk_star(dt, v, out, [](TetId) { return false; });
}

bool edge_tets(const Delaunay3& dt, VertexId a, VertexId b, std::vector<TetId>& out) {
  thread_local std::vector<TetId> star;  // scratch: a call allocates nothing once it has grown
  vertex_star(dt, a, star);
  out.clear();
  for (TetId t : star)
    if (holds(dt.vertices(t), b)) out.push_back(t);
  return !out.empty();
}

TetId edge_tet(const Delaunay3& dt, VertexId a, VertexId b) {
  thread_local std::vector<TetId> star;  // scratch: a call allocates nothing once it has grown
  return walk_star(dt, a, star, [&](TetId x) { return holds(dt.vertices(x), b); });
}

void edge_ring(const Delaunay3& dt, TetId t, VertexId a, VertexId b, std::vector<VertexId>& out) {
  // Around the edge from t: across the face (a, b, next) into the tetrahedron whose vertex
  // opposite that face is the one after next, until that one is t's first again.
  out.clear();
  const auto& tv = dt.vertices(t);
  int k[2], m = 0;
  for (int i = 0; i < 4; ++i)
    if (tv[i] != a && tv[i] != b) k[m++] = i;
  out.push_back(tv[k[0]]);
  out.push_back(tv[k[1]]);
  VertexId prev = tv[k[0]];
  TetId cur = t;
  for (;;) {
    const auto& cv = dt.vertices(cur);
    int i = 0;
    while (cv[i] != prev) ++i;
    const TetId n = dt.neighbour(cur, i);
    const VertexId next = dt.vertices(n)[dt.mirror_index(cur, i)];
    if (next == out.front()) return;
    prev = out.back();
    out.push_back(next);
    cur = n;
  }
}

int face_apexes(const Delaunay3& dt, VertexId a, VertexId b, VertexId c, std::array<VertexId, 2>& apex) {
  // The star of a, walked only until a tetrahedron with the face turns up: the other one is its
  // neighbour across that face.
  thread_local std::vector<TetId> star;  // scratch: a call allocates nothing once it has grown
  const TetId t = walk_star(dt, a, star, [&](TetId x) {
    const auto& xv = dt.vertices(x);
    return holds(xv, b) && holds(xv, c);
  });
  if (t == kNoId) return 0;
  const auto& tv = dt.vertices(t);
  int i = 0;
  while (tv[i] == a || tv[i] == b || tv[i] == c) ++i;
  apex[0] = tv[i];
  apex[1] = dt.vertices(dt.neighbour(t, i))[dt.mirror_index(t, i)];
  return 2;
}

void conflict_region(const Delaunay3& dt, Point3 p, TetId start, std::vector<TetId>& out) {
  conflict_region(dt, p, start, out, std::numeric_limits<std::size_t>::max());
}

bool conflict_region(const Delaunay3& dt, Point3 p, TetId start, std::vector<TetId>& out, std::size_t max_size) {
  out.clear();
  if (start == kNoId || dt.is_ghost(start)) return true;
  std::uint32_t* mark = next_marks(dt);
  const std::uint32_t stamp = mark_stamp();
  // The start is destroyed whether or not p is strictly inside its sphere (p on a face or an
  // edge lies on the spheres of the tetrahedra around it).
  out.push_back(start);
  mark[start] = stamp;
  for (std::size_t k = 0; k < out.size(); ++k) {
    for (int i = 0; i < 4; ++i) {
      const TetId n = dt.neighbour(out[k], i);
      if (mark[n] == stamp) continue;
      mark[n] = stamp;
      if (!in_conflict(dt, n, p)) continue;
      if (out.size() >= max_size) return false;
      out.push_back(n);
    }
  }
  return true;
}

bool in_conflict(const Delaunay3& dt, TetId t, Point3 p) {
  auto in_sphere = [&](TetId c) {
    const auto& v = dt.vertices(c);
    return predicates::insphere(dt.point(v[0]), dt.point(v[1]), dt.point(v[2]), dt.point(v[3]), p) > 0;
  };
  if (!dt.is_ghost(t)) return in_sphere(t);
  const auto& v = dt.vertices(t);
  const int o = predicates::orient3d(dt.point(v[0]), dt.point(v[1]), dt.point(v[2]), p);
  return o != 0 ? o > 0 : in_sphere(dt.neighbour(t, 3));
}

void release_query_scratch() {
  std::vector<std::uint32_t>().swap(marks);
  stamp_now = 0;
}

VertexEdgeRatios vertex_edge_ratios(const Delaunay3& dt, const std::function<bool(TetId)>& keep,
                                    const std::function<double(Point3)>& f, unsigned threads) {
  // Squared lengths: the square root is monotone and correctly rounded, so the root of the least
  // square is the least length, as a report that measures lengths directly gets it. Each worker
  // keeps its own per-vertex extremes over fixed chunks of slots; min and max are exact and
  // order-free, so the figures are the same for any thread count.
  constexpr std::size_t kSlotsPerChunk = 16384;
  const std::size_t n = dt.num_vertices(), slots = dt.tet_slots();
  const std::size_t nchunks = (slots + kSlotsPerChunk - 1) / kSlotsPerChunk;
  threads = static_cast<unsigned>(std::max<std::size_t>(1, std::min<std::size_t>(threads, nchunks)));
  struct Extremes {
    std::vector<double> shortest, longest;
  };
  std::vector<Extremes> w(threads, {std::vector<double>(n, std::numeric_limits<double>::infinity()),
                                    std::vector<double>(n, 0.0)});
  parallel_chunks(
      nchunks,
      [&](std::size_t c, unsigned worker) {
        Extremes& e = w[worker];
        for (TetId t = static_cast<TetId>(c * kSlotsPerChunk), end = static_cast<TetId>(std::min(slots, (c + 1) * kSlotsPerChunk));
             t < end; ++t) {
          if (!dt.alive(t) || dt.is_ghost(t) || !keep(t)) continue;
          const auto& v = dt.vertices(t);
          for (int i = 0; i < 4; ++i)
            for (int j = i + 1; j < 4; ++j) {
              const double l2 = norm2(dt.point(v[i]) - dt.point(v[j]));
              for (VertexId u : {v[i], v[j]}) {
                e.shortest[u] = std::min(e.shortest[u], l2);
                e.longest[u] = std::max(e.longest[u], l2);
              }
            }
        }
      },
      threads);
  VertexEdgeRatios r;
  r.nn_over_f_min = std::numeric_limits<double>::infinity();
  for (std::size_t u = 0; u < n; ++u) {
    double s2 = std::numeric_limits<double>::infinity(), l2 = 0;
    for (const Extremes& e : w) {
      s2 = std::min(s2, e.shortest[u]);
      l2 = std::max(l2, e.longest[u]);
    }
    if (l2 == 0) continue;  // a vertex of no kept tetrahedron
    const double fu = f(dt.point(static_cast<VertexId>(u)));
    r.nn_over_f_min = std::min(r.nn_over_f_min, std::sqrt(s2) / fu);
    r.el_over_f_max = std::max(r.el_over_f_max, std::sqrt(l2) / fu);
  }
  if (!std::isfinite(r.nn_over_f_min)) r.nn_over_f_min = 0;
  return r;
}

bool beyond_hull_face(const Delaunay3& dt, TetId g, Point3 p) {
  const auto& v = dt.vertices(g);
  return predicates::orient3d(dt.point(v[0]), dt.point(v[1]), dt.point(v[2]), p) > 0;
}

}  // namespace fdr::tet
