// Loose breakline ends and fixed points put on a boundary segment they nearly touch.
#include "base/num_format.hpp"
#include "pslg/snap_loose_ends.hpp"
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <unordered_map>

namespace fdr::pslg {
namespace {
std::string num(double v) { return num6(v); }
}  // namespace

// Breakline ends and free points lying within `tol` of a boundary segment they do not touch are
// put on it: the segment is split at the point. Why: a river clipped at the coast ends a rounding
// error short of it; pslg::clean merges close vertices but not vertex-segment pairs, and
// such a near-T-junction leaves a sliver the refiner cannot split (the rounded midpoint of the
// coast segment falls outside it). Returns one Repair per split (local coordinates).
std::vector<Repair> snap_loose_ends(pslg::Pslg& g, double tol) {
  std::vector<Repair> reps;
  if (!(tol > 0)) return reps;
  const std::size_t n = g.points.size();
  std::vector<int> bdeg(n, 0), ldeg(n, 0);
  for (const auto& sg : g.segments) {
    auto& d = sg.is_boundary() ? bdeg : ldeg;
    ++d[sg.a];
    ++d[sg.b];
  }
  std::vector<Index> loose;
  for (std::size_t v = 0; v < n; ++v)
    if (bdeg[v] == 0 && ldeg[v] <= 1) loose.push_back(static_cast<Index>(v));
  if (loose.empty()) return reps;
  // Loose points hashed on a grid; a segment looks at the cells its tol-widened box covers, or
  // at every loose point when that is fewer (long segments, few points).
  const Box2 box = g.bbox();
  const double cell = std::max({tol, std::hypot(box.width(), box.height()) / 4096.0, 1e-300});
  auto key = [&](long i, long j) { return i * 1000003L + j; };
  auto ci = [&](double x) { return static_cast<long>(std::floor((x - box.lo.x) / cell)); };
  auto cj = [&](double y) { return static_cast<long>(std::floor((y - box.lo.y) / cell)); };
  std::unordered_map<long, std::vector<Index>> grid;
  for (Index v : loose) grid[key(ci(g.points[v].x), cj(g.points[v].y))].push_back(v);
  struct Hit { double d = 0, t = 0; std::size_t seg = 0; bool found = false; };
  std::unordered_map<Index, Hit> hit;
  auto consider = [&](Index v, std::size_t s) {
    const auto& sg = g.segments[s];
    if (sg.a == v || sg.b == v) return;
    const Point2 p = g.points[v], a = g.points[sg.a], b = g.points[sg.b];
    const double dx = b.x - a.x, dy = b.y - a.y, l2 = dx * dx + dy * dy;
    if (!(l2 > 0)) return;
    const double t = ((p.x - a.x) * dx + (p.y - a.y) * dy) / l2;
    if (!(t > 0 && t < 1) || dist(p, a) <= tol || dist(p, b) <= tol) return;  // ends: clean's vertex snap
    const double d = std::fabs((p.x - a.x) * dy - (p.y - a.y) * dx) / std::sqrt(l2);
    Hit& h = hit[v];
    if (d <= tol && (!h.found || d < h.d)) h = {d, t, s, true};
  };
  const std::size_t nseg = g.segments.size();
  for (std::size_t s = 0; s < nseg; ++s) {
    const auto& sg = g.segments[s];
    if (!sg.is_boundary()) continue;
    const Point2 a = g.points[sg.a], b = g.points[sg.b];
    const long i0 = ci(std::min(a.x, b.x) - tol), i1 = ci(std::max(a.x, b.x) + tol);
    const long j0 = cj(std::min(a.y, b.y) - tol), j1 = cj(std::max(a.y, b.y) + tol);
    if (static_cast<double>(i1 - i0 + 1) * static_cast<double>(j1 - j0 + 1) > static_cast<double>(loose.size())) {
      for (Index v : loose) consider(v, s);
      continue;
    }
    for (long j = j0; j <= j1; ++j)
      for (long i = i0; i <= i1; ++i)
        if (auto it = grid.find(key(i, j)); it != grid.end())
          for (Index v : it->second) consider(v, s);
  }
  // Split each hit segment at its points, in order along it.
  std::map<std::size_t, std::vector<std::pair<double, Index>>> splits;
  for (const auto& [v, h] : hit)
    if (h.found) splits[h.seg].push_back({h.t, v});
  for (auto& [s, pts] : splits) {
    std::sort(pts.begin(), pts.end());
    const Segment orig = g.segments[s];
    Index prev = orig.a;
    for (std::size_t k = 0; k < pts.size(); ++k) {
      Segment piece = orig;
      piece.a = prev;
      piece.b = pts[k].second;
      if (k == 0) g.segments[s] = piece;
      else g.segments.push_back(piece);
      prev = pts[k].second;
      const double d = hit[pts[k].second].d;
      reps.push_back({"snap_to_segment", g.points[prev], d,
                      "a breakline end or fixed point lay " + num(d) +
                          " m from a boundary segment it did not touch; the segment was split there",
                      orig.part});
    }
    Segment last = orig;
    last.a = prev;
    g.segments.push_back(last);
  }
  return reps;
}

}  // namespace fdr::pslg
