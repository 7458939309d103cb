// Test helper: the two counter-clockwise triangles of a grid cell.
#pragma once
#include "mesh/mesh_view.hpp"

namespace fdr::quality::test {

// Cell (i, j) of an n-wide row-major vertex grid, cut along the diagonal from its lower-left to its
// upper-right corner when `rise`, else along the other one.
inline void push_cell(mesh::MeshView& m, int n, int i, int j, bool rise) {
  auto id = [n](int a, int b) { return Index(b * n + a); };
  if (rise) {
    m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
    m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
  } else {
    m.triangles.push_back({id(i, j), id(i + 1, j), id(i, j + 1)});
    m.triangles.push_back({id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
  }
}

}  // namespace fdr::quality::test
