// A hand-made tetrahedral mesh for the writer tests: the unit cube split into six tetrahedra
// around its diagonal (0,0,0)-(1,1,1), with its 12 boundary triangles marked by side.
#pragma once
#include <algorithm>
#include <map>
#include "tet/tet_mesh.hpp"

namespace fdr::tetio::testing {

inline double volume6(const tet::TetMesh& m, const std::array<VertexId, 4>& t) {
  const Point3 a = m.points[t[0]];
  return dot(m.points[t[1]] - a, cross(m.points[t[2]] - a, m.points[t[3]] - a));
}

// Points v = i + 2j + 4k at (i, j, k); materials 1 (x-first paths) and 2; faces with markers 1..6
// for x=0, x=1, y=0, y=1, z=0, z=1; cell fields "r_over_f" and "radius_edge".
inline tet::TetMesh cube_mesh() {
  tet::TetMesh m;
  for (int v = 0; v < 8; ++v) m.points.push_back({double(v & 1), double((v >> 1) & 1), double((v >> 2) & 1)});
  const int axes[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (const auto& a : axes) {
    std::array<VertexId, 4> t{0, VertexId(1 << a[0]), VertexId((1 << a[0]) | (1 << a[1])), 7};
    if (volume6(m, t) < 0) std::swap(t[0], t[1]);
    m.tets.push_back(t);
    m.tet_material.push_back(a[0] == 0 ? 1 : 2);
  }
  std::map<std::array<VertexId, 3>, int> uses;
  for (const auto& t : m.tets) {
    for (int skip = 0; skip < 4; ++skip) {
      std::array<VertexId, 3> f{};
      for (int k = 0, j = 0; k < 4; ++k) {
        if (k != skip) f[j++] = t[k];
      }
      std::sort(f.begin(), f.end());
      ++uses[f];
    }
  }
  for (const auto& [f, n] : uses) {
    if (n != 1) continue;
    m.faces.push_back(f);
    const Point3 c = (1.0 / 3) * (m.points[f[0]] + m.points[f[1]] + m.points[f[2]]);
    const int marker = c.x == 0 ? 1 : c.x == 1 ? 2 : c.y == 0 ? 3 : c.y == 1 ? 4 : c.z == 0 ? 5 : 6;
    m.face_marker.push_back(marker);
  }
  m.edges.push_back({0, 7});
  m.edge_marker.push_back(9);
  m.cell_fields.push_back({"r_over_f", {0.5, 0.25, 0.125, 1.5, 2.5, 1e-300}});
  m.cell_fields.push_back({"radius_edge", {0.866, 0.866, 0.866, 0.866, 0.866, 0.866}});
  m.material_names = {"", "upper", "lower"};
  m.marker_names = {"", "west", "east"};
  return m;
}

}  // namespace fdr::tetio::testing
