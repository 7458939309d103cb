// PLC checks: points, ids, polygons, planarity; then the triangulation-based checks in order.
#include "plc/check.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "base/error.hpp"
#include "plc/cells.hpp"
#include "plc/facet_frame.hpp"
#include "plc/intersections.hpp"
#include "predicates/predicates3d.hpp"

namespace fdr::plc {

namespace {

std::string source_of(const Plc& plc) { return plc.source.empty() ? std::string("input") : plc.source; }

std::string vertex_text(const Plc& plc, VertexId v) {
  return "vertex " + std::to_string(v) + " " + point_text(plc.points[v]);
}

}  // namespace

void check_points(const Plc& plc) {
  const auto& P = plc.points;
  for (std::size_t i = 0; i < P.size(); ++i)
    if (!std::isfinite(P[i].x) || !std::isfinite(P[i].y) || !std::isfinite(P[i].z))
      throw Error(ExitCode::kInvalidGeometry, source_of(plc) + ": vertex " + std::to_string(i) + " " +
                                                  point_text(P[i]) + " has a non-finite coordinate");
  for (std::size_t h = 0; h < plc.holes.size(); ++h) {
    const Point3 q = plc.holes[h];
    if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
      throw Error(ExitCode::kInvalidGeometry, source_of(plc) + ": volume hole point " + std::to_string(h) + " " +
                                                  point_text(q) + " has a non-finite coordinate");
  }
  for (std::size_t r = 0; r < plc.regions.size(); ++r) {
    const Point3 q = plc.regions[r].point;
    if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z) || !std::isfinite(plc.regions[r].attribute) ||
        std::isnan(plc.regions[r].max_volume))
      throw Error(ExitCode::kInvalidGeometry, source_of(plc) + ": region point " + std::to_string(r) + " " +
                                                  point_text(q) +
                                                  " has a non-finite coordinate, attribute or volume bound");
  }
  std::vector<VertexId> order(P.size());
  std::iota(order.begin(), order.end(), VertexId{0});
  auto less = [&](VertexId a, VertexId b) {
    if (P[a].x != P[b].x) return P[a].x < P[b].x;
    if (P[a].y != P[b].y) return P[a].y < P[b].y;
    if (P[a].z != P[b].z) return P[a].z < P[b].z;
    return a < b;
  };
  std::sort(order.begin(), order.end(), less);
  for (std::size_t k = 1; k < order.size(); ++k)
    if (P[order[k]] == P[order[k - 1]])
      throw Error(ExitCode::kInvalidGeometry, source_of(plc) + ": vertex " + std::to_string(order[k]) +
                                                  " and vertex " + std::to_string(order[k - 1]) +
                                                  " coincide at " + point_text(P[order[k]]));
}

void check_ids_and_polygons(const Plc& plc) {
  const std::size_t n = plc.points.size();
  if (!plc.point_markers.empty() && plc.point_markers.size() != n)
    throw Error(ExitCode::kInputMalformed, source_of(plc) + ": " + std::to_string(plc.point_markers.size()) +
                                               " point markers for " + std::to_string(n) + " points");
  for (std::size_t f = 0; f < plc.facets.size(); ++f) {
    const Facet& facet = plc.facets[f];
    if (facet.polygons.empty())
      throw Error(ExitCode::kInvalidGeometry, facet_label(plc, f) + " has no polygons");
    for (std::size_t p = 0; p < facet.polygons.size(); ++p) {
      const auto& poly = facet.polygons[p];
      const std::string where = facet_label(plc, f) + " polygon " + std::to_string(p);
      for (VertexId v : poly)
        if (v >= n)
          throw Error(ExitCode::kInputMalformed, where + ": vertex id " + std::to_string(v) + " out of range (" +
                                                     std::to_string(n) + " points)");
      if (poly.empty()) throw Error(ExitCode::kInvalidGeometry, where + " has no vertices");
      for (std::size_t i = 0; poly.size() >= 2 && i < poly.size(); ++i) {
        const VertexId a = poly[i], b = poly[(i + 1) % poly.size()];
        if (a == b && (i + 1 < poly.size() || poly.size() > 2))
          throw Error(ExitCode::kInvalidGeometry, where + " is degenerate: " + vertex_text(plc, a) +
                                                      " repeats consecutively");
      }
      if (poly.size() >= 3) {
        bool flat = true;
        for (std::size_t i = 2; i < poly.size() && flat; ++i)
          flat = collinear(plc.points[poly[0]], plc.points[poly[1]], plc.points[poly[i]]);
        if (flat)
          throw Error(ExitCode::kInvalidGeometry, where + " is degenerate: its " + std::to_string(poly.size()) +
                                                      " vertices lie on one line (from " + vertex_text(plc, poly[0]) +
                                                      ")");
      }
    }
  }
  for (std::size_t s = 0; s < plc.segments.size(); ++s) {
    const auto& seg = plc.segments[s];
    const std::string where = source_of(plc) + ": segment " + std::to_string(s);
    for (VertexId v : seg)
      if (v >= n)
        throw Error(ExitCode::kInputMalformed, where + ": vertex id " + std::to_string(v) + " out of range (" +
                                                   std::to_string(n) + " points)");
    if (seg[0] == seg[1])
      throw Error(ExitCode::kInvalidGeometry, where + " is degenerate: both ends are " + vertex_text(plc, seg[0]));
  }
}

void check_planarity(const Plc& plc) {
  for (std::size_t f = 0; f < plc.facets.size(); ++f) {
    const FacetFrame fr = facet_frame(plc, f);
    const Point3 a = plc.points[fr.p0], b = plc.points[fr.p1], c = plc.points[fr.p2];
    Box3 box;
    for (const auto& poly : plc.facets[f].polygons)
      for (VertexId v : poly) {
        box.add(plc.points[v]);
        if (predicates::orient3d(a, b, c, plc.points[v]) != 0)
          throw Error(ExitCode::kInvalidGeometry,
                      facet_label(plc, f) + " is not planar: " + vertex_text(plc, v) +
                          " lies off the plane through vertices " + std::to_string(fr.p0) + ", " +
                          std::to_string(fr.p1) + " and " + std::to_string(fr.p2));
      }
    const Point3 n = cross(b - a, c - a);
    const double extent = dist(box.lo, box.hi), nn = std::sqrt(norm2(n));
    const auto& holes = plc.facets[f].holes;
    for (std::size_t h = 0; h < holes.size(); ++h) {
      const Point3 q = holes[h];
      const bool finite = std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z);
      if (finite && (predicates::orient3d(a, b, c, q) == 0 || std::abs(dot(q - a, n)) / nn <= 1e-6 * extent))
        continue;
      throw Error(ExitCode::kInvalidGeometry, facet_label(plc, f) + ": hole point " + std::to_string(h) + " " +
                                                  point_text(q) + " is not in the facet's plane");
    }
  }
}

FacetTriangulation check_and_triangulate(const Plc& plc, const CheckOptions& opt) {
  check_points(plc);
  check_ids_and_polygons(plc);
  check_planarity(plc);
  FacetTriangulation ft = triangulate_facets(plc);
  check_intersections(plc, ft);
  if (opt.closed) {
    SurfaceCells cells(plc, ft);
    cells.check_closed();
    cells.check_volume_points();
  }
  return ft;
}

void check(const Plc& plc, const CheckOptions& opt) { (void)check_and_triangulate(plc, opt); }

}  // namespace fdr::plc
