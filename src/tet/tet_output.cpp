#include "tet/tet_output.hpp"
#include <algorithm>
#include <cmath>
#include <numbers>
#include "tet/tet_geometry.hpp"

namespace fdr::tet {

double min_dihedral_deg(Point3 a, Point3 b, Point3 c, Point3 d) {
  const Point3 p[4] = {a, b, c, d};
  double best = 180;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) {
      int k = 0;
      while (k == i || k == j) ++k;
      const int l = 6 - i - j - k;
      // The normals of the two faces at edge ij, both taken as (edge) x (to the third corner),
      // make the same angle as the faces do.
      const Point3 e = p[j] - p[i];
      const Point3 n1 = cross(e, p[k] - p[i]), n2 = cross(e, p[l] - p[i]);
      const double den = std::sqrt(norm2(n1) * norm2(n2));
      if (!(den > 0)) return 0;
      const double cosv = std::clamp(dot(n1, n2) / den, -1.0, 1.0);
      best = std::min(best, std::acos(cosv) * 180 / std::numbers::pi);
    }
  return best;
}

TetMesh make_tet_mesh(const Refiner3& r, bool cell_fields) {
  const Delaunay3& dt = r.dt();
  const Boundary& bd = r.boundary();
  TetMesh m;
  // Room for every finite tetrahedron and vertex at once: grown by doubling, the arrays would
  // hold up to twice their size while the tetrahedralization is still alive beside them.
  const std::size_t most = dt.num_finite_tets();
  m.points.reserve(dt.num_vertices());
  m.tets.reserve(most);
  m.tet_material.reserve(most);
  std::vector<VertexId> out_id(dt.num_vertices(), kNoId);
  auto use = [&](VertexId v) {
    if (out_id[v] == kNoId) {
      out_id[v] = static_cast<VertexId>(m.points.size());
      m.points.push_back(dt.point(v));
    }
    return out_id[v];
  };
  std::vector<double> rf, re, md;
  if (cell_fields) {
    rf.reserve(most);
    re.reserve(most);
    md.reserve(most);
  }
  dt.for_each_finite_tet([&](TetId t) {
    if (r.region(t) == kOutsideRegion) return;
    const auto& v = dt.vertices(t);
    m.tets.push_back({use(v[0]), use(v[1]), use(v[2]), use(v[3])});
    m.tet_material.push_back(r.material(t));
    if (!cell_fields) return;
    const Point3 a = dt.point(v[0]), b = dt.point(v[1]), c = dt.point(v[2]), d = dt.point(v[3]);
    const Sphere s = circumsphere(a, b, c, d);
    rf.push_back(s.radius / r.spacing()(s.centre));
    re.push_back(s.radius / shortest_edge(a, b, c, d));
    md.push_back(min_dihedral_deg(a, b, c, d));
  });
  for (std::uint32_t t = 0; t < bd.tri_slots(); ++t) {
    const SubfacetTri& s = bd.tri(t);
    if (!s.alive) continue;
    m.faces.push_back({use(s.v[0]), use(s.v[1]), use(s.v[2])});
    m.face_marker.push_back(bd.facet_marker(s.facet));
  }
  std::vector<std::pair<std::array<VertexId, 2>, std::int32_t>> edges;
  bd.for_each_subsegment([&](VertexId a, VertexId b, std::uint32_t o) {
    const auto& fs = bd.origin(o).facets;
    edges.push_back({{a, b}, fs.empty() ? 0 : bd.facet_marker(fs[0])});
  });
  std::sort(edges.begin(), edges.end());  // the hash map's order is not the output's
  for (const auto& [e, mk] : edges) {
    m.edges.push_back({use(e[0]), use(e[1])});
    m.edge_marker.push_back(mk);
  }
  if (cell_fields) {
    m.cell_fields.push_back({"r_over_f", std::move(rf)});
    m.cell_fields.push_back({"radius_edge", std::move(re)});
    m.cell_fields.push_back({"min_dihedral_deg", std::move(md)});
  }
  m.marker_names = r.plc().marker_names;
  m.material_names = r.plc().material_names;
  return m;
}

}  // namespace fdr::tet
