// Step: the places where the water stays narrower than the resolution, listed (narrow_gaps.hpp).
#include "coast/narrow_gaps.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "base/parallel.hpp"
#include "coast/convex.hpp"
#include "coast/geometry_ops.hpp"
#include "coast/report.hpp"
#include "pslg/segment_grid.hpp"

namespace fdr::coast {
namespace {

struct Seg {
  Point2 a, b;
  std::uint32_t ring;
  double at;  // the way along its ring to a (m)
};

// The closest points of two segments that do not cross: *s, *t their parameters on ab and cd.
double closest(const Seg& u, const Seg& v, double* s, double* t) {
  auto proj = [](Point2 p, Point2 a, Point2 b) {
    const Point2 d = b - a;
    const double l2 = norm2(d);
    return l2 > 0 ? std::clamp(dot(p - a, d) / l2, 0.0, 1.0) : 0.0;
  };
  auto at = [](Point2 a, Point2 b, double k) { return a + k * (b - a); };
  double best = std::numeric_limits<double>::infinity();
  const double cand[4][2] = {{0, proj(u.a, v.a, v.b)}, {1, proj(u.b, v.a, v.b)}, {proj(v.a, u.a, u.b), 0},
                             {proj(v.b, u.a, u.b), 1}};
  for (const auto& c : cand) {
    const double d = dist(at(u.a, u.b, c[0]), at(v.a, v.b, c[1]));
    if (d < best) {
      best = d;
      *s = c[0];
      *t = c[1];
    }
  }
  return best;
}

double cross(Point2 a, Point2 b) { return a.x * b.y - a.y * b.x; }

// The rings' segments with their way along the ring; *ring_len per ring, *box and *total.
std::vector<Seg> segments_of(const Polygons& polygons, std::vector<double>* ring_len, Box2* box, double* total) {
  std::vector<Seg> segs;
  for (const Rings& rings : polygons)
    for (const auto& r : rings) {
      const auto id = static_cast<std::uint32_t>(ring_len->size());
      double at = 0;
      for (std::size_t i = 0; i < r.size(); ++i) {
        const Point2 a = r[i], b = r[(i + 1) % r.size()];
        segs.push_back({a, b, id, at});
        at += dist(a, b);
        box->add(a);
      }
      ring_len->push_back(at);
      *total += at;
    }
  return segs;
}

pslg::SegmentGrid grid_of(const std::vector<Seg>& segs, const Box2& box, double total, double width) {
  pslg::SegmentGrid grid(box, segs.size(), std::max(total / static_cast<double>(segs.size()), width));
  for (std::size_t k = 0; k < segs.size(); ++k) grid.add_segment(static_cast<Index>(k), segs[k].a, segs[k].b);
  return grid;
}

// Distance from p to the nearest segment of segs within lim (lim when none is nearer).
double near_segment(const pslg::SegmentGrid& grid, const std::vector<Seg>& segs, Point2 p, double lim) {
  double best = lim;
  grid.for_box_cells({{p.x - lim, p.y - lim}, {p.x + lim, p.y + lim}}, [&](std::size_t c) {
    for (const Index k : grid.segments_in(c)) best = std::min(best, dist_to_segment(p, segs[k].a, segs[k].b));
  });
  return best;
}

}  // namespace

std::vector<NarrowGap> narrow_gaps(const Polygons& polygons, double width, const Polygons* input) {
  std::vector<NarrowGap> out;
  if (!(width > 0)) return out;
  std::vector<double> ring_len;
  Box2 box;
  double total = 0;
  const std::vector<Seg> segs = segments_of(polygons, &ring_len, &box, &total);
  if (segs.empty()) return out;
  const pslg::SegmentGrid grid = grid_of(segs, box, total, width);
  // Segments in chunks shared out to the threads, each chunk's hits kept apart and joined in
  // chunk order (the sort below makes the order the same for any thread count anyway).
  constexpr std::size_t kChunk = 4096;
  const std::size_t nchunks = (segs.size() + kChunk - 1) / kChunk;
  std::vector<std::vector<NarrowGap>> chunk_hits(nchunks);
  const unsigned nthreads = std::max(1u, max_threads());
  std::vector<std::vector<std::uint32_t>> stamp(nthreads, std::vector<std::uint32_t>(segs.size(), 0));
  std::vector<std::uint32_t> stamp_no(nthreads, 0);
  parallel_chunks(nchunks, [&](std::size_t c, unsigned worker) {
    std::vector<std::uint32_t>& seen = stamp[worker];
    std::uint32_t& now = stamp_no[worker];
    auto& hits = chunk_hits[c];
    for (std::size_t i = c * kChunk; i < std::min(segs.size(), (c + 1) * kChunk); ++i) {
      const Seg& u = segs[i];
      ++now;
      Box2 qb;
      qb.add({std::min(u.a.x, u.b.x) - width, std::min(u.a.y, u.b.y) - width});
      qb.add({std::max(u.a.x, u.b.x) + width, std::max(u.a.y, u.b.y) + width});
      grid.for_box_cells(qb, [&](std::size_t cell) {
        for (const Index k : grid.segments_in(cell)) {
          if (k <= i || seen[k] == now) continue;  // each pair once
          seen[k] = now;
          const Seg& v = segs[k];
          if (std::max(v.a.x, v.b.x) < qb.lo.x || std::min(v.a.x, v.b.x) > qb.hi.x ||
              std::max(v.a.y, v.b.y) < qb.lo.y || std::min(v.a.y, v.b.y) > qb.hi.y)
            continue;
          double s = 0, t = 0;
          const double d = closest(u, v, &s, &t);
          if (!(d < width) || !(d > 0)) continue;
          const Point2 p = u.a + s * (u.b - u.a), q = v.a + t * (v.b - v.a);
          // Water lies left of every segment: across water, each coast sees the other on its left.
          if (!(cross(u.b - u.a, q - p) > 0) || !(cross(v.b - v.a, p - q) > 0)) continue;
          if (u.ring == v.ring) {
            const double L = ring_len[u.ring];
            const double along = std::fabs((v.at + t * dist(v.a, v.b)) - (u.at + s * dist(u.a, u.b)));
            if (!(std::min(along, L - along) > 3 * d)) continue;
          }
          hits.push_back({0.5 * (p + q), d, false});
          hits.back().ends[0] = p;
          hits.back().ends[1] = q;
        }
      });
    }
  });
  std::vector<NarrowGap> hits;
  for (auto& h : chunk_hits) hits.insert(hits.end(), h.begin(), h.end());
  std::sort(hits.begin(), hits.end(), [](const NarrowGap& a, const NarrowGap& b) {
    auto key = [](const NarrowGap& g) {
      return std::array<double, 7>{g.width, g.where.x, g.where.y, g.ends[0].x, g.ends[0].y, g.ends[1].x, g.ends[1].y};
    };
    return key(a) < key(b);
  });
  // One place per cluster: cells of 2 width hold the places listed.
  const double cell = 2 * width;
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> listed;
  auto key = [](long i, long j) { return (static_cast<std::uint64_t>(i) << 32) ^ static_cast<std::uint32_t>(j); };
  for (const NarrowGap& g : hits) {
    const long ci = static_cast<long>(std::floor(g.where.x / cell)), cj = static_cast<long>(std::floor(g.where.y / cell));
    bool near_listed = false;
    for (long di = -1; di <= 1 && !near_listed; ++di)
      for (long dj = -1; dj <= 1 && !near_listed; ++dj)
        if (auto it = listed.find(key(ci + di, cj + dj)); it != listed.end())
          for (const std::size_t k : it->second)
            if (dist(out[k].where, g.where) < cell) { near_listed = true; break; }
    if (near_listed) continue;
    listed[key(ci, cj)].push_back(out.size());
    out.push_back(g);
  }
  // In the input: both coasts of the gap lie on the input's coast (within 5 % of the width).
  // Only the input's segments near a listed gap are indexed (the cells of the listing).
  if (input && !out.empty()) {
    const double tol = 0.05 * width;
    auto near_listed = [&](Point2 a, Point2 b) {
      const long i0 = static_cast<long>(std::floor((std::min(a.x, b.x) - tol) / cell)) - 1;
      const long i1 = static_cast<long>(std::floor((std::max(a.x, b.x) + tol) / cell)) + 1;
      const long j0 = static_cast<long>(std::floor((std::min(a.y, b.y) - tol) / cell)) - 1;
      const long j1 = static_cast<long>(std::floor((std::max(a.y, b.y) + tol) / cell)) + 1;
      if ((i1 - i0 + 1) * (j1 - j0 + 1) > 256) return true;  // a long segment: kept
      for (long i = i0; i <= i1; ++i)
        for (long j = j0; j <= j1; ++j)
          if (listed.count(key(i, j))) return true;
      return false;
    };
    std::vector<Seg> in_segs;
    Box2 in_box;
    double in_total = 0;
    for (const Rings& rings : *input)
      for (const auto& r : rings)
        for (std::size_t i = 0; i < r.size(); ++i) {
          const Point2 a = r[i], b = r[(i + 1) % r.size()];
          if (!near_listed(a, b)) continue;
          in_segs.push_back({a, b, 0, 0});
          in_box.add(a);
          in_box.add(b);
          in_total += dist(a, b);
        }
    if (!in_segs.empty()) {
      const pslg::SegmentGrid in_grid = grid_of(in_segs, in_box, in_total, width);
      for (NarrowGap& g : out) {
        for (int e = 0; e < 2; ++e) g.on_input[e] = near_segment(in_grid, in_segs, g.ends[e], tol) < tol;
        g.in_input = g.on_input[0] && g.on_input[1];
      }
    }
  }
  return out;
}

const char* gap_end_cause(Point2 end, const IsletPlacer* islets, double tol) {
  if (islets) {
    std::vector<std::uint32_t> cand;
    const Box2 qb{{end.x - tol, end.y - tol}, {end.x + tol, end.y + tol}};
    islets->placed_grid.near(qb, &cand);
    for (const std::uint32_t k : cand)
      if (!islets->placed_poly[k].empty() && convex_distance(end, end, islets->placed_poly[k]) < tol)
        return "an islet's triangle";
    islets->joined_grid.near(qb, &cand);
    for (const std::uint32_t k : cand)
      if (convex_distance(end, end, islets->joined[k]) < tol) return "an islet joined to land";
  }
  return "a widened bank or a cut";
}

void list_narrow_gaps(const Options& o, const OGRGeometry& input, Result& res, const IsletPlacer* islets) {
  if (!(o.narrow_gap > 0)) return;
  FilterLaps lap("  narrow gaps");
  OwnedPolygons ps;
  polygons_of(&input, ps);
  Polygons in;
  for (const auto& p : ps) {
    Rings rings;
    rings.push_back(ring_points(p->getExteriorRing(), true));
    for (int k = 0; k < p->getNumInteriorRings(); ++k) rings.push_back(ring_points(p->getInteriorRing(k), false));
    in.push_back(std::move(rings));
  }
  const double tol = 0.05 * o.narrow_gap;
  for (const NarrowGap& g : narrow_gaps(res.polygons, o.narrow_gap, &in)) {
    ++res.narrow_gaps;
    std::string why = "the input has it so";
    if (!g.in_input) {
      ++res.narrow_gaps_made;
      // Each moved coast by the step that moved it; the other coast may be the input's.
      std::string a = g.on_input[0] ? "" : gap_end_cause(g.ends[0], islets, tol);
      std::string b = g.on_input[1] ? "" : gap_end_cause(g.ends[1], islets, tol);
      if (a.empty()) std::swap(a, b);
      if (a == b) b.clear();
      why = "made where a step moved the coast: " + a + (b.empty() ? "" : " and " + b) +
            (g.on_input[0] || g.on_input[1] ? " facing the input's coast" : "");
    }
    res.repairs.push_back({"narrow_gap_kept", g.where, g.width,
                           "water " + num(g.width) + " m wide is kept narrower than " + num(o.narrow_gap) + " m (" + why +
                               "); the mesh needs elements about that small here",
                           -1});
  }
  lap("listed");
}

}  // namespace fdr::coast
