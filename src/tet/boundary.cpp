#include "tet/boundary.hpp"
#include <algorithm>
#include "base/error.hpp"

namespace fdr::tet {
namespace {

std::size_t mix(std::size_t h, std::uint64_t x) {
  x *= 0x9e3779b97f4a7c15ull;
  return (h ^ (x >> 29) ^ x) * 0xbf58476d1ce4e5b9ull;
}

}  // namespace

std::size_t Boundary::SegHash::operator()(const SegKey& k) const { return mix(mix(1, k.a), k.b); }
std::size_t Boundary::DirHash::operator()(const DirKey& k) const { return mix(mix(mix(3, k.f), k.a), k.b); }

Boundary::SegKey Boundary::seg_key(VertexId a, VertexId b) { return a < b ? SegKey{a, b} : SegKey{b, a}; }

Boundary::Boundary(const Delaunay3& dt, const plc::Plc& plc, const plc::FacetTriangulation& ft,
                   std::span<const VertexId> vid)
    : dt_(dt), plc_(plc), ft_(ft) {
  for (std::uint32_t o = 0; o < ft.subsegments.size(); ++o)
    add_segment(vid[ft.subsegments[o].a], vid[ft.subsegments[o].b], o);
  for (std::uint32_t f = 0; f < ft.triangles.size(); ++f)
    for (const auto& t : ft.triangles[f]) add_tri({vid[t[0]], vid[t[1]], vid[t[2]]}, f);
}

void Boundary::grow(VertexId v) {
  if (v >= seg_nbrs_.size()) {
    const std::size_t n = std::max<std::size_t>(v + 1, seg_nbrs_.size() * 3 / 2);
    seg_nbrs_.resize(n);
    vtris_.resize(n);
  }
}

bool Boundary::is_subsegment(VertexId a, VertexId b) const {
  // The shorter of the two ends' neighbour lists (a few entries, in cache) answers without the
  // hash map, whose look-up costs a miss or two: facet cavities and the boundary sweeps ask this
  // for every edge they meet, and on a terrain every TIN edge is a subsegment.
  const std::vector<VertexId>& na = segment_neighbours(a);
  const std::vector<VertexId>& nb = segment_neighbours(b);
  const bool a_shorter = na.size() <= nb.size();
  const std::vector<VertexId>& l = a_shorter ? na : nb;
  const VertexId other = a_shorter ? b : a;
  return std::find(l.begin(), l.end(), other) != l.end();
}

std::uint32_t Boundary::segment_origin(VertexId a, VertexId b) const {
  const auto it = segs_.find(seg_key(a, b));
  return it == segs_.end() ? UINT32_MAX : it->second;
}

const std::vector<VertexId>& Boundary::segment_neighbours(VertexId v) const {
  static const std::vector<VertexId> none;
  return v < seg_nbrs_.size() ? seg_nbrs_[v] : none;
}

void Boundary::add_segment(VertexId a, VertexId b, std::uint32_t origin) {
  grow(std::max(a, b));
  segs_[seg_key(a, b)] = origin;
  seg_nbrs_[a].push_back(b);
  seg_nbrs_[b].push_back(a);
}

void Boundary::remove_segment(VertexId a, VertexId b) {
  segs_.erase(seg_key(a, b));
  auto drop = [](std::vector<VertexId>& v, VertexId x) { v.erase(std::find(v.begin(), v.end(), x)); };
  drop(seg_nbrs_[a], b);
  drop(seg_nbrs_[b], a);
}

void Boundary::split_segment(VertexId a, VertexId b, VertexId v) {
  const std::uint32_t o = segment_origin(a, b);
  if (o == UINT32_MAX) throw Error(ExitCode::kInternal, "tet::Boundary: split of a vertex pair that is no subsegment");
  // The facet triangles on ab, found before ab stops being a constraint.
  std::vector<std::uint32_t> seeds;
  for (std::uint32_t f : ft_.subsegments[o].facets) {
    for (std::uint32_t t : {across(f, a, b), across(f, b, a)})
      if (t != UINT32_MAX) seeds.push_back(t);
  }
  remove_segment(a, b);
  add_segment(a, v, o);
  add_segment(v, b, o);
  // Each facet on ab gets v, with both its triangles on ab (one on a facet's outer edge) forced
  // into the cavity; a triangle of another facet is never in the same cavity.
  for (std::uint32_t f : ft_.subsegments[o].facets) {
    std::vector<std::uint32_t> cavity;
    for (std::uint32_t t : seeds)
      if (tris_[t].facet == f) cavity.push_back(t);
    if (!cavity.empty()) {
      const std::size_t forced = cavity.size();
      insert_with_cavity(std::move(cavity), forced, v, {a, b});
    }
  }
}

std::uint32_t Boundary::subfacet(VertexId a, VertexId b, VertexId c) const {
  // The shortest of the corners' lists is scanned: a few triangles in cache, where a hash map of
  // all subfacets cost a miss or two per query (and the tetrahedra's faces are queried by the
  // million near layers whose vertices all lie on facets).
  const std::vector<std::uint32_t>* l = &subfacets_at(a);
  for (VertexId u : {b, c}) {
    const std::vector<std::uint32_t>& m = subfacets_at(u);
    if (m.size() < l->size()) l = &m;
  }
  for (std::uint32_t t : *l) {
    const auto& v = tris_[t].v;
    const auto has = [&](VertexId x) { return v[0] == x || v[1] == x || v[2] == x; };
    if (has(a) && has(b) && has(c)) return t;
  }
  return UINT32_MAX;
}

const std::vector<std::uint32_t>& Boundary::subfacets_at(VertexId v) const {
  static const std::vector<std::uint32_t> none;
  return v < vtris_.size() ? vtris_[v] : none;
}

bool Boundary::on_facet(VertexId v, std::uint32_t f) const {
  for (std::uint32_t t : subfacets_at(v))
    if (tris_[t].facet == f) return true;
  return false;
}

std::uint32_t Boundary::add_tri(std::array<VertexId, 3> v, std::uint32_t f) {
  std::uint32_t id;
  if (!free_tris_.empty()) {
    id = free_tris_.back();
    free_tris_.pop_back();
    tris_[id] = {v, f, true};
  } else {
    id = static_cast<std::uint32_t>(tris_.size());
    tris_.push_back({v, f, true});
  }
  for (int k = 0; k < 3; ++k) {
    dir_[{f, v[k], v[(k + 1) % 3]}] = id;
    grow(v[k]);
    vtris_[v[k]].push_back(id);
  }
  return id;
}

void Boundary::kill_tri(std::uint32_t t) {
  SubfacetTri& s = tris_[t];
  for (int k = 0; k < 3; ++k) {
    dir_.erase({s.facet, s.v[k], s.v[(k + 1) % 3]});
    auto& vt = vtris_[s.v[k]];
    vt.erase(std::find(vt.begin(), vt.end(), t));
  }
  s.alive = false;
  free_tris_.push_back(t);
}

std::uint32_t Boundary::across(std::uint32_t f, VertexId a, VertexId b) const {
  const auto it = dir_.find({f, b, a});
  return it == dir_.end() ? UINT32_MAX : it->second;
}

}  // namespace fdr::tet
