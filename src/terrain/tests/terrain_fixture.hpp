// A small TIN for the terrain tests: a 3 x 3 lattice of vertices on [0, 2]^2, 8 triangles.
#pragma once
#include "terrain/surfaces.hpp"

namespace fdr::terrain::testing {

inline Tin lattice_tin() {
  Tin t;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) t.xy.push_back({static_cast<double>(i), static_cast<double>(j)});
  for (VertexId j = 0; j < 2; ++j)
    for (VertexId i = 0; i < 2; ++i) {
      const VertexId a = j * 3 + i, b = a + 1, c = a + 4, d = a + 3;
      t.triangles.push_back({a, b, c});
      t.triangles.push_back({a, c, d});
    }
  return t;
}

// z = c + sx x + sy y at every vertex of the TIN.
inline Surface plane(const Tin& tin, std::string name, double c, double sx = 0, double sy = 0) {
  Surface s{std::move(name), {}};
  for (const Point2 p : tin.xy) s.z.push_back(c + sx * p.x + sy * p.y);
  return s;
}

}  // namespace fdr::terrain::testing
