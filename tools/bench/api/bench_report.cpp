// bench_report K [REPEATS]: the quality report alone (quality::compute_quality, as the command line
// runs it after a .poly mesh) on the square [0,10]^2 meshed with f = K*paper-f1, B = 1; prints the
// best and the median wall and process CPU time of REPEATS reports of the same mesh and its triangle count. Why: the
// report is a fifth of the command line's whole run, and the whole process is too noisy on a
// shared host to compare two versions of it.
#include <algorithm>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>
#include "api/core_stages.hpp"
#include "api/triangulate.hpp"
#include "mesh/take_view.hpp"

int main(int argc, char** argv) {
  const std::string k = argc > 1 ? argv[1] : "0.025";
  const int repeats = argc > 2 ? std::max(1, std::atoi(argv[2])) : 11;
  fdr::Pslg g;
  g.points = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  for (fdr::Index i = 0; i < 4; ++i) g.segments.push_back({i, (i + 1) % 4, 0, -1});
  const fdr::Pslg local = fdr::to_local_frame(g);
  const auto f = fdr::spacing_in_frame(k + "*paper-f1", local.origin);
  fdr::mesh::Triangulation tri = fdr::build_cdt(local, "square", nullptr, fdr::poly_regions(local, false));
  fdr::TriangulateOptions to;
  const fdr::RefineOutcome out = fdr::refine_stage(tri, *f, local.bbox(), to);
  const fdr::mesh::MeshView view = fdr::mesh::take_view(tri);
  std::vector<double> s, cpu;
  double check = 0;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    timespec c0, c1;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &c0);
    std::vector<double> fv;  // f at the vertices, filled by the report (as the command line has it)
    const fdr::QualityReport q = fdr::quality::compute_quality(view, f.get(), 1.0, out.alpha, {}, nullptr, nullptr, &fv);
    s.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &c1);
    cpu.push_back(double(c1.tv_sec - c0.tv_sec) + 1e-9 * double(c1.tv_nsec - c0.tv_nsec));
    check += q.area;
  }
  std::sort(s.begin(), s.end());
  std::sort(cpu.begin(), cpu.end());
  std::printf("report_best_s=%.4f report_median_s=%.4f cpu_best_s=%.4f cpu_median_s=%.4f triangles=%zu (area %.6g)\n",
              s.front(), s[s.size() / 2], cpu.front(), cpu[cpu.size() / 2],
              view.triangles.size(), check / repeats);
  return 0;
}
