// Facet triangulation: the 2D CDT in a coordinate projection, then Delaunay flips in the true plane.
#include "plc/triangulate_facets.hpp"

#include <algorithm>
#include <map>

#include "base/error.hpp"
#include "cdt/cdt.hpp"

namespace fdr::plc {

namespace {

Edge edge_of(VertexId a, VertexId b) { return a < b ? Edge{a, b} : Edge{b, a}; }

const char* plane_name(int axis) { return axis == 0 ? "yz" : axis == 1 ? "zx" : "xy"; }

}  // namespace

std::vector<Triangle> triangulate_in_projection(const Plc& plc, std::size_t f, const FacetFrame& frame,
                                                std::vector<Edge>& constrained) {
  const Facet& facet = plc.facets[f];
  // Local numbering: the facet's distinct vertices in increasing id order.
  std::vector<VertexId> ids;
  for (const auto& poly : facet.polygons) ids.insert(ids.end(), poly.begin(), poly.end());
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  auto local = [&](VertexId v) {
    return static_cast<Index>(std::lower_bound(ids.begin(), ids.end(), v) - ids.begin());
  };
  pslg::Pslg in;
  for (VertexId v : ids) in.points.push_back(project(plc.points[v], frame.drop_axis));
  for (const auto& poly : facet.polygons) {
    const std::size_t n = poly.size();
    if (n < 2) continue;
    for (std::size_t i = 0; i < (n == 2 ? 1 : n); ++i)
      in.segments.push_back({local(poly[i]), local(poly[(i + 1) % n]), 0, -1});
  }
  for (Point3 h : facet.holes) in.holes.push_back(project(h, frame.drop_axis));
  cdt::CdtOptions opt;
  opt.regions = cdt::CdtOptions::Regions::kSeeds;
  opt.source = facet_label(plc, f) + " (projected onto the " + plane_name(frame.drop_axis) + " plane)";
  const mesh::Triangulation T = cdt::build_cdt(in, opt);
  std::vector<Triangle> tris;
  constrained.clear();
  for (TriangleId t = 0; t < T.num_slots(); ++t) {
    if (T.dead(t)) continue;
    Triangle tri;
    for (int k = 0; k < 3; ++k) {
      const Index c = T.corner(t, k);
      if (c >= ids.size()) throw Error(ExitCode::kInternal, opt.source + ": a triangle kept a vertex of its own");
      tri[static_cast<std::size_t>(k)] = ids[c];
    }
    tris.push_back(tri);
    for (int k = 0; k < 3; ++k)
      if (T.constrained(3 * t + static_cast<Index>(k))) constrained.push_back(edge_of(tri[k], tri[(k + 1) % 3]));
  }
  std::sort(constrained.begin(), constrained.end());
  constrained.erase(std::unique(constrained.begin(), constrained.end()), constrained.end());
  return tris;
}

void make_delaunay_in_plane(const Plc& plc, const FacetFrame& frame, const std::vector<Edge>& constrained,
                            std::vector<Triangle>& tris) {
  // Directed edge (u, v) -> the triangle holding it.
  auto key = [](VertexId u, VertexId v) { return Edge{u, v}; };
  std::map<Edge, std::size_t> owner;
  auto link = [&](std::size_t t) {
    for (int k = 0; k < 3; ++k) owner[key(tris[t][k], tris[t][(k + 1) % 3])] = t;
  };
  for (std::size_t t = 0; t < tris.size(); ++t) link(t);
  auto is_constrained = [&](VertexId u, VertexId v) {
    return std::binary_search(constrained.begin(), constrained.end(), edge_of(u, v));
  };
  std::vector<Edge> stack;
  for (const Triangle& t : tris)
    for (int k = 0; k < 3; ++k)
      if (t[k] < t[(k + 1) % 3]) stack.push_back({t[k], t[(k + 1) % 3]});
  const Point3 q = frame.off_plane;
  // Why a guard: Lawson's flips end (each lowers the lifted surface); a runaway loop is a bug.
  std::size_t guard = 0;
  const std::size_t max_flips = 4 * tris.size() * tris.size() + 16;
  while (!stack.empty()) {
    const Edge e = stack.back();
    stack.pop_back();
    if (is_constrained(e[0], e[1])) continue;
    const auto i1 = owner.find(key(e[0], e[1])), i2 = owner.find(key(e[1], e[0]));
    if (i1 == owner.end() || i2 == owner.end()) continue;  // on the facet's boundary
    const std::size_t t1 = i1->second, t2 = i2->second;
    // t1 = (u, v, c), t2 = (v, u, d), both counter-clockwise in the projection.
    int k1 = 0, k2 = 0;
    while (tris[t1][k1] != e[0]) ++k1;
    while (tris[t2][k2] != e[1]) ++k2;
    const VertexId u = e[0], v = e[1], c = tris[t1][(k1 + 2) % 3], d = tris[t2][(k2 + 2) % 3];
    const auto& P = plc.points;
    if (incircle_in_plane(P[u], P[v], P[c], P[d], q) <= 0) continue;
    if (++guard > max_flips)
      throw Error(ExitCode::kInternal, "facet through vertices " + std::to_string(frame.p0) + ", " +
                                           std::to_string(frame.p1) + ", " + std::to_string(frame.p2) +
                                           ": in-plane Delaunay flips did not finish");
    owner.erase(key(u, v));
    owner.erase(key(v, u));
    tris[t1] = {u, d, c};
    tris[t2] = {d, v, c};
    link(t1);
    link(t2);
    for (const Edge& n : {edge_of(u, d), edge_of(d, v), edge_of(v, c), edge_of(c, u)}) stack.push_back(n);
  }
}

FacetTriangulation triangulate_facets(const Plc& plc) {
  FacetTriangulation out;
  out.triangles.resize(plc.facets.size());
  std::map<Edge, std::vector<std::uint32_t>> shared;
  std::vector<Edge> constrained;
  for (std::size_t f = 0; f < plc.facets.size(); ++f) {
    const FacetFrame frame = facet_frame(plc, f);
    std::vector<Triangle> tris = triangulate_in_projection(plc, f, frame, constrained);
    if (tris.empty())
      throw Error(ExitCode::kInvalidGeometry, facet_label(plc, f) + " has no area: its polygons enclose no region "
                                                                    "(or its hole points remove all of it)");
    // A facet perpendicular to the dropped axis projects isometrically: its 2D CDT, decided by the
    // same exact incircle, is already Delaunay in its plane.
    auto along = [&](VertexId v) {
      const Point3 q = plc.points[v];
      return frame.drop_axis == 0 ? q.x : frame.drop_axis == 1 ? q.y : q.z;
    };
    if (along(frame.p0) != along(frame.p1) || along(frame.p0) != along(frame.p2))
      make_delaunay_in_plane(plc, frame, constrained, tris);
    if (frame.flip)
      for (Triangle& t : tris) std::swap(t[1], t[2]);
    out.triangles[f] = std::move(tris);
    out.frames.push_back(frame);
    for (const Edge& e : constrained) shared[e].push_back(static_cast<std::uint32_t>(f));
  }
  for (const auto& s : plc.segments) shared.try_emplace(edge_of(s[0], s[1]));
  out.subsegments.reserve(shared.size());
  for (auto& [e, facets] : shared) out.subsegments.push_back({e[0], e[1], std::move(facets)});
  return out;
}

}  // namespace fdr::plc
