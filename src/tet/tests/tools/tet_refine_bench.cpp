// Runs tet::tetrahedralize on the cube [0, s]^3 with a constant spacing and prints counts, splits,
// quality and time (not a test: it prints figures). Usage: tet_refine_bench SPACING [SIDE] [B]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <algorithm>
#include "sizing/spacing3d.hpp"
#include "tet/tetrahedralize.hpp"

int main(int argc, char** argv) {
  using namespace fdr;
  const double h = argc > 1 ? std::atof(argv[1]) : 0.5;
  const double side = argc > 2 ? std::atof(argv[2]) : 10;
  plc::Plc plc;
  for (int k = 0; k < 8; ++k) plc.points.push_back({(k & 1) ? side : 0, (k & 2) ? side : 0, (k & 4) ? side : 0});
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (int q = 0; q < 6; ++q) {
    plc::Facet f;
    f.polygons.push_back({VertexId(quads[q][0]), VertexId(quads[q][1]), VertexId(quads[q][2]), VertexId(quads[q][3])});
    f.marker = q + 1;
    plc.facets.push_back(f);
  }
  const sizing::ConstantField3 f(h);
  tet::TetOptions o;
  if (argc > 3) o.bound = std::atof(argv[3]);
  const auto t0 = std::chrono::steady_clock::now();
  const tet::TetResult r = tet::tetrahedralize(plc, f, o);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  double rf = 0, re = 0, md = 180;
  for (const auto& [n, v] : r.mesh.cell_fields) {
    const double mx = v.empty() ? 0 : *std::max_element(v.begin(), v.end());
    if (n == "r_over_f") rf = mx;
    if (n == "radius_edge") re = mx;
    if (n == "min_dihedral_deg" && !v.empty()) md = *std::min_element(v.begin(), v.end());
  }
  std::printf("h %g: %zu points %zu tets %zu faces; splits seg %zu facet %zu tet %zu rejected %zu capped %d "
              "shortfalls %zu; max R/f %.4f max R/l %.4f min dihedral %.2f; %.3f s\n",
              h, r.mesh.points.size(), r.mesh.tets.size(), r.mesh.faces.size(), r.stats.segment_splits,
              r.stats.facet_splits, r.stats.tet_splits, r.stats.rejected, int(r.stats.capped),
              r.stats.shortfalls.size(), rf, re, md, s);
  for (const auto& sf : r.stats.shortfalls)
    std::printf("  shortfall at (%g, %g, %g): %s\n", sf.where.x, sf.where.y, sf.where.z, sf.what.c_str());
  return 0;
}
