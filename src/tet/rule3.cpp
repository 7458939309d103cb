// Refiner3's regions and rule 3: B-bad tetrahedra split at their circumcentres, largest R / f(c)
// first, unless the circumcentre encroaches the boundary.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include "base/debug.hpp"
#include "base/memory.hpp"
#include "base/step_laps.hpp"
#include "predicates/predicates3d.hpp"
#include "tet/dt_queries.hpp"
#include "tet/refiner3.hpp"
#include "tet/tet_geometry.hpp"

namespace fdr::tet {

bool Refiner3::face_is_subfacet(TetId t, int i) const {
  const auto& v = dt_.vertices(t);
  const VertexId a = v[(i + 1) & 3], b = v[(i + 2) & 3], c = v[(i + 3) & 3];
  if (a == kInfinite || b == kInfinite || c == kInfinite) return false;
  return bd_->subfacet(a, b, c) != UINT32_MAX;
}

std::int32_t Refiner3::material(TetId t) const {
  const std::int32_t r = region(t);
  return r >= 0 ? static_cast<std::int32_t>(std::lround(plc_.regions[static_cast<std::size_t>(r)].attribute)) : 0;
}

void Refiner3::flood(TetId start, std::int32_t code, std::vector<std::uint32_t>& mark, std::uint32_t stamp) {
  std::vector<TetId> stack{start};
  mark[start] = stamp;
  while (!stack.empty()) {
    const TetId t = stack.back();
    stack.pop_back();
    region_[t] = code;
    for (int i = 0; i < 4; ++i) {
      const TetId n = dt_.neighbour(t, i);
      if (mark[n] == stamp || face_is_subfacet(t, i)) continue;
      mark[n] = stamp;
      stack.push_back(n);
    }
  }
}

void Refiner3::flood_regions() {
  const std::size_t n = dt_.tet_slots();
  region_.reserve(dt_.tet_capacity());  // as the slots grow, without copies while they fit
  region_.assign(n, kUnknownRegion);
  std::vector<std::uint32_t> mark(n, 0);
  std::uint32_t stamp = 1;
  // The outside: everything reached from the ghosts without crossing a subfacet (one flood: the
  // ghosts are connected to each other around the hull).
  for (TetId t = 0; t < n; ++t)
    if (dt_.alive(t) && dt_.is_ghost(t) && mark[t] == 0) flood(t, kOutsideRegion, mark, stamp);
  const bool closed = !plc_.facets.empty();
  if (!closed) {  // a point set: its convex hull is the domain
    for (TetId t = 0; t < n; ++t)
      if (dt_.alive(t)) region_[t] = dt_.is_ghost(t) ? kOutsideRegion : kDefaultRegion;
  }
  for (const Point3& h : plc_.holes) {
    const TetId t = dt_.locate(h);
    if (t != kNoId && !dt_.is_ghost(t)) flood(t, kOutsideRegion, mark, ++stamp);
  }
  for (std::size_t r = 0; r < plc_.regions.size(); ++r) {
    const TetId t = dt_.locate(plc_.regions[r].point);
    if (t != kNoId && !dt_.is_ghost(t) && region_[t] != kOutsideRegion)
      flood(t, static_cast<std::int32_t>(r), mark, ++stamp);
  }
  for (TetId t = 0; t < n; ++t)
    if (dt_.alive(t) && region_[t] == kUnknownRegion) region_[t] = kDefaultRegion;
}

std::string Refiner3::stale_regions() {
  // The live labels against a fresh flood, which replaces them only for the count.
  const LargeArray<std::int32_t> live(region_);
  flood_regions();
  std::size_t in_out = 0, out_in = 0, other = 0;
  for (TetId t = 0; t < region_.size() && t < live.size(); ++t) {
    if (!dt_.alive(t) || live[t] == region_[t]) continue;
    if (region_[t] == kOutsideRegion) ++in_out;
    else if (live[t] == kOutsideRegion) ++out_in;
    else ++other;
  }
  region_ = live;
  if (in_out + out_in + other == 0) return {};
  char s[160];
  std::snprintf(s, sizeof s, "regions: %zu tetrahedra outside labelled inside, %zu inside labelled outside, %zu in another region",
                in_out, out_in, other);
  return s;
}

void Refiner3::assign_regions(const std::vector<TetId>& created) {
  if (region_.size() < dt_.tet_slots()) {
    if (region_.capacity() < dt_.tet_slots()) region_.reserve(std::max(dt_.tet_capacity(), 2 * region_.capacity()));
    region_.resize(dt_.tet_slots(), kUnknownRegion);
  }
  const bool hull_domain = plc_.facets.empty();  // a point set: every finite tetrahedron is inside
  for (TetId t : created)
    region_[t] = dt_.is_ghost(t) ? kOutsideRegion : (hull_domain ? kDefaultRegion : kUnknownRegion);
  // A new tetrahedron takes the region of an old neighbour across a face that is not a subfacet;
  // new ones pass it on among themselves (a cavity that no subfacet crosses is one region).
  for (bool changed = true; changed;) {
    changed = false;
    for (TetId t : created) {
      if (region_[t] != kUnknownRegion) continue;
      for (int i = 0; i < 4; ++i) {
        const std::int32_t r = region_[dt_.neighbour(t, i)];
        if (r == kUnknownRegion || face_is_subfacet(t, i)) continue;
        region_[t] = r;
        changed = true;
        break;
      }
    }
  }
  for (TetId t : created)
    if (region_[t] == kUnknownRegion) region_[t] = kDefaultRegion;
}

void Refiner3::relabel_regions(const std::vector<TetId>& tets) {
  // A boundary split's cavity may destroy other subfacets for a while (a thin layer's, the
  // hull's), and the tetrahedra made meanwhile took their regions across faces that were no
  // subfacets then: a region may have leaked into its neighbour. With every subfacet back, the
  // tetrahedra made since the last relabelling are flooded again from the older ones, whose
  // labels were right, so that labels never go stale between the passes' full floods.
  // A point set has nothing that separates regions; before flood_regions there are none.
  if (plc_.facets.empty() || region_.size() < dt_.tet_slots()) return;
  std::vector<std::int32_t> old(tets.size());
  for (std::size_t k = 0; k < tets.size(); ++k) old[k] = region_[tets[k]];
  for (TetId t : tets)
    if (dt_.alive(t)) region_[t] = dt_.is_ghost(t) ? kOutsideRegion : kUnknownRegion;
  std::vector<TetId> stack;
  for (TetId t : tets) {
    if (!dt_.alive(t) || region_[t] != kUnknownRegion) continue;
    for (int i = 0; i < 4 && stack.empty(); ++i) {
      const std::int32_t r = region_[dt_.neighbour(t, i)];
      if (r == kUnknownRegion || face_is_subfacet(t, i)) continue;
      region_[t] = r;
      stack.push_back(t);
    }
    while (!stack.empty()) {
      const TetId u = stack.back();
      stack.pop_back();
      for (int i = 0; i < 4; ++i) {
        const TetId n = dt_.neighbour(u, i);
        if (region_[n] != kUnknownRegion || face_is_subfacet(u, i)) continue;
        region_[n] = region_[u];
        stack.push_back(n);
      }
    }
  }
  // Tetrahedra that left the outside were never offered; those that entered it leave the queue
  // when popped (try_split_tet).
  std::vector<TetId> now_inside;
  for (std::size_t k = 0; k < tets.size(); ++k) {
    const TetId t = tets[k];
    if (!dt_.alive(t)) continue;
    if (region_[t] == kUnknownRegion) region_[t] = kDefaultRegion;
    if (old[k] == kOutsideRegion && region_[t] != kOutsideRegion) now_inside.push_back(t);
  }
  std::sort(now_inside.begin(), now_inside.end());
  now_inside.erase(std::unique(now_inside.begin(), now_inside.end()), now_inside.end());
  for (TetId t : now_inside) offer(t);
}

bool Refiner3::tet_bad(TetId t, BadTet* out) const {
  if (!dt_.alive(t) || dt_.is_ghost(t) || region(t) == kOutsideRegion) return false;
  const auto& v = dt_.vertices(t);
  const Point3 a = dt_.point(v[0]), b = dt_.point(v[1]), c = dt_.point(v[2]), d = dt_.point(v[3]);
  const Sphere s = circumsphere(a, b, c, d);
  const double ratio = s.radius / f_(s.centre);
  *out = {ratio, t, v, s.centre};
  // A sliver too flat for a double circumcentre is bad; try_split_tet leaves it (a shortfall).
  if (!(ratio <= bound_)) return true;
  // The paper's theorem gives radius-edge <= 2 only under conditions on B and f's Lipschitz
  // constant that a user's B need not meet; asking for it directly keeps the output's shape bound.
  // Such a split stays within the termination argument of Theorem 4.2: with the protection spheres
  // apart, the shortest edge pq has |pq| >= beta (f(p) + f(q)), so R > 2 |pq| gives
  // R > 4 beta f(p) / (1 + alpha beta), which is what Lemma 4.1 asks of the circumcentre's
  // distance to every vertex whenever alpha beta <= 1/7 (always so with alpha B < 1).
  constexpr double kRadiusEdge = 2.0;
  if (s.radius > kRadiusEdge * shortest_edge(a, b, c, d)) return true;
  const std::int32_t r = region(t);
  if (r >= 0) {
    const double vmax = plc_.regions[static_cast<std::size_t>(r)].max_volume;
    if (vmax > 0 && std::fabs(dot(b - a, cross(c - a, d - a))) / 6 > vmax) return true;
  }
  return false;
}

void Refiner3::offer(TetId t) {
  // Without a queue (after rule 3, in the closing boundary pass) a bad tetrahedron is left to
  // list_shortfalls.
  if (!bad_) return;
  BadTet b;
  if (tet_bad(t, &b)) bad_->push(b);
  else if (slivers_) offer_sliver(t);
}

std::uint32_t Refiner3::subfacet_toward(TetId tet, Point3 centre) const {
  // A straight walk from the tetrahedron's centroid toward the centre, each step through the face
  // the segment leaves by (exact orientations; a tie takes the first face that qualifies). Every
  // tetrahedron whose interior the segment meets is in the centre's conflict region (it is
  // star-shaped from the centre and holds the tetrahedron), so the first subfacet
  // crossed is destroyed by the insertion unless the crossing is degenerate, and which it is
  // is decided exactly.
  const Point3 c = centre;
  const auto& bv = dt_.vertices(tet);
  const Point3 q = 0.25 * (dt_.point(bv[0]) + dt_.point(bv[1]) + dt_.point(bv[2]) + dt_.point(bv[3]));
  TetId t = tet;
  // The walk only spares a dig; one as long as a conflict region is large gives up to it.
  constexpr std::size_t kMaxSteps = 4096;
  for (std::size_t step = 0; step < kMaxSteps; ++step) {
    const auto& v = dt_.vertices(t);
    std::array<Point3, 4> p;
    for (int k = 0; k < 4; ++k) p[k] = dt_.point(v[k]);
    int exit = -1, first = -1;
    for (int i = 0; i < 4 && exit < 0; ++i) {
      std::array<Point3, 4> r = p;
      r[i] = c;
      if (predicates::orient3d(r[0], r[1], r[2], r[3]) >= 0) continue;  // c not beyond face i
      if (first < 0) first = i;
      const Point3 a = p[(i + 1) & 3], bb = p[(i + 2) & 3], d = p[(i + 3) & 3];
      const int s1 = predicates::orient3d(q, c, a, bb), s2 = predicates::orient3d(q, c, bb, d),
                s3 = predicates::orient3d(q, c, d, a);
      if ((s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0)) exit = i;
    }
    if (first < 0) return UINT32_MAX;  // c is in t's closure: no subfacet in between
    if (exit < 0) exit = first;
    const TetId n = dt_.neighbour(t, exit);
    if (face_is_subfacet(t, exit)) {
      const VertexId a = v[(exit + 1) & 3], bb = v[(exit + 2) & 3], d = v[(exit + 3) & 3];
      const std::uint32_t sf = bd_->subfacet(a, bb, d);
      const bool encroached = predicates::equatorial_side(dt_.point(a), dt_.point(bb), dt_.point(d), c) >= 0;
      const bool destroyed = in_conflict(dt_, t, c) && in_conflict(dt_, n, c);
      return encroached || destroyed ? sf : UINT32_MAX;
    }
    if (dt_.is_ghost(n)) return UINT32_MAX;
    t = n;
  }
  return UINT32_MAX;
}

void Refiner3::try_split_tet(const BadTet& b) {
  if (region(b.tet) == kOutsideRegion) return;  // relabelled since it was queued
  if (!std::isfinite(b.centre.x) || !std::isfinite(b.centre.y) || !std::isfinite(b.centre.z)) return;
  const std::size_t segs_before = seg_queue_.size(), facets_before = facet_queue_.size();
  // A circumcentre beyond a subfacet (often far outside, with a conflict region of thousands of
  // tetrahedra) is rejected for the first subfacet it lies beyond, found by a walk, when the
  // circumcentre encroaches it or the insertion would destroy it, as the dig below would decide.
  // Without acute facet pairs no subfacet stays encroached after conform(), and then no
  // circumcentre lies beyond one (its tetrahedron's vertex would encroach it): the walk is spared.
  const std::uint32_t crossed = acute_.empty() ? UINT32_MAX : subfacet_toward(b.tet, b.centre);
  if (crossed != UINT32_MAX) {
    facet_queue_.push_back({crossed, bd_->tri(crossed).v, true});
    reject_for_boundary(b, segs_before, facets_before);
    return;
  }
  // The conflict region is dug once: what the circumcentre would encroach is read from it, and
  // the insertion, when it goes ahead, is made from it.
  const TetId h = dt_.locate(b.centre, b.tet);
  if (h == kNoId || dt_.dig(b.centre, h).duplicate) {
    ++stats_.rejected;  // left bad: the final check lists it if nothing else splits it
    return;
  }
  const std::vector<TetId>& cavity = dt_.cavity();
  if (find_encroached(b.centre, cavity, true)) {
    dt_.abandon();
    reject_for_boundary(b, segs_before, facets_before);
    return;
  }
  // No subfacet lies inside the cavity, so the circumcentre is in the bad tetrahedron's region;
  // outside the hull it would have crossed one.
  if (dt_.is_ghost(h) || region(h) == kOutsideRegion) {
    dt_.abandon();
    ++stats_.rejected;  // as above
    return;
  }
  created_.clear();
  const Insertion ins = dt_.insert_dug(&created_);
  ++stats_.tet_splits;
  after_insert(ins.vertex, created_);
  conform();
}

void Refiner3::reject_for_boundary(const BadTet& b, std::size_t segs_before, std::size_t facets_before) {
  ++stats_.rejected;
  if (b.ratio <= bound_ && near_small_angle(segs_before, facets_before)) {
    // Only its shape is bad and the boundary it encroaches meets another facet at an acute
    // angle: splitting there cascades toward the angle without end, so the tetrahedron stays
    // (and is listed as a shortfall).
    seg_queue_.resize(segs_before);
    facet_queue_.resize(facets_before);
    return;
  }
  const std::size_t before = dt_.num_vertices();
  conform();
  // Still bad if the splits left it; without a new vertex it would only come back unchanged.
  if (dt_.num_vertices() > before) offer(b.tet);
}

bool Refiner3::near_acute_partner(std::uint32_t f, Point3 c, double r) const {
  // The cascade between two facets at a small angle runs where a piece of one has the other
  // within its ball: its split point then encroaches the other's pieces, and theirs it, ever
  // closer to the angle. A ball that stays off the other facet's plane holds none of that facet's
  // vertices: the two facets do not feed each other's splits there, and the termination argument
  // of the paper's Theorem 4.2 holds as it does away from any small angle. A policy choice only
  // (doubles suffice): which rejected splits to go ahead with.
  for (std::size_t k = 0; k < acute_.size(); ++k) {
    const auto& [g, h] = acute_[k];
    if (g != f && h != f) continue;
    const FacetPlane& other = acute_planes_[2 * k + (g == f ? 1 : 0)];
    if (!(std::fabs(dot(c - other.p, other.n)) > r)) return true;  // NaN counts as near
  }
  return false;
}

bool Refiner3::near_small_angle(std::size_t segs_from, std::size_t facets_from) const {
  if (acute_.empty()) return false;
  for (std::size_t i = facets_from; i < facet_queue_.size(); ++i) {
    const SubfacetTri& s = bd_->tri(facet_queue_[i].tri);
    const Point3 a = dt_.point(s.v[0]);
    const Point3 c = triangle_circumcentre(a, dt_.point(s.v[1]), dt_.point(s.v[2]));
    if (near_acute_partner(s.facet, c, dist(c, a))) return true;
  }
  for (std::size_t i = segs_from; i < seg_queue_.size(); ++i) {
    const std::uint32_t o = bd_->segment_origin(seg_queue_[i].a, seg_queue_[i].b);
    if (o == UINT32_MAX) continue;
    const Point3 a = dt_.point(seg_queue_[i].a), b = dt_.point(seg_queue_[i].b);
    for (std::uint32_t f : bd_->origin(o).facets)
      if (near_acute_partner(f, 0.5 * (a + b), 0.5 * dist(a, b))) return true;
  }
  return false;
}

void Refiner3::refine() {
  StepLaps lap(debug::Aid::kStages, "stage tet:");
  char what[64];
  bad_ = std::make_unique<BadTetQueue>(bound_);
  // A few passes: the regions are flooded again after each, in case a boundary split passed a
  // region on across a subfacet that was missing for a moment.
  constexpr int kPasses = 4;
  for (int pass = 0; pass < kPasses && !stats_.capped; ++pass) {
    const std::size_t before = dt_.num_vertices();
    enqueue_all();
    conform();
    std::snprintf(what, sizeof what, "pass %d sweep (%zu vertices)", pass, dt_.num_vertices() - before);
    lap(what);
    flood_regions();
    regions_live_ = true;
    dt_.for_each_finite_tet([&](TetId t) { offer(t); });
    std::snprintf(what, sizeof what, "pass %d flood and offer (%zu bad)", pass, bad_->size());
    lap(what);
    if (bad_->size() == 0) break;
    BadTet b;
    std::size_t purge_at = dt_.tet_slots() * 3 / 2;
    while (!capped() && bad_->pop(dt_, &b)) {
      try_split_tet(b);
      if (dt_.tet_slots() < purge_at) continue;
      // The per-tetrahedron arrays (slots, marks, regions) have grown by copying into larger
      // buffers: the outgrown ones go back to the system now rather than stay resident (for
      // seconds, by the allocator's decay) beside the arrays still growing.
      release_free_memory();
      purge_at = dt_.tet_slots() * 3 / 2;
    }
    std::snprintf(what, sizeof what, "pass %d rule 3 (%zu vertices)", pass, dt_.num_vertices() - before);
    lap(what);
    // A pass that made no vertex leaves the mesh and the flood's labels as it found them, so the
    // next would only repeat it (the same tetrahedra offered, the same circumcentres rejected).
    if (dt_.num_vertices() == before) break;
  }
  if (options_.remove_slivers && options_.sliver_angle_deg > 0 && !stats_.capped) remove_slivers();
  lap("slivers");
  bad_.reset();  // what it holds is stale or left for the shortfalls: its memory goes first
  const std::size_t before = dt_.num_vertices();
  enqueue_all();
  conform();
  std::snprintf(what, sizeof what, "closing sweep (%zu vertices)", dt_.num_vertices() - before);
  lap(what);
  flood_regions();
  list_shortfalls();
  lap("closing flood and shortfalls");
}

void Refiner3::list_shortfalls() {
  dt_.for_each_finite_tet([&](TetId t) {
    BadTet b;
    if (!tet_bad(t, &b)) return;
    const auto& v = dt_.vertices(t);
    const Point3 a = dt_.point(v[0]), bb = dt_.point(v[1]), c = dt_.point(v[2]), d = dt_.point(v[3]);
    char what[160];
    std::snprintf(what, sizeof what, "tetrahedron left with R/f(c) %.4g, radius-edge %.4g (circumcentre given)",
                  b.ratio, circumsphere(a, bb, c, d).radius / shortest_edge(a, bb, c, d));
    note_shortfall(b.centre, what);
  });
}

}  // namespace fdr::tet
