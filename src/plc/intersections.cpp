// Facet intersection check: box intersection for candidates, exact CGAL tests per pair.
#include "plc/intersections.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <tuple>

#include "base/error.hpp"
#include "plc/facet_frame.hpp"
#include "predicates/predicates3d.hpp"

namespace fdr::plc {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::size_t>;

K::Point_3 cg(Point3 p) { return {p.x, p.y, p.z}; }

K::Triangle_3 cg_triangle(const Plc& plc, const Triangle& t) {
  return {cg(plc.points[t[0]]), cg(plc.points[t[1]]), cg(plc.points[t[2]])};
}

K::Segment_3 cg_segment(const Plc& plc, VertexId a, VertexId b) { return {cg(plc.points[a]), cg(plc.points[b])}; }

Box box_of(const Plc& plc, const VertexId* v, int n, std::size_t info) {
  double lo[3], hi[3];
  for (int k = 0; k < 3; ++k) lo[k] = hi[k] = 0;
  for (int i = 0; i < n; ++i) {
    const Point3 p = plc.points[v[i]];
    const double c[3] = {p.x, p.y, p.z};
    for (int k = 0; k < 3; ++k) {
      lo[k] = i == 0 ? c[k] : std::min(lo[k], c[k]);
      hi[k] = i == 0 ? c[k] : std::max(hi[k], c[k]);
    }
  }
  return Box(lo, hi, info);
}

std::string triangle_text(const Triangle& t) {
  return "triangle " + std::to_string(t[0]) + "-" + std::to_string(t[1]) + "-" + std::to_string(t[2]);
}

// Free segments against each other: the first bad pair in index order.
void check_segment_pairs(const Plc& plc, std::vector<Box> boxes);

}  // namespace

bool improper_triangle_pair(const Plc& plc, const Triangle& s, const Triangle& t) {
  const auto& P = plc.points;
  int shared = 0, si[3] = {-1, -1, -1};  // si[i]: the corner of t equal to corner i of s
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (s[i] == t[j]) si[i] = j, ++shared;
  if (shared == 3) return true;
  if (shared == 0) return CGAL::do_intersect(cg_triangle(plc, s), cg_triangle(plc, t));
  if (shared == 2) {
    // Apart from their edge, two triangles on one edge meet only when coplanar and on one side.
    const int i = si[0] < 0 ? 0 : si[1] < 0 ? 1 : 2;  // s's corner off the shared edge
    int j = 0;
    while (t[j] == s[(i + 1) % 3] || t[j] == s[(i + 2) % 3]) ++j;
    const Point3 u = P[s[(i + 1) % 3]], v = P[s[(i + 2) % 3]], a = P[s[i]], b = P[t[j]];
    if (predicates::orient3d(u, v, a, b) != 0) return false;
    return side_in_plane(u, v, a, b) > 0;
  }
  // One shared vertex: the intersection beyond it must reach an opposite edge.
  const int i = si[0] >= 0 ? 0 : si[1] >= 0 ? 1 : 2, j = si[i];
  const auto s_opp = cg_segment(plc, s[(i + 1) % 3], s[(i + 2) % 3]);
  const auto t_opp = cg_segment(plc, t[(j + 1) % 3], t[(j + 2) % 3]);
  return CGAL::do_intersect(s_opp, cg_triangle(plc, t)) || CGAL::do_intersect(t_opp, cg_triangle(plc, s));
}

bool improper_segment_triangle(const Plc& plc, const Edge& s, const Triangle& t) {
  const auto& P = plc.points;
  int shared = 0, at = -1, end = -1;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 3; ++j)
      if (s[i] == t[j]) ++shared, end = i, at = j;
  if (shared == 2) return false;
  if (shared == 0) return CGAL::do_intersect(cg_segment(plc, s[0], s[1]), cg_triangle(plc, t));
  // From the shared vertex the segment leaves the plane unless it lies in it.
  const Point3 q = P[s[1 - end]];
  if (predicates::orient3d(P[t[0]], P[t[1]], P[t[2]], q) != 0) return false;
  const auto opp = cg_segment(plc, t[(at + 1) % 3], t[(at + 2) % 3]);
  return CGAL::do_intersect(cg_segment(plc, s[0], s[1]), opp) ||
         CGAL::do_intersect(cg(q), cg_triangle(plc, t));
}

bool improper_segment_pair(const Plc& plc, const Edge& s, const Edge& t) {
  const auto& P = plc.points;
  const int shared = (s[0] == t[0]) + (s[0] == t[1]) + (s[1] == t[0]) + (s[1] == t[1]);
  if (shared == 2) return true;  // the same segment twice
  if (shared == 0) return CGAL::do_intersect(cg_segment(plc, s[0], s[1]), cg_segment(plc, t[0], t[1]));
  // One common end v: they overlap only when collinear and on the same side of v.
  const VertexId v = (s[0] == t[0] || s[0] == t[1]) ? s[0] : s[1];
  const Point3 a = P[s[0] == v ? s[1] : s[0]], b = P[t[0] == v ? t[1] : t[0]];
  return collinear(P[v], a, b) && dot(a - P[v], b - P[v]) > 0;
}

void check_intersections(const Plc& plc, const FacetTriangulation& ft) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> tri_at;  // box info -> (facet, triangle)
  std::vector<Box> boxes;
  for (std::size_t f = 0; f < ft.triangles.size(); ++f)
    for (std::size_t k = 0; k < ft.triangles[f].size(); ++k) {
      boxes.push_back(box_of(plc, ft.triangles[f][k].data(), 3, tri_at.size()));
      tri_at.emplace_back(static_cast<std::uint32_t>(f), static_cast<std::uint32_t>(k));
    }
  using Bad = std::tuple<std::size_t, std::size_t, std::size_t, std::size_t>;  // facet, tri, facet, tri
  bool found = false;
  Bad first{};
  auto note = [&](Bad b) {
    if (!found || b < first) first = b, found = true;
  };
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& x, const Box& y) {
    auto [fa, ka] = tri_at[x.info()];
    auto [fb, kb] = tri_at[y.info()];
    if (fa == fb) return;
    if (std::tie(fb, kb) < std::tie(fa, ka)) std::swap(fa, fb), std::swap(ka, kb);
    if (improper_triangle_pair(plc, ft.triangles[fa][ka], ft.triangles[fb][kb])) note({fa, ka, fb, kb});
  });
  if (found) {
    const auto [fa, ka, fb, kb] = first;
    const Triangle& s = ft.triangles[fa][ka];
    const Triangle& t = ft.triangles[fb][kb];
    throw Error(ExitCode::kInvalidGeometry,
                facet_label(plc, fa) + " and facet " + std::to_string(fb) + " (marker " +
                    std::to_string(plc.facets[fb].marker) + ") intersect other than in shared vertices and polygon "
                    "edges: " + triangle_text(s) + " near " + point_text(plc.points[s[0]]) + " meets " +
                    triangle_text(t) + " near " + point_text(plc.points[t[0]]) +
                    " (a shared edge must be a polygon edge of both facets)");
  }
  if (plc.segments.empty()) return;
  std::vector<Box> seg_boxes;
  for (std::size_t s = 0; s < plc.segments.size(); ++s) seg_boxes.push_back(box_of(plc, plc.segments[s].data(), 2, s));
  check_segment_pairs(plc, seg_boxes);
  if (boxes.empty()) return;
  std::tuple<std::size_t, std::size_t, std::size_t> first_seg{};  // segment, facet, triangle
  CGAL::box_intersection_d(seg_boxes.begin(), seg_boxes.end(), boxes.begin(), boxes.end(),
                           [&](const Box& x, const Box& y) {
                             const auto& seg = plc.segments[x.info()];
                             const auto [f, k] = tri_at[y.info()];
                             const std::tuple<std::size_t, std::size_t, std::size_t> key{x.info(), f, k};
                             if ((found && !(key < first_seg)) ||
                                 !improper_segment_triangle(plc, {seg[0], seg[1]}, ft.triangles[f][k]))
                               return;
                             first_seg = key, found = true;
                           });
  if (found) {
    const auto [s, f, k] = first_seg;
    const auto& seg = plc.segments[s];
    throw Error(ExitCode::kInvalidGeometry,
                (plc.source.empty() ? std::string("input") : plc.source) + ": segment " + std::to_string(s) + " " +
                    std::to_string(seg[0]) + "-" + std::to_string(seg[1]) + " from " + point_text(plc.points[seg[0]]) +
                    " meets facet " + std::to_string(f) + " (marker " + std::to_string(plc.facets[f].marker) +
                    ") other than at a shared vertex: " + triangle_text(ft.triangles[f][k]) + " near " +
                    point_text(plc.points[ft.triangles[f][k][0]]));
  }
}

namespace {

void check_segment_pairs(const Plc& plc, std::vector<Box> boxes) {
  bool found = false;
  std::pair<std::size_t, std::size_t> first{};
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& x, const Box& y) {
    const std::pair<std::size_t, std::size_t> key{std::min(x.info(), y.info()), std::max(x.info(), y.info())};
    const auto& s = plc.segments[key.first];
    const auto& t = plc.segments[key.second];
    if ((found && !(key < first)) || !improper_segment_pair(plc, {s[0], s[1]}, {t[0], t[1]})) return;
    first = key, found = true;
  });
  if (!found) return;
  const auto& s = plc.segments[first.first];
  const auto& t = plc.segments[first.second];
  throw Error(ExitCode::kInvalidGeometry,
              (plc.source.empty() ? std::string("input") : plc.source) + ": segment " + std::to_string(first.first) +
                  " " + std::to_string(s[0]) + "-" + std::to_string(s[1]) + " from " + point_text(plc.points[s[0]]) +
                  " meets segment " + std::to_string(first.second) + " " + std::to_string(t[0]) + "-" +
                  std::to_string(t[1]) + " from " + point_text(plc.points[t[0]]) + " other than at a shared end");
}

}  // namespace

}  // namespace fdr::plc
