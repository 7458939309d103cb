// Sliver removal: the measurements and queue of slivers.hpp, and Refiner3's sliver phase that runs
// after rule 3 (with rule 3 and the boundary rules kept in force at every insertion).
#include "tet/slivers.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include "base/memory.hpp"
#include "predicates/predicates3d.hpp"
#include "tet/dt_queries.hpp"
#include "tet/refiner3.hpp"
#include "tet/tet_geometry.hpp"

namespace fdr::tet {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr std::size_t kHistogramBins = 18;  // 10-degree bins over [0, 180], as the report's

double cos_to_deg(double c) { return std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / kPi; }

std::size_t histogram_bin(double deg) {
  return std::min(kHistogramBins - 1, static_cast<std::size_t>(std::max(0.0, deg) / 10.0));
}

// The radical inverse of k in base 2: 1/2, 1/4, 3/4, 1/8, ... (evenly spread in (0, 1)).
double van_der_corput(unsigned k) {
  double x = 0, scale = 0.5;
  for (; k; k >>= 1, scale *= 0.5)
    if (k & 1) x += scale;
  return x;
}

}  // namespace

Sphere sliver_ball(Point3 a, Point3 b, Point3 c, Point3 d) {
  const Sphere s = circumsphere(a, b, c, d);
  const bool finite = std::isfinite(s.radius) && std::isfinite(s.centre.x) && std::isfinite(s.centre.y) &&
                      std::isfinite(s.centre.z);
  if (finite && predicates::insphere(a, b, c, d, s.centre) > 0) return s;
  // The sphere through a nearly flat tetrahedron is ill-conditioned. The circumcentre of any of
  // its faces lies in the face's plane at distance t from the sphere's centre, inside a sphere of
  // radius sqrt(r^2 + t^2): the largest face gives the best conditioned such point.
  const Point3 p[4] = {a, b, c, d};
  int best = 0;
  double best_area2 = -1;
  for (int i = 0; i < 4; ++i) {
    const Point3 q0 = p[(i + 1) & 3], q1 = p[(i + 2) & 3], q2 = p[(i + 3) & 3];
    const double area2 = norm2(cross(q1 - q0, q2 - q0));
    if (area2 > best_area2) best_area2 = area2, best = i;
  }
  const Point3 q0 = p[(best + 1) & 3], q1 = p[(best + 2) & 3], q2 = p[(best + 3) & 3];
  const Point3 centre = triangle_circumcentre(q0, q1, q2);
  return {centre, dist(centre, q0)};
}

double smallest_dihedral_cos(Point3 a, Point3 b, Point3 c, Point3 d) {
  // Each face's unit normal pointing away from the opposite vertex; the interior angle at the edge
  // two faces share is pi minus the angle between their outward normals.
  const Point3 p[4] = {a, b, c, d};
  Point3 n[4];
  for (int i = 0; i < 4; ++i) {
    const Point3 q0 = p[(i + 1) & 3], q1 = p[(i + 2) & 3], q2 = p[(i + 3) & 3];
    Point3 v = cross(q1 - q0, q2 - q0);
    const double side = dot(v, p[i] - q0);
    const double len2 = norm2(v);
    if (side == 0 || !(len2 > 0)) return 1;  // flat (or degenerate) in double precision
    if (side > 0) v = -1.0 * v;
    n[i] = (1.0 / std::sqrt(len2)) * v;
  }
  double worst = -1;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) worst = std::max(worst, -dot(n[i], n[j]));
  return std::min(worst, 1.0);
}

std::vector<Point3> sliver_candidates(Point3 centre, double radius, double delta, int count) {
  std::vector<Point3> out;
  out.reserve(static_cast<std::size_t>(std::max(count, 1)));
  out.push_back(centre);
  const int m = count - 1;
  const double golden_angle = kPi * (3.0 - std::sqrt(5.0));
  for (int k = 0; k < m; ++k) {
    const double z = 1.0 - (2.0 * k + 1.0) / m;
    const double rho = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = golden_angle * k;
    // The cube root makes the distances uniform in volume rather than in radius.
    const double r = delta * radius * std::cbrt(van_der_corput(static_cast<unsigned>(k) + 1));
    out.push_back(centre + Point3{r * rho * std::cos(phi), r * rho * std::sin(phi), r * z});
  }
  return out;
}

InsertionAngles insertion_angles(const Delaunay3& dt, Point3 p, const std::vector<TetId>& cavity,
                                 std::vector<TetId>& scratch, double good_cos, double rival_cos) {
  // The cavity sorted, to tell its boundary faces (a search in a few dozen slots instead of marks
  // over every slot of the mesh).
  scratch.assign(cavity.begin(), cavity.end());
  std::sort(scratch.begin(), scratch.end());
  InsertionAngles out;
  for (TetId t : cavity) {
    if (dt.is_ghost(t)) continue;
    const auto& v = dt.vertices(t);
    out.destroyed_cos = std::max(out.destroyed_cos, smallest_dihedral_cos(dt.point(v[0]), dt.point(v[1]),
                                                                          dt.point(v[2]), dt.point(v[3])));
  }
  // Past this the candidate is neither good nor an improvement: the rest need not be measured.
  const double useless = std::min(out.destroyed_cos, rival_cos);
  for (TetId t : cavity) {
    const auto& v = dt.vertices(t);
    for (int i = 0; i < 4; ++i) {
      if (std::binary_search(scratch.begin(), scratch.end(), dt.neighbour(t, i))) continue;
      const VertexId a = v[(i + 1) & 3], b = v[(i + 2) & 3], c = v[(i + 3) & 3];
      if (a == kInfinite || b == kInfinite || c == kInfinite) continue;  // the new tetrahedron is a ghost
      out.created_cos = std::max(out.created_cos, smallest_dihedral_cos(dt.point(a), dt.point(b), dt.point(c), p));
      if (out.created_cos > good_cos && out.created_cos >= useless) return out;
    }
  }
  return out;
}

bool SliverQueue::Better::operator()(const SliverTet& a, const SliverTet& b) const {
  // priority_queue puts the largest first: "a below b" when a's smallest angle is larger.
  if (a.cos != b.cos) return a.cos < b.cos;
  auto sa = a.v, sb = b.v;
  std::sort(sa.begin(), sa.end());
  std::sort(sb.begin(), sb.end());
  return sa > sb;
}

bool SliverQueue::pop(const Delaunay3& dt, SliverTet* out) {
  while (!heap_.empty()) {
    const SliverTet s = heap_.top();
    heap_.pop();
    if (dt.alive(s.tet) && dt.vertices(s.tet) == s.v) {
      *out = s;
      return true;
    }
  }
  return false;
}

double Refiner3::tet_dihedral_cos(TetId t) const {
  const auto& v = dt_.vertices(t);
  return smallest_dihedral_cos(dt_.point(v[0]), dt_.point(v[1]), dt_.point(v[2]), dt_.point(v[3]));
}

void Refiner3::offer_sliver(TetId t) {
  if (!dt_.alive(t) || dt_.is_ghost(t) || region(t) == kOutsideRegion) return;
  const double c = tet_dihedral_cos(t);
  if (c > slivers_->cos_threshold) slivers_->queue.push({c, t, dt_.vertices(t)});
}

void Refiner3::remove_slivers() {
  slivers_ = std::make_unique<SliverState>();
  slivers_->cos_threshold = std::cos(options_.sliver_angle_deg * kPi / 180.0);
  slivers_->cos_floor = std::cos(options_.sliver_angle_deg / 3 * kPi / 180.0);
  stats_.sliver_angle_deg = options_.sliver_angle_deg;
  stats_.dihedral_hist_before.assign(kHistogramBins, 0);
  const VertexEdgeRatios fdr = vertex_edge_ratios(
      dt_, [&](TetId t) { return region(t) != kOutsideRegion; }, [&](Point3 p) { return f_(p); });
  stats_.fdr_vertex_figures = true;
  stats_.fdr_nn_over_f_min = fdr.nn_over_f_min;
  stats_.fdr_el_over_f_max = fdr.el_over_f_max;
  release_free_memory();  // its per-vertex arrays would otherwise stay resident as the phase grows the mesh
  double worst = -1;
  dt_.for_each_finite_tet([&](TetId t) {
    if (region(t) == kOutsideRegion) return;
    const double c = tet_dihedral_cos(t);
    worst = std::max(worst, c);
    ++stats_.dihedral_hist_before[histogram_bin(cos_to_deg(c))];
    if (c > slivers_->cos_threshold) {
      slivers_->queue.push({c, t, dt_.vertices(t)});
      ++stats_.slivers_before;
    }
  });
  stats_.min_dihedral_before_deg = worst < -0.5 ? 0 : cos_to_deg(worst);
  // Every insertion here removes a sliver or splits the boundary for one; a budget proportional to
  // the mesh stops a cascade that the local improvement test alone would not.
  const std::size_t start = dt_.num_vertices();
  const std::size_t budget = start / 2 + 1000;
  SliverTet s;
  while (!capped() && dt_.num_vertices() - start < budget && slivers_->queue.pop(dt_, &s)) {
    try_split_sliver(s);
    BadTet b;
    while (!capped() && bad_->pop(dt_, &b)) try_split_tet(b);
  }
  slivers_.reset();
  list_slivers();
}

void Refiner3::try_split_sliver(const SliverTet& s) {
  const Point3 a = dt_.point(s.v[0]), b = dt_.point(s.v[1]), c = dt_.point(s.v[2]), d = dt_.point(s.v[3]);
  const Sphere sp = sliver_ball(a, b, c, d);
  if (!std::isfinite(sp.radius) || !std::isfinite(sp.centre.x) || !std::isfinite(sp.centre.y) ||
      !std::isfinite(sp.centre.z))
    return;
  std::vector<TetId>& cavity = slivers_->cavity;
  // The first candidate that makes no sliver wins; failing that, the one that improves most on the
  // tetrahedra it replaces. A candidate that encroaches the boundary or lies outside the domain
  // is never inserted (the mesh stays conforming Delaunay).
  Point3 pick{};
  TetId pick_h = kNoId;
  double pick_cos = 2;
  for (const Point3& p : sliver_candidates(sp.centre, sp.radius, kSliverBallDelta, kSliverCandidates)) {
    // Only a point strictly inside the sliver's circumsphere destroys it.
    if (predicates::insphere(a, b, c, d, p) <= 0) continue;
    if (!conflict_region(dt_, p, s.tet, cavity, kSliverMaxCavity)) continue;
    const InsertionAngles ang =
        insertion_angles(dt_, p, cavity, slivers_->sorted, slivers_->cos_threshold, pick_cos);
    const bool good = ang.created_cos <= slivers_->cos_threshold;
    if (!good && !(ang.created_cos < ang.destroyed_cos && ang.created_cos < pick_cos)) continue;
    const std::size_t segs = seg_queue_.size(), facets = facet_queue_.size();
    const bool encroaches = find_encroached(p, cavity, true);
    seg_queue_.resize(segs);
    facet_queue_.resize(facets);
    if (encroaches) continue;
    const TetId h = dt_.locate(p, s.tet);
    if (h == kNoId || dt_.is_ghost(h) || region(h) == kOutsideRegion) continue;
    pick = p, pick_h = h, pick_cos = ang.created_cos;
    if (good) break;
  }
  if (pick_h != kNoId) {
    std::vector<TetId> created;
    const Insertion ins = dt_.insert(pick, pick_h, &created);
    if (ins.duplicate) return;
    ++stats_.sliver_splits;
    after_insert(ins.vertex, created);
    conform();
    return;
  }
  if (predicates::insphere(a, b, c, d, sp.centre) > 0) yield_for_sliver(s, sp.centre);
}

void Refiner3::yield_for_sliver(const SliverTet& s, Point3 centre) {
  // No candidate could go in: as in rule 3, the boundary pieces the circumcentre encroaches are
  // split instead, unless they meet another facet at an acute angle, where splits feed each other;
  // there only the flattest slivers (under a third of the threshold) split it, few enough that the
  // phase's budget bounds them.
  const std::size_t segs = seg_queue_.size(), facets = facet_queue_.size();
  // A centre beyond a subfacet yields to the first one it lies beyond (rule3.cpp), undug.
  if (const std::uint32_t crossed = subfacet_toward(s.tet, centre); crossed != UINT32_MAX) {
    facet_queue_.push_back({crossed, bd_->tri(crossed).v, true});
  } else {
    std::vector<TetId>& cavity = slivers_->cavity;
    conflict_region(dt_, centre, s.tet, cavity);
    if (!find_encroached(centre, cavity, true)) return;  // left; listed at the end if still a sliver
  }
  if (s.cos <= slivers_->cos_floor && near_small_angle(segs, facets)) {
    seg_queue_.resize(segs);
    facet_queue_.resize(facets);
    return;
  }
  ++stats_.sliver_yields;
  const std::size_t before = dt_.num_vertices();
  conform();
  if (dt_.num_vertices() > before) offer_sliver(s.tet);
}

void Refiner3::list_slivers() {
  // A handful locate what is left; thousands would only repeat it.
  constexpr std::size_t kMaxListed = 32;
  const double threshold = std::cos(options_.sliver_angle_deg * kPi / 180.0);
  stats_.slivers_left = 0;
  stats_.slivers_listed.clear();
  dt_.for_each_finite_tet([&](TetId t) {
    if (region(t) == kOutsideRegion) return;
    const double c = tet_dihedral_cos(t);
    if (!(c > threshold)) return;
    ++stats_.slivers_left;
    if (stats_.slivers_listed.size() >= kMaxListed) return;
    const auto& v = dt_.vertices(t);
    const Point3 centroid = 0.25 * (dt_.point(v[0]) + dt_.point(v[1]) + dt_.point(v[2]) + dt_.point(v[3]));
    char what[96];
    std::snprintf(what, sizeof what, "sliver left with smallest dihedral angle %.3g deg (centroid given)", cos_to_deg(c));
    stats_.slivers_listed.push_back({centroid, what});
  });
}

}  // namespace fdr::tet
