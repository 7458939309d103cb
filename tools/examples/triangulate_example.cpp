// Core API example: a PSLG built in code (unit square with a square hole) meshed by FDR against
// a spacing that grows away from the hole; prints the size and the quality of the result.
#include <cstdio>
#include "api/triangulate.hpp"

int main(int argc, char** argv) {
  fdr::Pslg g;
  if (argc > 1) {
    g = fdr::read_pslg(argv[1]);
  } else {
    g.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.4, 0.4}, {0.6, 0.4}, {0.6, 0.6}, {0.4, 0.6}};
    for (fdr::Index i = 0; i < 4; ++i) {
      g.segments.push_back({i, (i + 1) % 4, 1, 0});
      g.segments.push_back({4 + i, 4 + (i + 1) % 4, 2, 1});
    }
    g.holes = {{0.5, 0.5}};
  }
  try {
    fdr::TriangulateOptions o;
    o.bound = 1.0;
    o.check = true;
    const fdr::Mesh m = fdr::triangulate(g, fdr::make_spacing("0.01 + 0.1 * sqrt((x-0.5)^2 + (y-0.5)^2)"), o);
    std::printf("%zu vertices, %zu triangles, max R/f(c) %.3f, min angle %.1f deg\n", m.view.vertices.size(),
                m.view.triangles.size(), m.report.max_R_over_f.value_or(-1), m.report.min_angle_deg.value_or(-1));
    return m.report.bad_triangles.value_or(1) == 0 ? 0 : 1;
  } catch (const fdr::Error& e) {
    std::fprintf(stderr, "ERROR %d: %s\n", e.exit_code(), e.what());
    return e.exit_code();
  }
}
