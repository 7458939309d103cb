// Wells as vertical PLC segments and their spacing cap (wells.hpp).
#include "terrain/wells.hpp"
#include <algorithm>
#include <cmath>
#include <sstream>
#include "base/error.hpp"

namespace fdr::terrain {
namespace {

std::string m(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

// Squared distance from p to the segment ab.
double dist2_to_segment(const Point3& p, const Point3& a, const Point3& b) {
  const Point3 ab = b - a, ap = p - a;
  const double len2 = dot(ab, ab);
  double t = len2 > 0 ? dot(ap, ab) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  const Point3 q = a + t * ab;
  const Point3 d = p - q;
  return dot(d, d);
}

// A new vertex id on the vertical line of a TIN vertex: where it lies inside a vertical edge of a
// facet (a wall where a layer ends, over an edge of that TIN vertex), the facet takes it as a
// corner, so facets and segments meet at vertices only.
void split_vertical_edges(plc::Plc& p, VertexId id) {
  const Point3 q = p.points[id];
  for (plc::Facet& f : p.facets)
    for (auto& poly : f.polygons)
      for (std::size_t k = 0; k < poly.size(); ++k) {
        const Point3 a = p.points[poly[k]], b = p.points[poly[(k + 1) % poly.size()]];
        if (a.x == q.x && a.y == q.y && b.x == q.x && b.y == q.y && std::min(a.z, b.z) < q.z && q.z < std::max(a.z, b.z)) {
          poly.insert(poly.begin() + static_cast<std::ptrdiff_t>(k + 1), id);
          break;
        }
      }
}

}  // namespace

std::vector<double> column_at(const std::vector<Surface>& stack, VertexId v) {
  std::vector<double> c;
  c.reserve(stack.size());
  for (const Surface& s : stack) c.push_back(s.z.at(v));
  return c;
}

WellColumn place_well(const Well& w, VertexId tin_vertex, const std::vector<double>& column, double snap,
                      WellRepairs* repairs) {
  if (column.size() < 2) throw Error(ExitCode::kInternal, "place_well: a column needs a top and a base");
  const double top = column.front(), base = column.back();
  double hi = w.upper, lo = w.lower;
  if (w.kind == WellRangeKind::kDepth) hi = top - w.upper, lo = top - w.lower;
  if (!(std::isfinite(hi) && std::isfinite(lo)) || !(hi > lo))
    throw Error(ExitCode::kInvalidGeometry, w.where + ": the well's range is empty (upper end " + m(hi) +
                                                " m, lower end " + m(lo) + " m as elevations)");
  if (lo >= top || hi <= base)
    throw Error(ExitCode::kInvalidGeometry, w.where + ": the well (elevations " + m(lo) + " to " + m(hi) +
                                                " m) lies outside the volume there (base " + m(base) + " m, top " +
                                                m(top) + " m)");
  WellRepairs rep;
  if (hi > top) hi = top, rep.clipped_top = true;
  if (lo < base) lo = base, rep.clipped_base = true;
  // An end near a surface moves onto it: a gap of a few metres between a well's end and a horizon
  // would force tetrahedra that small there.
  auto snap_end = [&](double z) {
    for (const double s : column)
      if (z != s && std::abs(z - s) < snap) {
        ++rep.snapped;
        return s;
      }
    return z;
  };
  hi = snap_end(hi);
  lo = snap_end(lo);
  if (!(hi > lo))  // both ends onto one surface: the well is shorter than the snap distance
    throw Error(ExitCode::kInvalidGeometry, w.where + ": the well is shorter than " + m(snap) +
                                                " m inside the volume (elevations " + m(lo) + " to " + m(hi) + " m)");
  if (repairs) *repairs = rep;
  return {w.name, tin_vertex, hi, lo};
}

std::vector<std::vector<VertexId>> add_well_segments(TerrainPlc& tp, const Tin& tin, const std::vector<Surface>& stack,
                                                     const std::vector<WellColumn>& wells) {
  plc::Plc& p = tp.plc;
  std::vector<std::uint8_t> on_boundary(tin.xy.size(), 0);
  for (const auto& e : boundary_edges(tin)) on_boundary[e[0]] = on_boundary[e[1]] = 1;
  std::vector<std::vector<VertexId>> chains;
  for (const WellColumn& w : wells) {
    const VertexId v = w.tin_vertex;
    if (on_boundary.at(v))
      throw Error(ExitCode::kInvalidGeometry, "well " + w.name + " lies on the domain's boundary (in a side wall)");
    std::vector<VertexId> chain;
    auto push = [&](VertexId id) {
      if (chain.empty() || chain.back() != id) chain.push_back(id);
    };
    // The end at z: the surface vertex there when one lies exactly at z, else a new vertex.
    auto end_vertex = [&](double z) {
      for (std::size_t s = 0; s < stack.size(); ++s)
        if (stack[s].z[v] == z && tp.ids[s][v] != kNoVertex) return tp.ids[s][v];
      p.points.push_back({tin.xy[v].x, tin.xy[v].y, z});
      const auto id = static_cast<VertexId>(p.points.size() - 1);
      split_vertical_edges(p, id);
      return id;
    };
    push(end_vertex(w.hi));
    for (std::size_t s = 0; s < stack.size(); ++s)
      if (stack[s].z[v] < w.hi && stack[s].z[v] > w.lo && tp.ids[s][v] != kNoVertex) push(tp.ids[s][v]);
    push(end_vertex(w.lo));
    for (std::size_t k = 0; k + 1 < chain.size(); ++k) p.segments.push_back({chain[k], chain[k + 1]});
    chains.push_back(std::move(chain));
  }
  return chains;
}

void cap_near_segments(sizing::Grid3& g, const std::vector<std::array<Point3, 2>>& segments, double h) {
  if (!(h > 0)) throw Error(ExitCode::kUsage, "the spacing near wells must be positive");
  const double reach = std::sqrt(g.dx * g.dx + g.dy * g.dy + g.dz * g.dz);
  auto range = [](double lo, double hi, double o, double d, std::size_t n, std::size_t& a, std::size_t& b) {
    // Cells whose centre o + (i + 0.5) d lies in [lo, hi].
    const double fa = std::ceil((lo - o) / d - 0.5), fb = std::floor((hi - o) / d - 0.5);
    a = static_cast<std::size_t>(std::clamp(fa, 0.0, static_cast<double>(n - 1)));
    b = static_cast<std::size_t>(std::clamp(fb, 0.0, static_cast<double>(n - 1)));
  };
  for (const auto& [a, b] : segments) {
    std::size_t i0, i1, j0, j1, k0, k1;
    range(std::min(a.x, b.x) - reach, std::max(a.x, b.x) + reach, g.x0, g.dx, g.nx, i0, i1);
    range(std::min(a.y, b.y) - reach, std::max(a.y, b.y) + reach, g.y0, g.dy, g.ny, j0, j1);
    range(std::min(a.z, b.z) - reach, std::max(a.z, b.z) + reach, g.z0, g.dz, g.nz, k0, k1);
    for (std::size_t k = k0; k <= k1; ++k)
      for (std::size_t j = j0; j <= j1; ++j)
        for (std::size_t i = i0; i <= i1; ++i)
          if (dist2_to_segment(g.center(i, j, k), a, b) <= reach * reach) g.at(i, j, k) = std::min(g.at(i, j, k), h);
  }
}

}  // namespace fdr::terrain
