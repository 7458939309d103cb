// bench_api SPACING [REPEATS]: best wall and CPU time of fdr::triangulate on the unit square (the input
// of bench_python.py), with the triangle count.
#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include "api/triangulate.hpp"

int main(int argc, char** argv) {
  const std::string spec = argc > 1 ? argv[1] : "0.0011";
  const int repeats = argc > 2 ? std::atoi(argv[2]) : 3;
  fdr::Pslg g;
  g.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (fdr::Index i = 0; i < 4; ++i) g.segments.push_back({i, (i + 1) % 4, 0, -1});
  double best = 1e300, best_cpu = 1e300;
  std::size_t tris = 0;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::clock_t c0 = std::clock();
    const fdr::Mesh m = fdr::triangulate(g, fdr::make_spacing(spec));
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    best = std::min(best, s);
    best_cpu = std::min(best_cpu, double(std::clock() - c0) / CLOCKS_PER_SEC);
    tris = m.view.triangles.size();
  }
  std::printf("cpp_s=%.4f cpp_cpu_s=%.4f triangles=%zu\n", best, best_cpu, tris);
  return 0;
}
