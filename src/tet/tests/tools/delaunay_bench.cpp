// Benchmark: tet::Delaunay3 beside CGAL's Delaunay_triangulation_3 (Epick, sequential) on the same
// random points in the unit cube. Each build runs in a child process of its own, so that its wall
// time and peak resident memory (VmHWM) are its own; the points are made before the fork.
//
// usage: tet_delaunay_bench [--fdr-only] [N ...]   (default: 10000 100000 1000000)
// --fdr-only skips CGAL (for profiling Delaunay3 alone).
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include "base/memory.hpp"
#include "predicates/predicates.hpp"
#include "tet/delaunay3.hpp"

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Dt = CGAL::Delaunay_triangulation_3<K>;

struct Result {
  double seconds = 0;
  double cpu_seconds = 0;  // user + system of the build alone
  double tets = 0;
  double peak_mib = 0;
  double base_mib = 0;
  double exact_share = 0;
};

double mib(std::size_t b) { return b / (1024.0 * 1024.0); }

// Runs fn in a child process; fn fills seconds, tets and exact_share, the child adds its peak.
template <class Fn>
Result in_child(Fn&& fn) {
  int fd[2];
  if (pipe(fd) != 0) std::abort();
  const pid_t pid = fork();
  if (pid == 0) {
    close(fd[0]);
    Result r;
    r.base_mib = mib(fdr::process_memory()->rss);
    fn(r);
    r.peak_mib = mib(fdr::process_memory()->peak);
    if (write(fd[1], &r, sizeof r) != sizeof r) _exit(1);
    _exit(0);
  }
  close(fd[1]);
  Result r;
  if (read(fd[0], &r, sizeof r) != sizeof r) std::fprintf(stderr, "child failed\n");
  close(fd[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  return r;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double cpu_now() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}
}  // namespace

int main(int argc, char** argv) {
  std::vector<std::size_t> sizes;
  bool with_cgal = true;
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--fdr-only") with_cgal = false;
    else sizes.push_back(std::stoull(argv[i]));
  }
  if (sizes.empty()) sizes = {10000, 100000, 1000000};
  std::printf("%10s  %-6s %9s %9s %11s %10s %10s %8s %8s\n", "points", "build", "wall_s", "cpu_s", "tets", "peak_MiB",
              "base_MiB", "B/tet", "exact%");
  for (const std::size_t n : sizes) {
    std::mt19937_64 rng(n);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<fdr::Point3> pts(n);
    for (auto& p : pts) p = {u(rng), u(rng), u(rng)};
    const Result ours = in_child([&](Result& r) {
      fdr::predicates::reset_counters();
      const auto t0 = std::chrono::steady_clock::now();
      const double c0 = cpu_now();
      fdr::tet::Delaunay3 d;
      d.insert_all(pts);
      r.seconds = seconds_since(t0);
      r.cpu_seconds = cpu_now() - c0;
      r.tets = static_cast<double>(d.num_finite_tets());
      const auto& c = fdr::predicates::counters();
      r.exact_share = 100.0 * c.exact / std::max<double>(1, c.exact + c.filtered);
    });
    if (!with_cgal) {
      std::printf("%10zu  %-6s %9.3f %9.3f %11.0f %10.1f %10.1f %8.1f %8.3f\n", n, "fdr", ours.seconds, ours.cpu_seconds,
                  ours.tets, ours.peak_mib, ours.base_mib,
                  (ours.peak_mib - ours.base_mib) * 1024 * 1024 / std::max(1.0, ours.tets), ours.exact_share);
      continue;
    }
    const Result cgal = in_child([&](Result& r) {
      std::vector<K::Point_3> cp;
      cp.reserve(n);
      for (const auto& p : pts) cp.emplace_back(p.x, p.y, p.z);
      const auto t0 = std::chrono::steady_clock::now();
      const double c0 = cpu_now();
      Dt dt(cp.begin(), cp.end());
      r.seconds = seconds_since(t0);
      r.cpu_seconds = cpu_now() - c0;
      r.tets = static_cast<double>(dt.number_of_finite_cells());
      r.exact_share = -1;
    });
    for (const auto& [name, r] : {std::pair{"fdr", ours}, std::pair{"cgal", cgal}})
      std::printf("%10zu  %-6s %9.3f %9.3f %11.0f %10.1f %10.1f %8.1f %8.3f\n", n, name, r.seconds, r.cpu_seconds, r.tets, r.peak_mib,
                  r.base_mib, (r.peak_mib - r.base_mib) * 1024 * 1024 / std::max(1.0, r.tets), r.exact_share);
    std::printf("%10zu  speed-up %.2fx wall, %.2fx cpu; memory above base %.2fx lower\n", n, cgal.seconds / ours.seconds,
                cgal.cpu_seconds / ours.cpu_seconds,
                (cgal.peak_mib - cgal.base_mib) / std::max(1e-9, ours.peak_mib - ours.base_mib));
    std::fflush(stdout);
  }
  return 0;
}
