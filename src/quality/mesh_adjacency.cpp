// Triangle adjacency of a MeshView and the exact nearest-neighbour walk over it.
#include "quality/mesh_adjacency.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <unordered_set>

#include "base/parallel.hpp"
#include "quality/orthogonality.hpp"

namespace fdr::quality {

std::vector<Index> half_edge_neighbours(const mesh::MeshView& m) {
  const std::size_t nt = m.triangles.size(), nv = m.vertices.size();
  if (m.neighbours.size() == 3 * nt) return m.neighbours;
  // Half-edges grouped by tail vertex (compressed rows), each with its head, sorted by head: the
  // twin of a -> b is a binary search among the half-edges leaving b. No hashing.
  struct Out {
    Index head;
    Index he;
  };
  std::vector<std::size_t> start(nv + 1, 0);
  for (const auto& tr : m.triangles)
    for (Index v : tr) ++start[v + 1];
  for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  std::vector<Out> out(3 * nt);
  {
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::size_t t = 0; t < nt; ++t)
      for (int k = 0; k < 3; ++k)
        out[fill[m.triangles[t][k]]++] = {m.triangles[t][(k + 1) % 3], static_cast<Index>(3 * t + k)};
  }
  auto before = [](const Out& x, const Out& y) { return x.head < y.head || (x.head == y.head && x.he < y.he); };
  for (std::size_t v = 0; v < nv; ++v) {
    Out* b = out.data() + start[v];
    Out* e = out.data() + start[v + 1];
    for (Out* i = b + 1; i < e; ++i)  // insertion sort: a vertex has a handful of half-edges
      for (Out* j = i; j > b && before(*j, *(j - 1)); --j) std::swap(*j, *(j - 1));
  }
  std::vector<Index> nb(3 * nt, kNoId);
  for (std::size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      const Index a = m.triangles[t][k], b = m.triangles[t][(k + 1) % 3];
      const Out* b0 = out.data() + start[b];
      const Out* b1 = out.data() + start[b + 1];
      const Out* it = std::lower_bound(b0, b1, a, [](const Out& x, Index key) { return x.head < key; });
      if (it != b1 && it->head == a) nb[3 * t + k] = it->he;
    }
  return nb;
}

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// True when segment uv may come closer to p than sqrt(r2). Conservative: the slack (relative to
// r2 and to the operands' own size) only makes the walk visit a little more, so rounding in this
// test can never hide a vertex; the distances that decide the result are computed exactly as
// the brute force computes them.
inline bool segment_near(Point2 p, Point2 u, Point2 v, double r2) {
  const Point2 d = p - u, e = v - u;
  const double l2 = norm2(e);
  const double t = l2 > 0 ? std::clamp(dot(d, e) / l2, 0.0, 1.0) : 0.0;
  const Point2 c{d.x - t * e.x, d.y - t * e.y};
  return norm2(c) <= r2 * (1 + 1e-9) + 1e-12 * (norm2(d) + l2);
}

// Whether S edge ab can matter for the nearest neighbour of vertex p (position P) given the bound
// r2 (a squared distance, nn2 or the walk's best so far), once segment_near(P, A, B, r2) held. It
// cannot when it has p as an endpoint, nor when its point nearest to p is certainly an endpoint z
// (dot product clearly negative: the rounding of a dot of differences is ~1e-16 of the terms)
// that is not nearer than r2 by the same formula as the result's (norm2(z - P) >= r2). Why: the
// edges that matter (the blocking edge of the constrained-Delaunay shortcut, the edge through
// which the segment from p to its nearest vertex q leaves or re-enters the mesh) meet that segment
// at a point x other than p with |px| <= |pq|; an edge through p and x would lie along pq and
// hold q or a nearer vertex inside it. If the edge's point nearest to p is an endpoint z, then
// |pz| <= |px| <= |pq|, so z is q itself (when x = q: then norm2(z - P) < r2 unless the bound
// already is q's distance) or a vertex nearer than q, which there is not.
inline bool may_matter(Index p, Point2 P, Index a, Index b, Point2 A, Point2 B, double r2) {
  if (a == p || b == p) return false;
  const Point2 e = B - A, pa = P - A, pb = P - B;
  const double da = dot(pa, e), db = -dot(pb, e);  // at a: (P - A).(B - A); at b: (P - B).(A - B)
  if (da < -1e-12 * (std::fabs(pa.x * e.x) + std::fabs(pa.y * e.y))) return norm2(A - P) < r2;
  if (db < -1e-12 * (std::fabs(pb.x * e.x) + std::fabs(pb.y * e.y))) return norm2(B - P) < r2;
  return true;
}

// The S edges in the cells of a uniform grid, cells about as long as the S edges on average (at
// most 2^26 cells): an occupancy bitmap, the number of occupied cells before each 64-bit word,
// and the edges of every occupied cell (compressed rows). Each edge is listed in every cell its
// bounding box (a little enlarged) meets; a query lists the edges of the cells its disk's box
// meets, so it finds every edge within the radius in a few cells. Not usable (ok() false) when
// long diagonal edges would be listed in too many cells: then the tree below.
class CellIndex {
 public:
  CellIndex(const mesh::MeshView& m, const std::vector<Index>& he) : m_(m) {
    if (he.empty() || he.size() >= 0xffffffffu) return;
    double x0 = kInf, y0 = kInf, x1 = -kInf, y1 = -kInf, total = 0;
    for (Index h : he) {
      const Point2 a = tail(h), b = head(h);
      for (const Point2 q : {a, b}) {
        x0 = std::min(x0, q.x);
        y0 = std::min(y0, q.y);
        x1 = std::max(x1, q.x);
        y1 = std::max(y1, q.y);
      }
      total += std::max(std::fabs(b.x - a.x), std::fabs(b.y - a.y));
    }
    if (!(x1 - x0 < kInf) || !(y1 - y0 < kInf) || !(total < kInf)) return;
    const double span = std::max({x1 - x0, y1 - y0, 1e-300});
    margin_ = 1e-9 * (span + std::max({std::fabs(x0), std::fabs(y0), std::fabs(x1), std::fabs(y1)}));
    double cell = std::max(total / static_cast<double>(he.size()), span / 65536.0);
    const double w = x1 - x0 + 4 * margin_, h = y1 - y0 + 4 * margin_;
    for (int guard = 0; guard < 64 && (w / cell + 1) * (h / cell + 1) > 67108864.0; ++guard) cell *= 1.5;
    if (!(cell > 0) || !std::isfinite(cell)) return;
    nx_ = static_cast<std::size_t>(w / cell) + 1;
    ny_ = static_cast<std::size_t>(h / cell) + 1;
    x0_ = x0 - 2 * margin_;
    y0_ = y0 - 2 * margin_;
    cell_ = cell;
    inv_cell_ = 1 / cell_;  // its rounding is far below the margins
    words_ = (nx_ + 63) / 64;
    bits_.assign(words_ * ny_, 0);
    // Every (edge, cell) pair, three times: mark, count, fill.
    std::size_t marked = 0;
    // The edges' endpoints in one compact array (a query reads them without the two scattered
    // loads through the triangles).
    he_ = he;
    seg_.resize(he.size());
    for (std::size_t k = 0; k < he.size(); ++k) seg_[k] = {tail(he[k]), head(he[k])};
    auto each = [&](auto&& visit) {
      for (std::uint32_t k = 0; k < seg_.size(); ++k) {
        const Point2 a = seg_[k].a, b = seg_[k].b;
        std::size_t i0, i1, j0, j1;
        range(std::min(a.x, b.x), std::max(a.x, b.x), x0_, nx_, i0, i1);
        range(std::min(a.y, b.y), std::max(a.y, b.y), y0_, ny_, j0, j1);
        for (std::size_t j = j0; j <= j1; ++j)
          for (std::size_t i = i0; i <= i1; ++i) visit(j * words_ * 64 + i, k);
      }
    };
    for (Index e : he) {  // the cost first: long diagonal edges would cover the grid
      const Point2 a = tail(e), b = head(e);
      std::size_t i0, i1, j0, j1;
      range(std::min(a.x, b.x), std::max(a.x, b.x), x0_, nx_, i0, i1);
      range(std::min(a.y, b.y), std::max(a.y, b.y), y0_, ny_, j0, j1);
      marked += (i1 - i0 + 1) * (j1 - j0 + 1);
      if (marked > 16 * he.size() + 4096) {
        bits_.clear();
        return;
      }
    }
    each([&](std::size_t bit, std::uint32_t) { bits_[bit / 64] |= std::uint64_t{1} << (bit % 64); });
    before_.resize(bits_.size() + 1);
    before_[0] = 0;
    for (std::size_t k = 0; k < bits_.size(); ++k) before_[k + 1] = before_[k] + popcount(bits_[k]);
    start_.assign(before_.back() + 1, 0);
    each([&](std::size_t bit, std::uint32_t) { ++start_[rank(bit) + 1]; });
    for (std::size_t c = 0; c + 1 < start_.size(); ++c) start_[c + 1] += start_[c];
    items_.resize(start_.back());
    std::vector<std::size_t> cursor(start_.begin(), start_.end() - 1);
    each([&](std::size_t bit, std::uint32_t k) { items_[cursor[rank(bit)]++] = k; });
  }
  bool ok() const { return !bits_.empty(); }
  // Calls f(h) for every listed half-edge h (some more than once) of the cells that the box of
  // the disk (p, sqrt(r2)) meets whose segment may come closer to p than sqrt(r2) (segment_near);
  // stops when f returns true, and returns whether it did.
  template <class F>
  bool for_each_near(Point2 p, double r2, F&& f) const {
    const double r = std::sqrt(r2) * (1 + 1e-6);
    if (!(r < kInf)) return scan_all(p, r2, f);
    const double limx = x0_ + cell_ * static_cast<double>(nx_), limy = y0_ + cell_ * static_cast<double>(ny_);
    if (p.x + r < x0_ || p.y + r < y0_ || p.x - r > limx || p.y - r > limy) return false;  // outside every edge's box
    std::size_t i0, i1, j0, j1;
    range(p.x - r, p.x + r, x0_, nx_, i0, i1);
    range(p.y - r, p.y + r, y0_, ny_, j0, j1);
    const std::size_t w0 = i0 / 64, w1 = i1 / 64;
    for (std::size_t j = j0; j <= j1; ++j)
      for (std::size_t w = w0; w <= w1; ++w) {
        std::uint64_t b = bits_[j * words_ + w];
        if (w == w0) b &= ~std::uint64_t{0} << (i0 % 64);
        if (w == w1) b &= ~std::uint64_t{0} >> (63 - i1 % 64);
        while (b) {
          const std::size_t bit = (j * words_ + w) * 64 + static_cast<std::size_t>(__builtin_ctzll(b));
          b &= b - 1;
          const std::size_t c = rank(bit);
          for (std::size_t k = start_[c]; k < start_[c + 1]; ++k) {
            const Seg& sg = seg_[items_[k]];
            if (segment_near(p, sg.a, sg.b, r2) && f(he_[items_[k]])) return true;
          }
        }
      }
    return false;
  }

 private:
  Point2 tail(Index h) const { return m_.vertices[m_.triangles[h / 3][h % 3]]; }
  Point2 head(Index h) const { return m_.vertices[m_.triangles[h / 3][(h % 3 + 1) % 3]]; }
  static std::size_t popcount(std::uint64_t x) {  // no popcnt instruction in the baseline ISA
    x = x - ((x >> 1) & 0x5555555555555555ULL);
    x = (x & 0x3333333333333333ULL) + ((x >> 2) & 0x3333333333333333ULL);
    x = (x + (x >> 4)) & 0x0f0f0f0f0f0f0f0fULL;
    return static_cast<std::size_t>((x * 0x0101010101010101ULL) >> 56);
  }
  std::size_t rank(std::size_t bit) const {  // occupied cells before this one
    return before_[bit / 64] + popcount(bits_[bit / 64] & ((std::uint64_t{1} << (bit % 64)) - 1));
  }
  template <class F>
  bool scan_all(Point2 p, double r2, F& f) const {
    for (std::size_t k = 0; k < seg_.size(); ++k)
      if (segment_near(p, seg_[k].a, seg_[k].b, r2) && f(he_[k])) return true;
    return false;
  }
  // The cells [k0, k1] that [lo, hi] (enlarged by the margin) meets along one axis of n cells.
  void range(double lo, double hi, double origin, std::size_t n, std::size_t& k0, std::size_t& k1) const {
    auto cell = [&](double v) {  // truncation is the floor for c > 0 (no libm call)
      const double c = (v - origin) * inv_cell_;
      return !(c > 0) ? std::size_t{0} : c >= static_cast<double>(n - 1) ? n - 1 : static_cast<std::size_t>(c);
    };
    k0 = cell(lo - margin_);
    k1 = cell(hi + margin_);
  }
  const mesh::MeshView& m_;
  std::size_t nx_ = 0, ny_ = 0, words_ = 0;
  double x0_ = 0, y0_ = 0, cell_ = 0, inv_cell_ = 0, margin_ = 0;
  std::vector<std::uint64_t> bits_;
  std::vector<std::size_t> before_, start_;
  struct Seg {
    Point2 a, b;
  };
  std::vector<Seg> seg_;             // per listed edge: tail, head
  std::vector<Index> he_;            // per listed edge: its half-edge
  std::vector<std::uint32_t> items_;  // per occupied cell (compressed rows): listed edges
};

// Half-edges (the boundary and the constrained edges) in a static bounding-box tree: ranges of
// the array sorted by midpoint (median splits, alternating axis), node boxes in heap order.
class EdgeIndex {
 public:
  EdgeIndex(const mesh::MeshView& m, const std::vector<Index>& nb, std::vector<Index> he)
      : m_(m), nb_(nb), he_(std::move(he)), cells_(m, he_) {
    if (!he_.empty() && !cells_.ok()) build(0, 0, he_.size(), 0);  // the tree only when the cells cannot serve
  }
  // Calls f(h) for every indexed half-edge h whose segment may come closer to p than sqrt(r2)
  // (some more than once); stops when f returns true, and returns whether it did.
  template <class F>
  bool for_each_near(Point2 p, double r2, F&& f) const {
    if (cells_.ok()) return cells_.for_each_near(p, r2, f);
    return !he_.empty() && query(0, 0, he_.size(), p, r2, f);
  }
  Index tail_id(Index h) const { return m_.triangles[h / 3][h % 3]; }
  Index head_id(Index h) const { return m_.triangles[h / 3][(h % 3 + 1) % 3]; }
  // Whether h can matter for vertex p: not a boundary edge of one of p's own triangles (the
  // segment from p to a vertex beyond it would re-enter the mesh through another boundary edge,
  // which cannot be one of p's: each of p's triangles spans its own angle around p), and
  // may_matter.
  bool matters(Index h, Index p, Point2 P, double r2) const {
    if (nb_[h] == kNoId && m_.triangles[h / 3][(h % 3 + 2) % 3] == p) return false;
    const Index a = tail_id(h), b = head_id(h);
    return may_matter(p, P, a, b, m_.vertices[a], m_.vertices[b], r2);
  }

 private:
  struct Box {
    double x0, y0, x1, y1;
  };
  static constexpr std::size_t kLeaf = 8;
  Point2 tail(Index h) const { return m_.vertices[m_.triangles[h / 3][h % 3]]; }
  Point2 head(Index h) const { return m_.vertices[m_.triangles[h / 3][(h % 3 + 1) % 3]]; }
  Box build(std::size_t node, std::size_t lo, std::size_t hi, int axis) {
    if (box_.size() <= node) box_.resize(node + 1);
    Box b{kInf, kInf, -kInf, -kInf};
    if (hi - lo <= kLeaf) {
      for (std::size_t i = lo; i < hi; ++i)
        for (const Point2 q : {tail(he_[i]), head(he_[i])})
          b = {std::min(b.x0, q.x), std::min(b.y0, q.y), std::max(b.x1, q.x), std::max(b.y1, q.y)};
    } else {
      const std::size_t mid = lo + (hi - lo) / 2;
      auto key = [&](Index h) {
        const Point2 a = tail(h), c = head(h);
        return axis == 0 ? a.x + c.x : a.y + c.y;
      };
      std::nth_element(he_.begin() + static_cast<std::ptrdiff_t>(lo), he_.begin() + static_cast<std::ptrdiff_t>(mid),
                       he_.begin() + static_cast<std::ptrdiff_t>(hi),
                       [&](Index x, Index y) { return key(x) < key(y) || (key(x) == key(y) && x < y); });
      const Box l = build(2 * node + 1, lo, mid, 1 - axis), r = build(2 * node + 2, mid, hi, 1 - axis);
      b = {std::min(l.x0, r.x0), std::min(l.y0, r.y0), std::max(l.x1, r.x1), std::max(l.y1, r.y1)};
    }
    box_[node] = b;
    return b;
  }
  template <class F>
  bool query(std::size_t node, std::size_t lo, std::size_t hi, Point2 p, double r2, F& f) const {
    const Box& b = box_[node];
    const double dx = std::max({b.x0 - p.x, 0.0, p.x - b.x1}), dy = std::max({b.y0 - p.y, 0.0, p.y - b.y1});
    if (dx * dx + dy * dy > r2 * (1 + 1e-9)) return false;  // the whole box is farther (slack as segment_near)
    if (hi - lo <= kLeaf) {
      for (std::size_t i = lo; i < hi; ++i)
        if (segment_near(p, tail(he_[i]), head(he_[i]), r2) && f(he_[i])) return true;
      return false;
    }
    const std::size_t mid = lo + (hi - lo) / 2;
    return query(2 * node + 1, lo, mid, p, r2, f) || query(2 * node + 2, mid, hi, p, r2, f);
  }
  const mesh::MeshView& m_;
  const std::vector<Index>& nb_;
  std::vector<Index> he_;
  CellIndex cells_;
  std::vector<Box> box_;
};

// The walk for one vertex, with its scratch lists (one Walker per thread).
//
// Why it is exact: let q be the vertex nearest to p and r = |pq| (the final best). The open
// segment pq holds no vertex (it would be nearer). Follow pq backwards from q: it runs through
// a chain of triangles, consecutive ones sharing an edge that pq crosses at a point nearer to p
// than r, until it reaches p's own triangles or leaves the mesh through a boundary edge at such
// a point. The walk crosses every edge that comes nearer than the best so far (never below r),
// so it follows the chain from p's triangles; when the chain starts at a boundary edge instead,
// that edge is near p, the walk therefore met the boundary near p (p's own triangles are bounded
// by it or by edges the walk crossed), and every boundary edge that near is a starting point.
class Walker {
 public:
  Walker(const mesh::MeshView& m, const std::vector<Index>& nb, const EdgeIndex& bi) : m_(m), nb_(nb), bi_(bi) {}
  double nearest_sq(Index p, Index t0, double best) {
    if (!(best > 0)) return best;  // a duplicate point: nothing is nearer than 0
    const Point2 P = m_.vertices[p];
    seen_.clear();
    todo_.clear();
    visit(t0);
    bool boundary = false, seeded = false;
    while (true) {
      while (!todo_.empty()) {
        const Index t = todo_.back();
        todo_.pop_back();
        const auto& tr = m_.triangles[t];
        for (int k = 0; k < 3; ++k)
          if (tr[k] != p) best = std::min(best, norm2(m_.vertices[tr[k]] - P));
        for (int k = 0; k < 3; ++k) {
          const Index a = tr[k], b = tr[k == 2 ? 0 : k + 1];
          const Index n = nb_[3 * t + k];
          if (n != kNoId && seen(n / 3)) continue;
          if (a != p && b != p && !segment_near(P, m_.vertices[a], m_.vertices[b], best)) continue;
          if (n == kNoId) boundary = true;
          else visit(n / 3);
        }
      }
      if (!boundary || seeded) break;
      seeded = true;  // the region near p may continue beyond the boundary: start from every near boundary edge
      bi_.for_each_near(P, best, [&](Index h) {
        if (!seen(h / 3) && bi_.matters(h, p, P, best)) visit(h / 3);
        return false;
      });
    }
    return best;
  }

 private:
  // A short list while the walk is small (the usual dozen triangles), a hash set beyond.
  bool seen(Index t) const {
    if (seen_.size() <= kShort) return std::find(seen_.begin(), seen_.end(), t) != seen_.end();
    return many_.count(t) != 0;
  }
  void visit(Index t) {
    seen_.push_back(t);
    if (seen_.size() == kShort + 1) many_ = std::unordered_set<Index>(seen_.begin(), seen_.end());
    else if (seen_.size() > kShort + 1) many_.insert(t);
    todo_.push_back(t);
  }
  static constexpr std::size_t kShort = 48;
  std::unordered_set<Index> many_;
  const mesh::MeshView& m_;
  const std::vector<Index>& nb_;
  const EdgeIndex& bi_;
  std::vector<Index> seen_, todo_;
};

}  // namespace

namespace {

// The half-edge a -> b, else b -> a, found by rotating around a (kNoId when a's triangles
// reachable by rotation do not have it, e.g. at a vertex where two fans touch).
Index find_half_edge(const mesh::MeshView& m, const std::vector<Index>& nb, Index t0, Index a, Index b) {
  const auto& tr0 = m.triangles[t0];
  const Index start = 3 * t0 + (tr0[0] == a ? 0 : tr0[1] == a ? 1 : 2);
  auto prev = [](Index h) { return h % 3 == 0 ? h + 2 : h - 1; };
  auto next = [](Index h) { return h % 3 == 2 ? h - 2 : h + 1; };
  auto head = [&](Index h) { return m.triangles[h / 3][next(h) % 3]; };
  auto tail = [&](Index h) { return m.triangles[h / 3][h % 3]; };
  for (int dir = 0; dir < 2; ++dir) {
    Index h = start;
    for (std::size_t guard = 0; guard < nb.size() + 1; ++guard) {  // at most every half-edge once
      if (head(h) == b) return h;
      if (tail(prev(h)) == b) return prev(h);
      const Index g = dir == 0 ? nb[prev(h)] : nb[h];
      if (g == kNoId) break;
      h = dir == 0 ? g : next(g);
      if (h == start) return kNoId;  // full turn
    }
  }
  return kNoId;
}

}  // namespace

namespace {

}  // namespace

struct MeshNearestNeighbours::Impl {
  const mesh::MeshView& m;
  const std::vector<Index>& nb;
  const LargeArray<Index>& tri_of_vertex;
  std::vector<double> nn;
  bool usable = false, certify = false;
  std::unique_ptr<EdgeIndex> si;
  Impl(const mesh::MeshView& mm, const std::vector<Index>& nbb, const LargeArray<Index>& tov)
      : m(mm), nb(nbb), tri_of_vertex(tov) {}
};

MeshNearestNeighbours::MeshNearestNeighbours(const mesh::MeshView& m, const std::vector<Index>& nb,
                                             MeshWalkPrep& prep) {
  const std::size_t nv = m.vertices.size(), nt = m.triangles.size();
  impl_ = std::make_unique<Impl>(m, nb, prep.tri_of_vertex);
  const LargeArray<Index>& tri_of_vertex = prep.tri_of_vertex;
  if (nv < 2 || nb.size() != 3 * nt || prep.nn2.size() != nv || tri_of_vertex.size() != nv) return;
  // One triangle of every vertex (prep.nn2 is left intact when the walk cannot be used).
  if (std::find(tri_of_vertex.begin(), tri_of_vertex.end(), kNoId) != tri_of_vertex.end()) return;
  impl_->nn = std::move(prep.nn2).take();  // upper bounds from the mesh edges
  impl_->usable = true;

  // S: the boundary and the constrained edges (m.edges), as half-edges, sorted.
  std::vector<Index> s_edges;
  bool certify = prep.ccw;  // and every edge of m.edges found (else the shortcut below is off)
  for (std::size_t h = 0; h < 3 * nt; ++h)
    if (nb[h] == kNoId) s_edges.push_back(static_cast<Index>(h));
  for (const auto& e : m.edges) {
    if (e.a >= nv || e.b >= nv) { certify = false; continue; }
    const Index h = find_half_edge(m, nb, tri_of_vertex[e.a], e.a, e.b);
    if (h == kNoId) { certify = false; continue; }
    s_edges.push_back(h);
    if (nb[h] != kNoId) s_edges.push_back(nb[h]);
  }
  std::sort(s_edges.begin(), s_edges.end());
  s_edges.erase(std::unique(s_edges.begin(), s_edges.end()), s_edges.end());
  // The shortcut needs a constrained Delaunay triangulation with respect to S: every triangle
  // counter-clockwise and every other interior edge locally Delaunay (which implies it, Lawson).
  // Why it then holds: let p have no S edge nearer than d, its nearest mesh neighbour, that
  // matters (may_matter: p's own S edges and those whose nearest point is an endpoint not nearer
  // than d do not). Let v be the nearest vertex, |pv| < d. If the direction of v from p lies in
  // one of p's triangles puw, v lies beyond uw, in the part of the disk D(p, d) beyond uw, which
  // lies inside the circumcircle of puw (that circle passes through p, and u, w are outside D);
  // in a constrained Delaunay triangulation v must then be hidden from puw by an S edge, which
  // crosses the segment pv at a point x other than p and v. Otherwise (p on the boundary, v seen
  // across the exterior) pv re-enters the mesh through a boundary edge at a point x other than p
  // (possibly v). Either edge meets pv at x with |px| <= |pv|, so it matters (see may_matter).
  // So nn(p) = d.
  for (Index h : prep.not_delaunay)
    if (!std::binary_search(s_edges.begin(), s_edges.end(), h)) certify = false;
  impl_->certify = certify;
  impl_->si = std::make_unique<EdgeIndex>(m, nb, std::move(s_edges));
}

MeshNearestNeighbours::~MeshNearestNeighbours() = default;

bool MeshNearestNeighbours::usable() const { return impl_->usable; }

void MeshNearestNeighbours::search(std::size_t lo, std::size_t hi) {
  Impl& s = *impl_;
  if (!s.usable) return;
  Walker w(s.m, s.nb, *s.si);
  for (std::size_t v = lo; v < hi && v < s.nn.size(); ++v) {
    const Point2 p = s.m.vertices[v];
    const Index pv = static_cast<Index>(v);
    const double r2 = s.nn[v];
    if (s.certify && !s.si->for_each_near(p, r2, [&](Index h) { return s.si->matters(h, pv, p, r2); }))
      continue;  // exact: no S edge within nn[v] that matters (see the constructor)
    s.nn[v] = w.nearest_sq(static_cast<Index>(v), s.tri_of_vertex[v], s.nn[v]);
  }
}

std::vector<double> MeshNearestNeighbours::take() { return std::move(impl_->nn); }

std::vector<double> mesh_nearest_neighbour_sq(const mesh::MeshView& m, const std::vector<Index>& nb, unsigned threads,
                                              MeshWalkPrep* prep) {
  const std::size_t nv = m.vertices.size(), nt = m.triangles.size();
  if (nv < 2) return std::vector<double>(nv, kInf);
  if (nb.size() != 3 * nt) return {};
  for (const auto& tr : m.triangles)
    if (tr[0] >= nv || tr[1] >= nv || tr[2] >= nv) return {};
  MeshWalkPrep own;
  if (!prep) {
    prep = &own;
    compute_orthogonality(m, nb, prep);
  }
  MeshNearestNeighbours s(m, nb, *prep);
  if (!s.usable()) return {};
  // Vertices in two fixed halves (results per vertex do not depend on the split).
  if (threads > 1 && nv >= 4096) {
    run_beside([&] { s.search(nv / 2, nv); }, [&] { s.search(0, nv / 2); });
  } else {
    s.search(0, nv);
  }
  return s.take();
}

}  // namespace fdr::quality
