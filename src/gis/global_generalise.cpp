// Land generalised in ground metres, batch by batch in stereographic planes centred on the
// batches (global_generalise.hpp).
#include "gis/global_generalise.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <tuple>

#include "coast/convex.hpp"
#include "base/debug.hpp"
#include "base/error.hpp"
#include "base/parallel.hpp"
#include "gis/global_land.hpp"
#include "gis/global_sphere.hpp"
#include "gis/vector_layers.hpp"

namespace fdr::gis {

namespace {

// A point of a ring on the sphere (metres from the centre) in its cube of the hash grid, on the
// ring's edge `edge` (from vertex edge to edge + 1); a vertex lies on edge - 1 as well.
struct CellPoint {
  std::array<std::int64_t, 3> cell;
  std::uint32_t ring;
  std::uint32_t edge;
  bool vertex;
  Point3 p;
};

Point3 normalised(Point3 v) { return (1.0 / std::sqrt(dot(v, v))) * v; }

// Distance between the segments pq and rs of R^3 (closest points clamped to the segments).
double segment_distance(Point3 p, Point3 q, Point3 r, Point3 s) {
  const Point3 d1 = q - p, d2 = s - r, w = p - r;
  const double a = dot(d1, d1), e = dot(d2, d2), b = dot(d1, d2), c = dot(d1, w), f = dot(d2, w);
  auto clamp01 = [](double t) { return std::clamp(t, 0.0, 1.0); };
  double t1 = 0, t2 = 0;
  if (a <= 0 && e <= 0) return std::sqrt(dot(w, w));
  if (a <= 0) {
    t2 = clamp01(f / e);
  } else if (e <= 0) {
    t1 = clamp01(-c / a);
  } else {
    const double den = a * e - b * b;
    t1 = den > 0 ? clamp01((b * f - c * e) / den) : 0.0;
    t2 = (b * t1 + f) / e;
    if (t2 < 0) {
      t2 = 0;
      t1 = clamp01(-c / a);
    } else if (t2 > 1) {
      t2 = 1;
      t1 = clamp01((b - c) / a);
    }
  }
  const Point3 g = (p + t1 * d1) - (r + t2 * d2);
  return std::sqrt(dot(g, g));
}

// True when edge k of ring a may come within `reach` metres of edge l of ring b on the sphere:
// their chords within reach plus how far each arc bulges beyond its chord (its sagitta), so that
// arcs within reach always pass.
bool edges_within(const std::vector<LonLat>& a, std::size_t k, const std::vector<LonLat>& b, std::size_t l, double reach) {
  const Point3 p = kEarthRadius * unit_vector(a[k]), q = kEarthRadius * unit_vector(a[(k + 1) % a.size()]);
  const Point3 r = kEarthRadius * unit_vector(b[l]), s = kEarthRadius * unit_vector(b[(l + 1) % b.size()]);
  const double sag = (dot(q - p, q - p) + dot(s - r, s - r)) / (8 * kEarthRadius);
  return segment_distance(p, q, r, s) <= reach + sag;
}

// Every vertex of every ring and points between them at most `gap` metres apart, in cubes of
// side `cell` metres.
std::vector<CellPoint> cell_points(const std::vector<std::vector<LonLat>>& rings, double gap, double cell) {
  std::vector<CellPoint> out;
  auto add = [&](Point3 u, std::size_t ring, std::size_t edge, bool vertex) {
    const Point3 p = kEarthRadius * u;
    out.push_back({{static_cast<std::int64_t>(std::floor(p.x / cell)), static_cast<std::int64_t>(std::floor(p.y / cell)),
                    static_cast<std::int64_t>(std::floor(p.z / cell))},
                   static_cast<std::uint32_t>(ring), static_cast<std::uint32_t>(edge), vertex, p});
  };
  for (std::size_t i = 0; i < rings.size(); ++i) {
    const auto& r = rings[i];
    for (std::size_t k = 0, n = r.size(); k < n; ++k) {
      const Point3 a = unit_vector(r[k]), b = unit_vector(r[(k + 1) % n]);
      add(a, i, k, true);
      const int m = static_cast<int>(std::min(1e5, std::ceil(std::sqrt(dot(b - a, b - a)) * kEarthRadius / gap)));
      for (int j = 1; j < m; ++j) add(normalised(a + (static_cast<double>(j) / m) * (b - a)), i, k, false);
    }
  }
  std::sort(out.begin(), out.end(), [](const CellPoint& a, const CellPoint& b) {
    return std::tie(a.cell, a.ring) < std::tie(b.cell, b.ring);
  });
  return out;
}

// The scale factor and widths of a batch's plane: lengths times `s`, areas times s^2.
coast::Options scaled(const coast::Options& g, double s) {
  coast::Options o = g;
  for (double* len : {&o.close_width, &o.min_feature, &o.grow_island, &o.widen_width, &o.islet_side, &o.islet_shift,
                      &o.islet_clearance, &o.connect_width, &o.narrow_gap, &o.tip_clearance})
    *len *= s;
  for (double* area : {&o.min_island_area, &o.grow_island_area, &o.list_area, &o.connect_area, &o.gap_body_area}) *area *= s * s;
  o.defer_removed = false;
  o.early_listing_rss = 0;
  return o;
}

// The exterior rings of the land pieces (their holes, water enclosed by land, filled), pieces
// inside such a hole dropped.
std::vector<std::vector<Point2>> filled_land(std::vector<std::unique_ptr<OGRPolygon>> pieces) {
  std::vector<char> drop(pieces.size(), 0);
  std::vector<OGREnvelope> env(pieces.size());
  for (std::size_t i = 0; i < pieces.size(); ++i) pieces[i]->getEnvelope(&env[i]);
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    if (pieces[i]->getNumInteriorRings() == 0) continue;  // disjoint pieces: only a hole holds others
    OGRPolygon outer;
    outer.addRing(pieces[i]->getExteriorRing());
    const PreparedPtr prep(OGRCreatePreparedGeometry(OGRGeometry::ToHandle(&outer)));
    for (std::size_t j = 0; j < pieces.size(); ++j)
      if (j != i && !drop[j] && env[i].Contains(env[j]) &&
          OGRPreparedGeometryContains(prep.get(), OGRGeometry::ToHandle(pieces[j].get())))
        drop[j] = 1;
  }
  std::vector<std::vector<Point2>> out;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    if (drop[i]) continue;
    std::vector<Point2> r = curve_points(pieces[i]->getExteriorRing());
    if (r.size() >= 2 && r.front() == r.back()) r.pop_back();
    if (r.size() >= 3) out.push_back(std::move(r));
  }
  return out;
}

// Points along every edge longer than `step`, so that the ring keeps its line in another plane.
std::vector<Point2> densified(const std::vector<Point2>& r, double step) {
  std::vector<Point2> out;
  out.reserve(r.size());
  for (std::size_t i = 0, n = r.size(); i < n; ++i) {
    const Point2 a = r[i], b = r[(i + 1) % n];
    out.push_back(a);
    const int m = static_cast<int>(std::min(1e5, std::ceil(std::hypot(b.x - a.x, b.y - a.y) / step)));
    for (int j = 1; j < m; ++j) out.push_back(a + (static_cast<double>(j) / m) * (b - a));
  }
  return out;
}

// Land generalised in one plane: whole groups.
struct Batch {
  std::vector<std::vector<LonLat>> rings;
  std::size_t points = 0;
};

struct BatchOut {
  std::vector<std::vector<LonLat>> rings;
  std::vector<char> holds_pole;
  coast::Result res;
  double scale = 1;
};

// One batch: its land in the plane centred on it, the water around it (a box a margin beyond the
// land) generalised with the widths times the plane's scale, the holes of that water back on the
// sphere. The scale is the geometric mean of the plane's scale factors over the batch (1 at its
// centre), so that ground widths are met within sqrt(largest factor) either way.
BatchOut generalise_batch(const Batch& b, LonLat pole, const coast::Options& ground, double reach, double step_m) {
  Point3 sum{0, 0, 0};
  for (const auto& r : b.rings)
    for (const LonLat& p : r) sum = sum + unit_vector(p);
  const Point3 c = dot(sum, sum) > 0 ? normalised(sum) : unit_vector(b.rings[0][0]);
  const LonLat centre = to_lonlat(c);
  const SphereStereo local({centre.lon_deg > 0 ? centre.lon_deg - 180 : centre.lon_deg + 180, -centre.lat_deg});
  BatchOut out;
  double kmax = 1;
  std::vector<std::unique_ptr<OGRPolygon>> pieces;
  for (std::size_t i = 0; i < b.rings.size(); ++i) {
    std::vector<Point2> pts;
    pts.reserve(b.rings[i].size());
    for (const LonLat& p : b.rings[i]) {
      const Point2 q = local.forward(p);
      if (!std::isfinite(q.x) || !std::isfinite(q.y) || std::hypot(q.x, q.y) > 100 * local.radius())
        throw Error(ExitCode::kInvalidGeometry, "land near (" + std::to_string(p.lon_deg) + ", " +
                                                    std::to_string(p.lat_deg) + "): a group of land spans the sphere");
      kmax = std::max(kmax, local.scale(q));
      pts.push_back(q);
    }
    std::unique_ptr<OGRGeometry> v = valid_copy(plane_polygon(pts), "global land ring " + std::to_string(i));
    std::vector<const OGRPolygon*> ps;
    collect_polygons(v.get(), ps);
    for (const OGRPolygon* p : ps)
      if (!p->IsEmpty()) pieces.emplace_back(p->clone());
  }
  out.scale = std::sqrt(kmax);
  std::vector<std::vector<Point2>> land = filled_land(disjoint_land(std::move(pieces), "global land"));
  Box2 box;
  for (const auto& r : land)
    for (const Point2& p : r) box.add(p);
  coast::Rings water;
  const double m = 2 * reach * out.scale;
  water.push_back({{box.lo.x - m, box.lo.y - m}, {box.hi.x + m, box.lo.y - m}, {box.hi.x + m, box.hi.y + m},
                   {box.lo.x - m, box.hi.y + m}});
  for (auto& r : land) {
    if (coast::signed_area(r) > 0) std::reverse(r.begin(), r.end());  // holes clockwise
    water.push_back(std::move(r));
  }
  out.res = coast::generalise({std::move(water)}, scaled(ground, out.scale));
  // The water around the land: the piece with the largest outer ring (the box, its corners rounded).
  std::size_t main = 0;
  for (std::size_t k = 1; k < out.res.polygons.size(); ++k)
    if (std::fabs(coast::signed_area(out.res.polygons[k][0])) > std::fabs(coast::signed_area(out.res.polygons[main][0]))) main = k;
  const Point2 pole_at = local.forward(pole);
  const bool pole_here = std::isfinite(pole_at.x) && std::isfinite(pole_at.y);
  std::vector<std::vector<Point2>> land_out(out.res.polygons[main].begin() + 1, out.res.polygons[main].end());
  for (const auto& r : land_out) {
    out.holds_pole.push_back(pole_here && coast::inside_ring(pole_at, r) ? 1 : 0);
    std::vector<LonLat> ll;
    for (const Point2& p : densified(r, step_m)) ll.push_back(local.inverse(p));
    out.rings.push_back(std::move(ll));
  }
  out.res.polygons.clear();
  // Repairs in lon/lat.
  std::vector<pslg::Repair> reps;
  for (auto& rep : out.res.repairs) {
    const LonLat at = local.inverse(rep.where);
    rep.where = {at.lon_deg, at.lat_deg};
    rep.part = -1;
    reps.push_back(std::move(rep));
  }
  out.res.repairs = std::move(reps);
  return out;
}

// Adds a batch's figures to the sum (areas from its plane to the ground).
void add_figures(coast::Result& sum, coast::Result& r, double scale) {
  const double a = 1.0 / (scale * scale);
  sum.input_pieces += r.input_pieces;
  sum.output_pieces += r.output_pieces;
  sum.united += r.united;
  sum.united_overlap_area += a * r.united_overlap_area;
  sum.closed += r.closed;
  sum.closed_area += a * r.closed_area;
  sum.corner_pieces += r.corner_pieces;
  sum.channels_kept += r.channels_kept;
  sum.cut_off += r.cut_off;
  sum.cut_off_area += a * r.cut_off_area;
  sum.reconnected += r.reconnected;
  sum.reconnected_area += a * r.reconnected_area;
  sum.narrow_gaps += r.narrow_gaps;
  sum.narrow_gaps_made += r.narrow_gaps_made;
  sum.land_removed_area += a * r.land_removed_area;
  sum.widened += r.widened;
  sum.widened_area += a * r.widened_area;
  sum.islets_replaced += r.islets_replaced;
  sum.islets_joined += r.islets_joined;
  sum.islets_joined_area += a * r.islets_joined_area;
  sum.tips_kept += r.tips_kept;
  sum.islands_grown += r.islands_grown;
  sum.islands_grown_area += a * r.islands_grown_area;
  sum.islands_removed += r.islands_removed;
  sum.islands_area += a * r.islands_area;
  sum.input_area += a * r.input_area;
  sum.output_area += a * r.output_area;
  for (auto& rep : r.repairs) sum.repairs.push_back(std::move(rep));
}

// The batch of a group: its centre's cell of 20 degrees, or the cap within 30 degrees of a pole.
std::pair<int, int> batch_key(Point3 centre) {
  const LonLat c = to_lonlat(centre);
  if (c.lat_deg >= 60) return {100, 0};
  if (c.lat_deg <= -60) return {-100, 0};
  return {static_cast<int>(std::floor((c.lat_deg + 60) / 20)), static_cast<int>(std::floor((c.lon_deg + 180) / 20))};
}

// A group reaching farther than this from its centre with a ring round a pole has that ring's
// land split off into a polar batch (split_polar).
constexpr double kGroupRadiusDeg = 35;
// The polar batch takes the group's land within this many reaches (group_reach) of its ring, so
// that its coast is generalised as with all land around it.
constexpr double kHaloReaches = 3;

// A large group with a ring round a pole (Antarctica's coast, joined to other continents at a
// coarse resolution): that ring cannot be cut in lon/lat, so it goes whole into a batch of its
// own with the group's land within a halo (metres) of it; returns the rest of the group.
std::vector<std::size_t> split_polar(const std::vector<std::vector<LonLat>>& rings, const std::vector<std::size_t>& g,
                                     double halo, std::map<std::pair<int, int>, Batch>& by_key) {
  std::vector<char> placed(g.size(), 0);
  for (const Point3 pole : {Point3{0, 0, -1}, Point3{0, 0, 1}}) {
    double cos_cap = 1;  // the farthest point of the rings round this pole
    for (std::size_t i : g)
      if (winds_round_pole(rings[i]) && (rings[i][0].lat_deg < 0) == (pole.z < 0))
        for (const LonLat& p : rings[i]) cos_cap = std::min(cos_cap, dot(pole, unit_vector(p)));
    if (cos_cap == 1) continue;
    const double cos_halo = std::cos(std::acos(cos_cap) + halo / kEarthRadius);
    Batch& b = by_key[{pole.z < 0 ? -200 : 200, 0}];
    for (std::size_t k = 0; k < g.size(); ++k) {
      const auto& r = rings[g[k]];
      if (placed[k] || !std::all_of(r.begin(), r.end(), [&](const LonLat& p) { return dot(pole, unit_vector(p)) >= cos_halo; }))
        continue;
      placed[k] = 1;
      b.rings.push_back(r);
      b.points += r.size();
    }
  }
  std::vector<std::size_t> rest;
  for (std::size_t k = 0; k < g.size(); ++k)
    if (!placed[k]) rest.push_back(g[k]);
  return rest;
}

}  // namespace

double group_reach(const coast::Options& o) {
  const double islet = o.islet_side + o.islet_shift + o.islet_clearance;
  return 2 * std::max({o.close_width, o.min_feature, o.widen_width, islet, o.tip_clearance, o.narrow_gap,
                       o.connect_width, o.grow_island});
}

std::vector<std::vector<std::size_t>> land_groups(const std::vector<std::vector<LonLat>>& rings, double reach) {
  // Two coasts within `reach` have samples within reach + gap of each other (every point of an
  // edge lies within gap/2 of a sample on that edge or at one of its ends; chords are never longer
  // than great circles); of such candidates, only edges within reach join their rings, so that
  // land farther apart than the reach (two continents across a strait) stays in two groups.
  const double gap = 0.5 * reach, near = reach + gap;
  const std::vector<CellPoint> pts = cell_points(rings, gap, near);
  // Runs of points of one ring in one cube.
  std::vector<std::size_t> run{0};
  for (std::size_t i = 1; i < pts.size(); ++i)
    if (pts[i].cell != pts[i - 1].cell || pts[i].ring != pts[i - 1].ring) run.push_back(i);
  run.push_back(pts.size());
  std::vector<std::size_t> up(rings.size());
  for (std::size_t i = 0; i < up.size(); ++i) up[i] = i;
  // Samples nearer than `near` are candidates; their edges (both edges at a vertex) decide.
  auto edges_meet = [&](const CellPoint& x, const CellPoint& y) {
    const auto& ra = rings[x.ring];
    const auto& rb = rings[y.ring];
    for (std::size_t ba = 0; ba <= (x.vertex ? 1u : 0u); ++ba)  // ba = 1: the edge before
      for (std::size_t bb = 0; bb <= (y.vertex ? 1u : 0u); ++bb)
        if (edges_within(ra, (x.edge + ra.size() - ba) % ra.size(), rb, (y.edge + rb.size() - bb) % rb.size(), reach))
          return true;
    return false;
  };
  auto meet = [&](std::size_t r, std::size_t s) {
    for (std::size_t i = run[r]; i < run[r + 1]; ++i)
      for (std::size_t j = run[s]; j < run[s + 1]; ++j) {
        const Point3 d = pts[i].p - pts[j].p;
        if (dot(d, d) < near * near && edges_meet(pts[i], pts[j])) return true;
      }
    return false;
  };
  for (std::size_t r = 0; r + 1 < run.size(); ++r) {
    const auto& c = pts[run[r]].cell;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const std::array<std::int64_t, 3> n{c[0] + dx, c[1] + dy, c[2] + dz};
          if (n < c) continue;  // every pair of cubes once
          auto first = std::lower_bound(run.begin(), run.end() - 1, n,
                                        [&](std::size_t k, const auto& key) { return pts[k].cell < key; });
          for (auto it = first; it != run.end() - 1 && pts[*it].cell == n; ++it) {
            const std::size_t s = static_cast<std::size_t>(it - run.begin());
            const std::size_t a = find_root(up, pts[run[r]].ring), b = find_root(up, pts[run[s]].ring);
            if (a != b && meet(r, s)) up[std::max(a, b)] = std::min(a, b);
          }
        }
  }
  std::vector<std::vector<std::size_t>> groups;
  std::vector<std::size_t> group_of(rings.size(), rings.size());
  for (std::size_t i = 0; i < rings.size(); ++i) {
    const std::size_t root = find_root(up, i);
    if (group_of[root] == rings.size()) {
      group_of[root] = groups.size();
      groups.emplace_back();
    }
    groups[group_of[root]].push_back(i);
  }
  return groups;
}

GeneralisedLand generalise_land(const std::vector<std::vector<LonLat>>& rings, LonLat pole,
                                const coast::Options& ground, double step_deg) {
  GeneralisedLand out;
  const double reach = group_reach(ground);
  const std::vector<std::vector<std::size_t>> groups = land_groups(rings, reach);
  out.groups = groups.size();
  std::map<std::pair<int, int>, Batch> by_key;
  for (const auto& g : groups) {
    Point3 sum{0, 0, 0};
    std::size_t n = 0;
    bool round_pole = false;
    for (std::size_t i : g) {
      for (const LonLat& p : rings[i]) sum = sum + unit_vector(p);
      n += rings[i].size();
      round_pole = round_pole || winds_round_pole(rings[i]);
    }
    Point3 c = dot(sum, sum) > 0 ? normalised(sum) : unit_vector(rings[g[0]][0]);
    double cos_far = 1;
    for (std::size_t i : g)
      for (const LonLat& p : rings[i]) cos_far = std::min(cos_far, dot(c, unit_vector(p)));
    std::vector<std::size_t> rest = g;
    if (cos_far < std::cos(kGroupRadiusDeg * std::numbers::pi / 180)) {
      if (round_pole) rest = split_polar(rings, g, kHaloReaches * reach, by_key);
    }
    if (rest.empty()) continue;
    if (rest.size() < g.size()) {  // the group less its polar batch: a batch of its own
      sum = Point3{0, 0, 0};
      n = 0;
      for (std::size_t i : rest) {
        for (const LonLat& p : rings[i]) sum = sum + unit_vector(p);
        n += rings[i].size();
      }
      c = dot(sum, sum) > 0 ? normalised(sum) : unit_vector(rings[rest[0]][0]);
    }
    Batch& b = by_key[rest.size() < g.size() ? std::pair<int, int>{300, static_cast<int>(g[0])} : batch_key(c)];
    for (std::size_t i : rest) b.rings.push_back(rings[i]);
    b.points += n;
  }
  std::vector<Batch> batches;
  for (auto& [key, b] : by_key) batches.push_back(std::move(b));
  out.batches = batches.size();
  // The largest batches first, so that two threads finish together; results by batch.
  std::vector<std::size_t> order(batches.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return batches[a].points > batches[b].points; });
  std::vector<BatchOut> done(batches.size());
  const double step_m = step_deg * std::numbers::pi / 180 * kEarthRadius;
  const bool laps = debug::on(debug::Aid::kFilter);
  parallel_chunks(order.size(), [&](std::size_t k, unsigned) {
    const auto t0 = std::chrono::steady_clock::now();
    const Batch& b = batches[order[k]];
    done[order[k]] = generalise_batch(b, pole, ground, reach, step_m);
    if (laps)  // developer aid: the batches' sizes and times
      std::fprintf(stderr, "global batch %zu: %zu rings, %zu points, scale %.3f, %.3f s\n", order[k],
                   b.rings.size(), b.points, done[order[k]].scale,
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  });
  out.result.close_width = ground.close_width;
  for (auto& d : done) {
    out.max_scale = std::max(out.max_scale, d.scale * d.scale);
    add_figures(out.result, d.res, d.scale);
    for (std::size_t k = 0; k < d.rings.size(); ++k) {
      out.rings.push_back(std::move(d.rings[k]));
      out.holds_pole.push_back(d.holds_pole[k]);
    }
  }
  return out;
}

}  // namespace fdr::gis
