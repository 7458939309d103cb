// api_dump POLY SPACING [BOUND]: meshes a .poly with fdr::triangulate and prints the vertices
// (world coordinates, 17 significant digits) and triangles, for the CLI/C++/Python comparison.
#include <cstdio>
#include <cstdlib>
#include "api/triangulate.hpp"

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: api_dump POLY SPACING [BOUND]\n");
    return 2;
  }
  try {
    const fdr::Pslg g = fdr::read_pslg(argv[1]);
    fdr::TriangulateOptions o;
    if (argc > 3) o.bound = std::atof(argv[3]);
    const fdr::Mesh m = fdr::triangulate(g, fdr::make_spacing(argv[2]), o);
    std::printf("%zu %zu\n", m.view.vertices.size(), m.view.triangles.size());
    for (std::size_t i = 0; i < m.view.vertices.size(); ++i) {
      const fdr::Point2 w = m.view.world(static_cast<fdr::Index>(i));
      std::printf("%.17g %.17g\n", w.x, w.y);
    }
    for (const auto& t : m.view.triangles) std::printf("%u %u %u\n", unsigned(t[0]), unsigned(t[1]), unsigned(t[2]));
  } catch (const fdr::Error& e) {
    std::fprintf(stderr, "ERROR %d: %s\n", e.exit_code(), e.what());
    return e.exit_code();
  }
  return 0;
}
