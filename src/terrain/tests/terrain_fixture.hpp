// A small TIN for the terrain tests: a lattice of nx x ny vertices at integer points from the
// origin (3 x 3: [0, 2]^2, 8 triangles), each square cut along its rising diagonal.
#pragma once
#include <string>
#include <utility>
#include "terrain/surfaces.hpp"

namespace fdr::terrain::testing {

inline Tin lattice_tin(int nx = 3, int ny = 3) {
  Tin t;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) t.xy.push_back({static_cast<double>(i), static_cast<double>(j)});
  const auto w = static_cast<VertexId>(nx);
  for (VertexId j = 0; j + 1 < static_cast<VertexId>(ny); ++j)
    for (VertexId i = 0; i + 1 < w; ++i) {
      const VertexId a = j * w + i, b = a + 1, c = a + w + 1, d = a + w;
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
