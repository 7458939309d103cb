// Refiner3's start and rules 1 and 2: the conforming Delaunay tetrahedralization of the PLC.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include "base/debug.hpp"
#include "predicates/predicates3d.hpp"
#include "tet/dt_queries.hpp"
#include "tet/refiner3.hpp"

namespace fdr::tet {
namespace {

// The 2D mesher's default: R / f(c) <= 1. Radius-edge <= 2 is asked for separately (tet_bad).
constexpr double kDefaultBound = 1.0;

// Vertices the spacing asks for over the PLC's box, estimated from f on a coarse grid of samples
// (a regular tetrahedron with edge f has volume f^3 / (6 sqrt 2), about six per vertex).
double estimated_vertices(const plc::Plc& plc, const sizing::SizingField3& f) {
  Box3 box;
  for (const Point3& p : plc.points) box.add(p);
  if (box.empty()) return 0;
  constexpr int kSamples = 12;
  const Point3 d = (1.0 / kSamples) * (box.hi - box.lo);
  const double cell = std::max(d.x, 1e-300) * std::max(d.y, 1e-300) * std::max(d.z, 1e-300);
  double n = 0;
  for (int i = 0; i < kSamples; ++i)
    for (int j = 0; j < kSamples; ++j)
      for (int k = 0; k < kSamples; ++k) {
        const Point3 p = box.lo + Point3{(i + 0.5) * d.x, (j + 0.5) * d.y, (k + 0.5) * d.z};
        const double h = f(p);
        if (h > 0 && std::isfinite(h)) n += cell / (h * h * h / (6 * std::sqrt(2.0))) / 6;
      }
  return n;
}

// Facet pairs that share a vertex but no segment and leave that vertex in nearly the same direction
// (an edge of one within 15 degrees of an edge of the other): the wedge between them, such as a
// layer pinching out to a point, is as thin as at a small dihedral angle, and their splits feed
// each other toward the vertex in the same way. 15 degrees stays below the angles of a quality 2D
// triangulation, so facets of one flat surface around a vertex are not taken; like the dihedral
// test this picks a policy only, in double precision.
std::vector<std::pair<std::uint32_t, std::uint32_t>> vertex_wedge_pairs(const plc::Plc& plc, const plc::FacetTriangulation& ft) {
  constexpr double kSmallWedgeCos = 0.96592582628906831;  // cos 15 degrees
  // A vertex with more edges than this is the apex of a fan, not the tip of a wedge of two layers:
  // its pairs are not tried.
  constexpr std::size_t kMaxRays = 256;
  struct Ray {
    std::uint32_t facet;
    Point3 d;  // unit direction
  };
  std::vector<std::vector<Ray>> rays(plc.points.size());
  for (std::uint32_t f = 0; f < ft.triangles.size(); ++f)
    for (const auto& t : ft.triangles[f])
      for (int k = 0; k < 3; ++k)
        for (int j = 1; j < 3; ++j) {
          const Point3 d = plc.points[t[(k + j) % 3]] - plc.points[t[k]];
          const double len = std::sqrt(norm2(d));
          if (len > 0) rays[t[k]].push_back({f, (1.0 / len) * d});
        }
  std::vector<std::pair<std::uint32_t, std::uint32_t>> shared, out;
  for (const plc::Subsegment& s : ft.subsegments)
    for (std::size_t i = 0; i < s.facets.size(); ++i)
      for (std::size_t j = i + 1; j < s.facets.size(); ++j) shared.push_back({s.facets[i], s.facets[j]});
  std::sort(shared.begin(), shared.end());
  for (const auto& rs : rays) {
    if (rs.size() > kMaxRays) continue;
    for (std::size_t i = 0; i < rs.size(); ++i)
      for (std::size_t j = i + 1; j < rs.size(); ++j) {
        if (rs[i].facet == rs[j].facet || dot(rs[i].d, rs[j].d) <= kSmallWedgeCos) continue;
        const std::pair<std::uint32_t, std::uint32_t> key{std::min(rs[i].facet, rs[j].facet), std::max(rs[i].facet, rs[j].facet)};
        if (!std::binary_search(shared.begin(), shared.end(), key)) out.push_back(key);
      }
  }
  return out;
}

}  // namespace

Point3 segment_split_point(Point3 a, Point3 b, bool a_apex, bool b_apex) {
  if (a_apex == b_apex) return 0.5 * (a + b);
  const Point3 from = a_apex ? a : b, to = a_apex ? b : a;
  const double len = dist(a, b);
  // 2^round(log2(len / 2)) lies within [len / 2 / sqrt 2, len / 2 * sqrt 2]: well inside the piece.
  const double r = std::exp2(std::round(std::log2(0.5 * len)));
  return from + (r / len) * (to - from);
}

Point3 triangle_circumcentre(Point3 a, Point3 b, Point3 c) {
  const Point3 ab = b - a, ac = c - a, n = cross(ab, ac);
  // The normal's rounding error is a few units in the last place of |ab| |ac|; a triangle whose
  // normal is within a million times that has a double centre that may be anywhere (or NaN when
  // the normal rounds to zero), so it is constructed exactly, as circumsphere does for tetrahedra.
  constexpr double kFlat = 1e6 * 8 * std::numeric_limits<double>::epsilon();
  const double scale = norm2(ab) * norm2(ac);
  if (!(norm2(n) > kFlat * kFlat * scale) || !std::isfinite(scale)) {
    if (predicates::collinear3d(a, b, c)) {
      const double nan = std::numeric_limits<double>::quiet_NaN();
      return {nan, nan, nan};
    }
    return predicates::triangle_circumcentre_exact(a, b, c);
  }
  const double s = 0.5 / norm2(n);
  return a + s * (norm2(ac) * cross(n, ab) + norm2(ab) * cross(ac, n));
}

Refiner3::Refiner3(const plc::Plc& plc, const plc::FacetTriangulation& ft, const sizing::SizingField3& f,
                   const TetOptions& options)
    : plc_(plc), ft_(ft), f_(f), options_(options) {
  bound_ = options.bound > 0 ? options.bound : kDefaultBound;
  check_boundary_ = debug::on(debug::Aid::kTet);
  stats_.bound = bound_;
  stats_.input_vertices = plc.points.size();
  const double est = estimated_vertices(plc, f);
  cap_ = options.max_vertices ? options.max_vertices
                              : static_cast<std::size_t>(std::min(20 * est, 4e9)) + 50 * plc.points.size() + 10000;
  // The estimate is of the right order for most spacings; room for it spares the copies of
  // growth, and a refinement that goes beyond it grows as usual. Capped so that an absurd
  // estimate asks for no more address space than a large machine has memory.
  constexpr double kMaxReserved = 1 << 24;
  dt_.reserve(std::min<std::size_t>(cap_, static_cast<std::size_t>(std::min(est, kMaxReserved)) + plc.points.size()));
  vid_ = dt_.insert_all(plc.points).vertex_of;
  std::vector<int> uses(plc.points.size(), 0);
  for (const auto& s : ft.subsegments) ++uses[s.a], ++uses[s.b];
  apex_.assign(dt_.num_vertices(), 0);
  for (std::size_t p = 0; p < plc.points.size(); ++p) apex_[vid_[p]] = uses[p] >= 2;
  bd_ = std::make_unique<Boundary>(dt_, plc, ft, vid_);
  find_acute_facet_pairs();
  bd_->for_each_subsegment([&](VertexId a, VertexId b, std::uint32_t) { seg_queue_.push_back({a, b, false}); });
  for (std::uint32_t t = 0; t < bd_->tri_slots(); ++t)
    if (bd_->tri(t).alive) facet_queue_.push_back({t, bd_->tri(t).v});
  facet_queued_.assign(bd_->tri_slots(), 1);
}

void Refiner3::find_acute_facet_pairs() {
  // Below 60 degrees the splits of two facets' subfacets feed each other; at 60 degrees and above
  // they die out as in the cube's corners.
  constexpr double kSmallDihedralCos = 0.5;
  // Per input subsegment the facets on it and, for each, the corner of its triangle on the
  // segment: the angle between the two triangles' directions away from the segment. This picks a
  // protection policy only (double precision suffices); no mesh decision rests on it.
  for (const plc::Subsegment& s : ft_.subsegments) {
    if (s.facets.size() < 2) continue;
    const VertexId a = vid_[s.a], b = vid_[s.b];
    const Point3 pa = dt_.point(a), e = dt_.point(b) - pa;
    std::vector<std::pair<std::uint32_t, Point3>> away;
    for (std::uint32_t t : bd_->subfacets_at(a)) {
      const SubfacetTri& tr = bd_->tri(t);
      if (std::find(tr.v.begin(), tr.v.end(), b) == tr.v.end()) continue;
      for (VertexId w : tr.v)
        if (w != a && w != b) {
          const Point3 d = dt_.point(w) - pa;
          away.push_back({tr.facet, d - (dot(d, e) / norm2(e)) * e});
        }
    }
    for (std::size_t i = 0; i < away.size(); ++i)
      for (std::size_t j = i + 1; j < away.size(); ++j)
        if (away[i].first != away[j].first &&
            dot(away[i].second, away[j].second) > kSmallDihedralCos * std::sqrt(norm2(away[i].second) * norm2(away[j].second)))
          acute_.push_back({std::min(away[i].first, away[j].first), std::max(away[i].first, away[j].first)});
  }
  const auto wedges = vertex_wedge_pairs(plc_, ft_);
  acute_.insert(acute_.end(), wedges.begin(), wedges.end());
  std::sort(acute_.begin(), acute_.end());
  acute_.erase(std::unique(acute_.begin(), acute_.end()), acute_.end());
  auto plane = [&](std::uint32_t f) {
    const plc::FacetFrame& fr = ft_.frames[f];
    const Point3 p0 = plc_.points[fr.p0];
    const Point3 n = cross(plc_.points[fr.p1] - p0, plc_.points[fr.p2] - p0);
    return FacetPlane{p0, (1.0 / std::sqrt(norm2(n))) * n};
  };
  acute_planes_.clear();
  for (const auto& [f, g] : acute_) {
    acute_planes_.push_back(plane(f));
    acute_planes_.push_back(plane(g));
  }
}

bool Refiner3::acute_pair(std::uint32_t f, std::uint32_t g) const {
  const std::pair<std::uint32_t, std::uint32_t> key{std::min(f, g), std::max(f, g)};
  return std::binary_search(acute_.begin(), acute_.end(), key);
}

bool Refiner3::capped() {
  if (dt_.num_vertices() < cap_) return false;
  if (!stats_.capped) note_shortfall({}, "vertex cap reached before every rule was met");
  stats_.capped = true;
  return true;
}

void Refiner3::note_shortfall(Point3 where, const std::string& what) {
  // A handful locate the trouble; thousands would only repeat it.
  constexpr std::size_t kMaxListed = 32;
  if (stats_.shortfalls.size() < kMaxListed) stats_.shortfalls.push_back({where, what});
}

bool Refiner3::segment_encroached(VertexId a, VertexId b) {
  // Only the vertices around the edge can lie in its diametral sphere first (the sphere is empty
  // when they do not): each is tested once, from a walk around the edge rather than a's whole star.
  const TetId t = edge_tet(dt_, a, b);
  if (t == kNoId) return true;  // missing: its diametral sphere is not empty
  edge_ring(dt_, t, a, b, ring_);
  const Point3 pa = dt_.point(a), pb = dt_.point(b);
  for (VertexId u : ring_)
    if (u != kInfinite && predicates::diametral_side(pa, pb, dt_.point(u)) >= 0) return true;
  return false;
}

bool Refiner3::subfacet_encroached(std::uint32_t t) {
  const SubfacetTri& s = bd_->tri(t);
  std::array<VertexId, 2> apex{};
  const int n = face_apexes(dt_, s.v[0], s.v[1], s.v[2], apex);
  if (n == 0) return true;  // missing
  const Point3 a = dt_.point(s.v[0]), b = dt_.point(s.v[1]), c = dt_.point(s.v[2]);
  // A Delaunay face whose two apexes lie outside its equatorial sphere has that sphere empty; a
  // vertex of the same facet is coplanar by construction (rounding aside), so never encroaches.
  for (int i = 0; i < n; ++i) {
    const VertexId u = apex[i];
    if (u == kInfinite || bd_->on_facet(u, s.facet)) continue;
    bool protected_apex = false;
    if (!acute_.empty())
      for (std::uint32_t k : bd_->subfacets_at(u)) protected_apex = protected_apex || acute_pair(bd_->tri(k).facet, s.facet);
    if (protected_apex) continue;
    const Point3 p = dt_.point(u);
    if (predicates::orient3d(a, b, c, p) != 0 && predicates::equatorial_side(a, b, c, p) >= 0) return true;
  }
  return false;
}

void Refiner3::enqueue_at(VertexId u) {
  for (VertexId w : bd_->segment_neighbours(u))
    if (u < w) seg_queue_.push_back({u, w, false});
  if (facet_queued_.size() < bd_->tri_slots()) facet_queued_.resize(bd_->tri_slots(), 0);
  for (std::uint32_t t : bd_->subfacets_at(u))
    if (!facet_queued_[t]) {
      facet_queued_[t] = 1;
      facet_queue_.push_back({t, bd_->tri(t).v});
    }
}

void Refiner3::enqueue_changed(VertexId v, const std::vector<TetId>& created) {
  // Every vertex of a destroyed tetrahedron is a vertex of a created one (the cavity is
  // star-shaped from v), so a subsegment or subfacet that the insertion destroyed, or whose
  // neighbourhood it changed, has all its corners among the created tetrahedra's vertices. Taken
  // from the insertion itself, not from a cavity computed before it, so that no lost piece can
  // go unqueued whatever that computation missed.
  if (vmark_.size() < dt_.num_vertices()) vmark_.resize(dt_.num_vertices() * 3 / 2 + 16, 0);
  ++vstamp_;
  around_.clear();
  for (TetId t : created)
    for (VertexId u : dt_.vertices(t))
      if (u != kInfinite && u != v && vmark_[u] != vstamp_) {
        vmark_[u] = vstamp_;
        around_.push_back(u);
      }
  for (VertexId u : around_) {
    for (VertexId w : bd_->segment_neighbours(u))
      if (u < w && vmark_[w] == vstamp_) seg_queue_.push_back({u, w, false});
    for (std::uint32_t t : bd_->subfacets_at(u)) {
      const auto& c = bd_->tri(t).v;
      if (facet_queued_[t] || vmark_[c[0]] != vstamp_ || vmark_[c[1]] != vstamp_ || vmark_[c[2]] != vstamp_) continue;
      facet_queued_[t] = 1;
      facet_queue_.push_back({t, c});
    }
  }
}

void Refiner3::enqueue_all() {
  bd_->for_each_subsegment([&](VertexId a, VertexId b, std::uint32_t) { seg_queue_.push_back({a, b, false}); });
  if (facet_queued_.size() < bd_->tri_slots()) facet_queued_.resize(bd_->tri_slots(), 0);
  for (std::uint32_t t = 0; t < bd_->tri_slots(); ++t)
    if (bd_->tri(t).alive && !facet_queued_[t]) {
      facet_queued_[t] = 1;
      facet_queue_.push_back({t, bd_->tri(t).v});
    }
}

void Refiner3::after_insert(VertexId v, const std::vector<TetId>& created) {
  if (apex_.size() < dt_.num_vertices()) apex_.resize(dt_.num_vertices(), 0);
  if (facet_queued_.size() < bd_->tri_slots()) facet_queued_.resize(bd_->tri_slots(), 0);
  enqueue_changed(v, created);
  enqueue_at(v);  // the new pieces at v, when it was split into the boundary
  if (regions_live_) {
    episode_tets_.insert(episode_tets_.end(), created.begin(), created.end());
    assign_regions(created);
    for (TetId t : created) offer(t);
  }
  if (options_.progress && cap_ > 0 && dt_.num_vertices() % 4096 == 0)
    options_.progress(std::min(0.99, static_cast<double>(dt_.num_vertices()) / static_cast<double>(cap_)));
}

void Refiner3::split_segment(VertexId a, VertexId b) {
  const Point3 p = segment_split_point(dt_.point(a), dt_.point(b), apex_[a], apex_[b]);
  std::vector<TetId> created;
  const TetId on_edge = edge_tet(dt_, a, b);
  const TetId hint = on_edge != kNoId ? on_edge : dt_.vertex_tet(a);
  const TetId h = dt_.locate(p, hint);
  const Insertion ins = dt_.insert(p, h, &created);
  if (ins.duplicate) {  // the piece is too short to split in doubles
    ++stalls_;
    note_shortfall(p, "subsegment too short to split");
    return;
  }
  const std::size_t capped = bd_->capped_cavities();
  bd_->split_segment(a, b, ins.vertex);
  if (bd_->capped_cavities() > capped) note_shortfall(p, "facet cavity capped at a subsegment split (facet left non-Delaunay there)");
  ++stats_.segment_splits;
  episode_split_ = true;
  after_insert(ins.vertex, created);
}

bool Refiner3::find_encroached(Point3 p, const std::vector<TetId>& cavity, bool facets) {
  constexpr std::size_t kSmallCavity = 64;
  bool any = false;
  if (vmark_.size() < dt_.num_vertices()) vmark_.resize(dt_.num_vertices() * 3 / 2 + 16, 0);
  if (facet_queued_.size() < bd_->tri_slots()) facet_queued_.resize(bd_->tri_slots(), 0);
  // Two stamps: a vertex seen here, and one seen that is a corner of some subfacet. Only a face
  // with three such corners can be a subfacet, so a cavity away from the facets (the usual case)
  // makes no face look-up at all.
  if (vstamp_ > UINT32_MAX - 2) {
    std::fill(vmark_.begin(), vmark_.end(), 0);
    vstamp_ = 0;
  }
  const std::uint32_t seen = ++vstamp_, on_facets = ++vstamp_;
  bool tmarked = false;
  for (TetId t : cavity) {
    const auto& tv = dt_.vertices(t);
    int corners = 0;  // vertices of t on some facet
    for (VertexId u : tv) {
      if (u == kInfinite) continue;
      if (vmark_[u] == seen) continue;
      if (vmark_[u] == on_facets) {
        ++corners;
        continue;
      }
      vmark_[u] = bd_->subfacets_at(u).empty() ? seen : on_facets;
      corners += vmark_[u] == on_facets;
      for (VertexId w : bd_->segment_neighbours(u))
        if (u < w && predicates::diametral_side(dt_.point(u), dt_.point(w), p) >= 0) {
          seg_queue_.push_back({u, w, true});
          any = true;
        }
    }
    if (!facets || corners < 3 || dt_.is_ghost(t)) continue;
    // Which tetrahedra are in the cavity: a search of a small one, marks for a large one (marks
    // over every slot would cost bytes per tetrahedron for a question rarely asked).
    const bool small = cavity.size() <= kSmallCavity;
    if (!small && !tmarked) {
      if (tmark_.size() < dt_.tet_slots()) tmark_.resize(dt_.tet_slots() * 3 / 2 + 16, 0);
      ++tstamp_;
      for (TetId c : cavity) tmark_[c] = tstamp_;
      tmarked = true;
    }
    for (int i = 0; i < 4; ++i) {
      const std::array<VertexId, 3> f{tv[(i + 1) & 3], tv[(i + 2) & 3], tv[(i + 3) & 3]};
      if (vmark_[f[0]] != on_facets || vmark_[f[1]] != on_facets || vmark_[f[2]] != on_facets) continue;
      const std::uint32_t s = bd_->subfacet(f[0], f[1], f[2]);
      if (s == UINT32_MAX) continue;
      const TetId n = dt_.neighbour(t, i);
      // A subfacet inside the cavity would be destroyed: split it as if encroached.
      const bool destroyed =
          small ? std::find(cavity.begin(), cavity.end(), n) != cavity.end() : tmark_[n] == tstamp_;
      if (destroyed || predicates::equatorial_side(dt_.point(f[0]), dt_.point(f[1]), dt_.point(f[2]), p) >= 0) {
        facet_queue_.push_back({s, bd_->tri(s).v, true});
        any = true;
      }
    }
  }
  return any;
}

void Refiner3::split_subfacet(std::uint32_t t) {
  const SubfacetTri s = bd_->tri(t);
  const Point3 c = triangle_circumcentre(dt_.point(s.v[0]), dt_.point(s.v[1]), dt_.point(s.v[2]));
  if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z)) {
    // Collinear corners: the piece has no circumcentre to split it at (a stall, as a duplicate is).
    ++stalls_;
    note_shortfall(dt_.point(s.v[0]), "subfacet with collinear corners cannot be split");
    return;
  }
  const FacetLocation loc = bd_->locate_in_facet(t, c);
  if (loc.tri == UINT32_MAX) {  // beyond a subsegment of the facet: it is encroached
    seg_queue_.push_back({loc.seg[0], loc.seg[1], true});
    ++stats_.rejected;
    facet_queue_.push_back({t, s.v, true});
    return;
  }
  const TetId h = dt_.locate(c, dt_.vertex_tet(s.v[0]));
  // The conflict region is dug once, for the encroachment test and the insertion (a point on a
  // facet next to the outside digs the outside's large tetrahedra too).
  if (h == kNoId || dt_.dig(c, h).duplicate) {
    ++stalls_;
    note_shortfall(c, "subfacet circumcentre repeats a vertex");
    return;
  }
  static const std::vector<TetId> kNone;
  if (find_encroached(c, dt_.is_ghost(h) ? kNone : dt_.cavity(), false)) {
    dt_.abandon();
    ++stats_.rejected;
    facet_queue_.push_back({t, s.v, true});
    return;
  }
  std::vector<TetId> created;
  const Insertion ins = dt_.insert_dug(&created);
  const std::size_t capped = bd_->capped_cavities();
  bd_->insert_in_facet(loc.tri, ins.vertex);
  if (bd_->capped_cavities() > capped) note_shortfall(c, "facet cavity capped at a subfacet split (facet left non-Delaunay there)");
  ++stats_.facet_splits;
  episode_split_ = true;
  after_insert(ins.vertex, created);
}

void Refiner3::conform() {
  // One episode: rules 1 and 2 until the queues are empty. Stalled splits (pieces too short for
  // doubles) and rounds that only queue again without inserting (a rejected split whose
  // replacement cannot be made) are counted within the episode, so that a long run's earlier
  // episodes do not shorten a later one; either reaching its cap ends the episode.
  constexpr std::size_t kMaxStalls = 1000;
  constexpr std::size_t kMaxIdle = 100000;
  stalls_ = 0;
  std::size_t idle = 0;
  Point3 last{};
  while ((!seg_queue_.empty() || !facet_queue_.empty()) && !capped() && stalls_ < kMaxStalls && idle < kMaxIdle) {
    const std::size_t vertices = dt_.num_vertices(), queued = seg_queue_.size() + facet_queue_.size();
    conform_step(&last);
    if (dt_.num_vertices() > vertices) idle = 0;
    else if (seg_queue_.size() + facet_queue_.size() >= queued) ++idle;
  }
  if (stalls_ >= kMaxStalls || idle >= kMaxIdle) {
    char what[120];
    std::snprintf(what, sizeof what, "boundary splits %s; the last piece tried is given",
                  stalls_ >= kMaxStalls ? "stalled (pieces too short to split)" : "made no progress");
    note_shortfall(last, what);
    gave_up_ = true;
  }
  if (regions_live_) {
    if (episode_split_) relabel_regions(episode_tets_);
    episode_tets_.clear();
    episode_split_ = false;
  }
  if (check_boundary_ && conforming()) {
    const std::string m = missing_boundary();
    if (!m.empty()) std::fprintf(stderr, "tet: %zu vertices: %s\n", dt_.num_vertices(), m.c_str());
    // A flood per episode would be quadratic: one every 1024 vertices.
    if (regions_live_ && dt_.num_vertices() >= regions_checked_at_ + 1024) {
      regions_checked_at_ = dt_.num_vertices();
      const std::string r = stale_regions();
      if (!r.empty()) std::fprintf(stderr, "tet: %zu vertices: %s\n", dt_.num_vertices(), r.c_str());
    }
  }
}

void Refiner3::conform_step(Point3* last) {
  if (!seg_queue_.empty()) {
    const QueuedSegment q = seg_queue_.front();
    seg_queue_.pop_front();
    if (bd_->is_subsegment(q.a, q.b) && (q.forced || segment_encroached(q.a, q.b))) {
      *last = 0.5 * (dt_.point(q.a) + dt_.point(q.b));
      split_segment(q.a, q.b);
    }
    return;
  }
  const QueuedFacet q = facet_queue_.front();
  facet_queue_.pop_front();
  if (!q.forced) facet_queued_[q.tri] = 0;
  const SubfacetTri& s = bd_->tri(q.tri);
  // A slot that holds another subfacet than when queued: a forced entry is void, but the flag of
  // an unforced one also stood for the new subfacet (not queued again while it was set), so that
  // one is checked now.
  if (!s.alive || (q.forced && s.v != q.v)) return;
  if (q.forced || subfacet_encroached(q.tri)) {
    *last = (1.0 / 3) * (dt_.point(s.v[0]) + dt_.point(s.v[1]) + dt_.point(s.v[2]));
    split_subfacet(q.tri);
  }
}

std::string Refiner3::missing_boundary() const {
  auto at = [&](VertexId v) {
    const Point3 p = dt_.point(v);
    char s[96];
    std::snprintf(s, sizeof s, "%u (%.17g, %.17g, %.17g)", v, p.x, p.y, p.z);
    return std::string(s);
  };
  std::string out;
  bd_->for_each_subsegment([&](VertexId a, VertexId b, std::uint32_t) {
    if (out.empty() && edge_tet(dt_, a, b) == kNoId) out = "subsegment " + at(a) + " - " + at(b) + " is no edge";
  });
  for (std::uint32_t t = 0; t < bd_->tri_slots() && out.empty(); ++t) {
    const SubfacetTri& s = bd_->tri(t);
    std::array<VertexId, 2> apex{};
    if (s.alive && face_apexes(dt_, s.v[0], s.v[1], s.v[2], apex) == 0)
      out = "subfacet " + std::to_string(t) + " of facet " + std::to_string(s.facet) + ": " + at(s.v[0]) + " " +
            at(s.v[1]) + " " + at(s.v[2]) + " is no face";
  }
  return out;
}

}  // namespace fdr::tet
