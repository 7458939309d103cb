// Cells cut out by the facets: sides joined around edges and along rays, all decided exactly.
#include "plc/cells.hpp"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <numeric>

#include "base/error.hpp"
#include "plc/facet_frame.hpp"
#include "predicates/predicates3d.hpp"

namespace fdr::plc {

using predicates::orient3d;

namespace {

using FT = CGAL::Exact_predicates_exact_constructions_kernel::FT;
using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using TriangleList = std::vector<Epick::Triangle_3>;
using Primitive = CGAL::AABB_triangle_primitive<Epick, TriangleList::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Epick, Primitive>>;

}  // namespace

struct SurfaceCells::Crossing {
  FT t;             // where along p r, 0 at p, exact
  std::size_t tri;
  bool p_positive;  // whether p lies on the triangle's positive side
};

struct SurfaceCells::RayIndex {
  TriangleList tris;
  Tree tree;
};

namespace {

Epick::Point_3 cg(Point3 p) { return {p.x, p.y, p.z}; }

// det[b - a, c - a, x - a] exactly.
FT volume(Point3 a, Point3 b, Point3 c, Point3 x) {
  const FT bx = FT(b.x) - a.x, by = FT(b.y) - a.y, bz = FT(b.z) - a.z;
  const FT cx = FT(c.x) - a.x, cy = FT(c.y) - a.y, cz = FT(c.z) - a.z;
  const FT xx = FT(x.x) - a.x, xy = FT(x.y) - a.y, xz = FT(x.z) - a.z;
  return bx * (cy * xz - cz * xy) - by * (cx * xz - cz * xx) + bz * (cx * xy - cy * xx);
}

// splitmix64: a fixed sequence of directions, the same on every machine.
double unit_from(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * (2.0 / 9007199254740992.0) - 1.0;  // [-1, 1)
}

}  // namespace

SurfaceCells::SurfaceCells(const Plc& plc, const FacetTriangulation& ft) : plc_(plc) {
  for (std::size_t f = 0; f < ft.triangles.size(); ++f)
    for (const Triangle& t : ft.triangles[f]) {
      tris_.push_back(t);
      facet_of_.push_back(static_cast<std::uint32_t>(f));
      for (VertexId v : t) box_.add(plc.points[v]);
    }
  for (std::size_t k = 0; k < tris_.size(); ++k)
    for (int i = 0; i < 3; ++i) {
      const VertexId a = tris_[k][i], b = tris_[k][(i + 1) % 3];
      edge_uses_.push_back({a < b ? Edge{a, b} : Edge{b, a}, k});
    }
  std::sort(edge_uses_.begin(), edge_uses_.end());
  rays_ = std::make_unique<RayIndex>();
  for (const Triangle& t : tris_)
    rays_->tris.emplace_back(cg(plc.points[t[0]]), cg(plc.points[t[1]]), cg(plc.points[t[2]]));
  rays_->tree.insert(rays_->tris.cbegin(), rays_->tris.cend());
  rays_->tree.build();
  parent_.resize(2 * tris_.size() + 1);
  std::iota(parent_.begin(), parent_.end(), std::size_t{0});
  if (!box_.empty()) reach_ = 2 * dist(box_.lo, box_.hi) + 1;
  join_around_edges();
  place_pieces();
}

SurfaceCells::~SurfaceCells() = default;

std::size_t SurfaceCells::find(std::size_t s) {
  while (parent_[s] != s) s = parent_[s] = parent_[parent_[s]];
  return s;
}

void SurfaceCells::join(std::size_t a, std::size_t b) {
  a = find(a), b = find(b);
  if (a != b) parent_[std::max(a, b)] = std::min(a, b);
}

std::size_t SurfaceCells::side_class(std::size_t k, bool positive) { return find(2 * k + (positive ? 1 : 0)); }

std::size_t SurfaceCells::unbounded_class() { return find(parent_.size() - 1); }

void SurfaceCells::join_around_edges() {
  const auto& P = plc_.points;
  std::vector<std::size_t> ks;
  for (std::size_t r = 0; r < edge_uses_.size();) {
    const Edge e = edge_uses_[r].first;
    ks.clear();
    for (; r < edge_uses_.size() && edge_uses_[r].first == e; ++r) ks.push_back(edge_uses_[r].second);
    const Point3 u = P[e[0]], v = P[e[1]];
    auto apex = [&](std::size_t k) {
      for (VertexId w : tris_[k])
        if (w != e[0] && w != e[1]) return w;
      return tris_[k][0];
    };
    // +1 when (u, v, apex) runs as the triangle's own corners do (a rotation of them).
    auto parity = [&](std::size_t k) {
      int i = 0;
      while (tris_[k][i] != e[0]) ++i;
      return tris_[k][(i + 1) % 3] == e[1] ? 1 : -1;
    };
    const Point3 w0 = P[apex(ks[0])];
    // Angle sectors about the axis u -> v from the first apex: 0 at it, 1 in (0, pi), 2 at pi,
    // 3 in (pi, 2 pi); orient3d(u, v, w0, w) > 0 for w in sector 1.
    auto sector = [&](std::size_t k) {
      const Point3 w = P[apex(k)];
      const int s = orient3d(u, v, w0, w);
      if (s > 0) return 1;
      if (s < 0) return 3;
      return side_in_plane(u, v, w0, w) > 0 ? 0 : 2;
    };
    std::sort(ks.begin(), ks.end(), [&](std::size_t a, std::size_t b) {
      const int sa = sector(a), sb = sector(b);
      if (sa != sb) return sa < sb;
      if (sa == 0 || sa == 2) return a < b;
      return orient3d(u, v, P[apex(a)], P[apex(b)]) > 0;
    });
    for (std::size_t i = 0; i < ks.size(); ++i) {
      const std::size_t a = ks[i], b = ks[(i + 1) % ks.size()];
      // The wedge from a to b: a's side towards increasing angle, b's side towards decreasing.
      join(2 * a + (parity(a) > 0 ? 1 : 0), 2 * b + (parity(b) > 0 ? 0 : 1));
    }
  }
}

Point3 SurfaceCells::far_point(Point3 through, std::uint64_t attempt, double sign) const {
  std::uint64_t state = attempt * 7919 + 17;
  Point3 d{unit_from(state), unit_from(state), unit_from(state)};
  const double len = std::sqrt(norm2(d));
  d = (1 / (len > 0 ? len : 1)) * d;
  if (!(len > 0.1)) d = {0.6, 0.48, 0.64};
  double r = reach_ + dist(through, box_.center());
  Point3 q = through + (sign * r) * d;
  while (box_.contains(q)) r *= 2, q = through + (sign * r) * d;
  return q;
}

bool SurfaceCells::crossings(Point3 p, Point3 r, std::vector<Crossing>& out, const std::string& what) const {
  out.clear();
  const auto& P = plc_.points;
  // Candidates: the triangles the closed segment meets at all (exact), in index order.
  std::vector<Primitive::Id> hits;
  rays_->tree.all_intersected_primitives(Epick::Segment_3(cg(p), cg(r)), std::back_inserter(hits));
  std::vector<std::size_t> ks;
  for (const auto& h : hits) ks.push_back(static_cast<std::size_t>(h - rays_->tris.cbegin()));
  std::sort(ks.begin(), ks.end());
  for (std::size_t k : ks) {
    const Point3 a = P[tris_[k][0]], b = P[tris_[k][1]], c = P[tris_[k][2]];
    const int op = orient3d(a, b, c, p), orr = orient3d(a, b, c, r);
    if (op == 0 && CGAL::do_intersect(cg(p), Epick::Triangle_3(cg(a), cg(b), cg(c))))
      throw Error(ExitCode::kInvalidGeometry, what + " " + point_text(p) + " lies on facet " +
                                                  std::to_string(facet_of_[k]) + " (marker " +
                                                  std::to_string(plc_.facets[facet_of_[k]].marker) + ")");
    if (op == 0 && orr == 0) {
      if (CGAL::do_intersect(Epick::Segment_3(cg(p), cg(r)), Epick::Triangle_3(cg(a), cg(b), cg(c)))) return false;
      continue;
    }
    if (op == 0 || orr == 0 || op == orr) continue;  // touches the plane at an end only, or stays on one side
    const int e1 = orient3d(p, r, a, b), e2 = orient3d(p, r, b, c), e3 = orient3d(p, r, c, a);
    const bool pos = e1 >= 0 && e2 >= 0 && e3 >= 0, neg = e1 <= 0 && e2 <= 0 && e3 <= 0;
    if (!pos && !neg) continue;                          // passes beside the triangle
    if (e1 == 0 || e2 == 0 || e3 == 0) return false;     // through an edge or a vertex
    const FT vp = volume(a, b, c, p), vr = volume(a, b, c, r);
    out.push_back({vp / (vp - vr), k, op > 0});
  }
  std::sort(out.begin(), out.end(), [](const Crossing& x, const Crossing& y) { return x.t < y.t; });
  return true;
}

std::size_t SurfaceCells::walk(const std::vector<Crossing>& cs, bool start_unbounded) {
  const std::size_t unb = parent_.size() - 1;
  if (cs.empty()) return find(unb);
  auto near_side = [&](const Crossing& c) { return 2 * c.tri + (c.p_positive ? 1 : 0); };
  auto far_side = [&](const Crossing& c) { return 2 * c.tri + (c.p_positive ? 0 : 1); };
  for (std::size_t i = 0; i + 1 < cs.size(); ++i) join(far_side(cs[i]), near_side(cs[i + 1]));
  join(far_side(cs.back()), unb);
  if (start_unbounded) join(near_side(cs.front()), unb);
  return find(near_side(cs.front()));
}

void SurfaceCells::place_pieces() {
  // Pieces: triangles joined through shared edges.
  std::vector<std::size_t> piece(tris_.size());
  std::iota(piece.begin(), piece.end(), std::size_t{0});
  auto root = [&](std::size_t k) {
    while (piece[k] != k) k = piece[k] = piece[piece[k]];
    return k;
  };
  for (std::size_t r = 1; r < edge_uses_.size(); ++r) {
    if (edge_uses_[r].first != edge_uses_[r - 1].first) continue;
    const std::size_t x = root(edge_uses_[r].second), y = root(edge_uses_[r - 1].second);
    if (x != y) piece[std::max(x, y)] = std::min(x, y);
  }
  const auto& P = plc_.points;
  std::vector<Crossing> cs;
  std::vector<char> placed(tris_.size(), 0);
  for (std::size_t k = 0; k < tris_.size(); ++k) {
    const std::size_t pc = root(k);
    if (placed[pc]) continue;
    // A segment between two far points through the centroid of a triangle of this piece.
    bool done = false;
    for (std::size_t k2 = k; k2 < tris_.size() && !done; ++k2) {
      if (root(k2) != pc) continue;
      const Triangle& t = tris_[k2];
      const Point3 c = (1.0 / 3.0) * (P[t[0]] + P[t[1]] + P[t[2]]);
      for (std::uint64_t attempt = 0; attempt < 16 && !done; ++attempt) {
        const Point3 p = far_point(c, attempt, 1), r = far_point(c, attempt, -1);
        if (!crossings(p, r, cs, "a probe point")) continue;
        if (std::none_of(cs.begin(), cs.end(), [&](const Crossing& x) { return root(x.tri) == pc; })) continue;
        walk(cs, true);
        done = true;
      }
    }
    if (!done)
      throw Error(ExitCode::kInternal, facet_label(plc_, facet_of_[k]) + ": no ray found to place its surface");
    placed[pc] = 1;
  }
}

bool SurfaceCells::outside(Point3 p, const std::string& what) {
  std::vector<Crossing> cs;
  for (std::uint64_t attempt = 0; attempt < 64; ++attempt) {
    if (!crossings(p, far_point(p, attempt, 1), cs, what)) continue;
    return walk(cs, false) == unbounded_class();
  }
  throw Error(ExitCode::kInternal, what + " " + point_text(p) + ": no ray found to locate it");
}

void SurfaceCells::check_closed() {
  const std::string src = plc_.source.empty() ? std::string("input") : plc_.source;
  if (tris_.empty()) throw Error(ExitCode::kInvalidGeometry, src + ": no facets, so no volume to mesh");
  const std::size_t unb = unbounded_class();
  const auto& P = plc_.points;
  for (std::size_t r = 0; r < edge_uses_.size(); ++r) {
    const auto& [e, k] = edge_uses_[r];
    const bool single = (r == 0 || edge_uses_[r - 1].first != e) &&
                        (r + 1 == edge_uses_.size() || edge_uses_[r + 1].first != e);
    if (!single || side_class(k, true) != unb) continue;
    throw Error(ExitCode::kInvalidGeometry,
                facet_label(plc_, facet_of_[k]) + ": the boundary is not closed: edge " + std::to_string(e[0]) +
                    "-" + std::to_string(e[1]) + " " + point_text(P[e[0]]) + "-" + point_text(P[e[1]]) +
                    " belongs to this facet only and has the outside on both sides");
  }
  for (std::size_t k = 0; k < tris_.size(); ++k)
    if (side_class(k, true) == unb && side_class(k, false) == unb)
      throw Error(ExitCode::kInvalidGeometry, facet_label(plc_, facet_of_[k]) +
                                                  " lies outside every volume (outside on both sides), near " +
                                                  point_text(P[tris_[k][0]]));
}

void SurfaceCells::check_volume_points() {
  const std::string src = plc_.source.empty() ? std::string("input") : plc_.source;
  for (std::size_t h = 0; h < plc_.holes.size(); ++h) {
    const std::string what = src + ": volume hole point " + std::to_string(h);
    if (outside(plc_.holes[h], what))
      throw Error(ExitCode::kInvalidGeometry, what + " " + point_text(plc_.holes[h]) + " lies outside the domain");
  }
  for (std::size_t r = 0; r < plc_.regions.size(); ++r) {
    const std::string what = src + ": region point " + std::to_string(r);
    if (outside(plc_.regions[r].point, what))
      throw Error(ExitCode::kInvalidGeometry,
                  what + " " + point_text(plc_.regions[r].point) + " lies outside the domain");
  }
}

}  // namespace fdr::plc
