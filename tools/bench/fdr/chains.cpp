// Chain benchmark (chains.hpp): each case and tool in its own child process, so that every row
// has its own peak RSS and CPU time.
#include "chains.hpp"
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <vector>
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <nlohmann/json.hpp>
#include "base/error.hpp"
#include "cdt/cdt.hpp"
#include "cdt/tests/chain_inputs.hpp"
#include "child.hpp"
#include "pslg/poly_io.hpp"

namespace {
using Clock = std::chrono::steady_clock;
double secs(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

struct Case {
  const char* name;
  std::function<fdr::pslg::Pslg()> make;
};

// The cases for about n vertices: the degenerate ones and random points of the same size.
std::vector<Case> cases(std::size_t n) {
  using namespace fdr::testing;
  const int k = static_cast<int>(n);
  const int side = std::max(2, static_cast<int>(std::lround(std::sqrt(static_cast<double>(n)))) - 2);
  const int per_ring = 500, rings = std::max(1, k / per_ring), per_chain = 2000;
  const int chains = std::max(1, k / per_chain - 1);
  return {
      {"square", [k] { return collinear_square(k / 4); }},
      {"lattice", [side] { return lattice_square(side + 1); }},
      {"rings", [rings] { return concentric_rings(rings, per_ring); }},
      {"breaklines", [chains] { return breaklines(chains, per_chain); }},
      {"random", [k] { return random_points(k); }},
  };
}

// Runs fn in a forked child; prints its line with the child's whole wall clock, CPU and peak.
int measured(const char* tool, const char* name, std::size_t vertices, const std::function<std::string()>& fn) {
  std::fflush(stdout);
  const auto t0 = Clock::now();
  const pid_t pid = fork();
  if (pid == 0) {
    int code = 0;
    std::string line;
    try {
      line = fn();
    } catch (const fdr::Error& e) {
      std::fprintf(stderr, "%s\n", e.what());
      code = e.exit_code();
    }
    std::printf("%s", line.c_str());
    std::fflush(stdout);
    _exit(code);
  }
  int st = 0;
  rusage ru{};
  wait4(pid, &st, 0, &ru);
  const double cpu = static_cast<double>(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
                     1e-6 * static_cast<double>(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
  std::printf("%-12s %-10s %8zu vertices  whole %7.3f s  cpu %7.3f s  peak %7.1f MiB\n", tool, name, vertices,
              secs(t0, Clock::now()), cpu, ru.ru_maxrss / 1024.0);
  std::fflush(stdout);
  return WIFEXITED(st) ? WEXITSTATUS(st) : static_cast<int>(fdr::ExitCode::kInternal);
}

// fdrmesh's CDT as the command line builds it (resolve, then the triangulation), in process.
std::string run_fdr_cdt(const fdr::pslg::Pslg& p) {
  fdr::cdt::CdtStats st;
  fdr::cdt::CdtOptions o;
  o.resolve = true;
  const auto t0 = Clock::now();
  const auto T = fdr::cdt::build_cdt(p, o, &st);
  const double s = secs(t0, Clock::now());
  char line[256];
  std::snprintf(line, sizeof line,
                "  cdt %.3f s, %zu triangles; per vertex %.1f walk steps, %.1f new triangles; %.1f recovery steps per "
                "segment%s\n",
                s, T.num_live_triangles(), double(st.walk_steps) / p.points.size(),
                double(st.new_triangles) / p.points.size(),
                double(st.recovery_steps) / std::max<std::size_t>(1, p.segments.size()),
                st.random_rounds ? "; random rounds" : "");
  return line;
}

// CGAL's constrained Delaunay triangulation of the same points and segments (points inserted as
// a range, so spatially sorted), as a Triangle-like reference.
std::string run_cgal_cdt(const fdr::pslg::Pslg& p) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using CDT = CGAL::Constrained_Delaunay_triangulation_2<K, CGAL::Default, CGAL::Exact_predicates_tag>;
  const auto t0 = Clock::now();
  std::vector<std::pair<K::Point_2, std::size_t>> pts;
  for (std::size_t i = 0; i < p.points.size(); ++i) pts.push_back({{p.points[i].x, p.points[i].y}, i});
  std::vector<std::pair<std::size_t, std::size_t>> segs;
  for (const auto& s : p.segments) segs.push_back({s.a, s.b});
  CDT cdt;
  std::vector<K::Point_2> plain;
  for (const auto& q : pts) plain.push_back(q.first);
  cdt.insert_constraints(plain.begin(), plain.end(), segs.begin(), segs.end());
  char line[160];
  std::snprintf(line, sizeof line, "  cgal cdt %.3f s, %zu faces\n", secs(t0, Clock::now()), cdt.number_of_faces());
  return line;
}

// The command line on the case written as a .poly: fdrmesh mesh X.poly --spacing extent/20.
int run_cli(const char* name, const fdr::pslg::Pslg& p, const std::string& binary) {
  char dir_tmpl[] = "/tmp/bench_fdr_chains.XXXXXX";
  if (!mkdtemp(dir_tmpl)) throw fdr::Error(fdr::ExitCode::kOutputError, "bench_fdr: mkdtemp in /tmp failed");
  const std::string dir = dir_tmpl, poly = dir + "/" + name + ".poly", json = dir + "/report.json", log = dir + "/log.txt";
  fdr::pslg::write_poly(p, poly);
  const fdr::Box2 b = p.bbox();
  const std::string spacing = std::to_string(std::max(b.width(), b.height()) / 20);
  const ChildRun c = spawn_and_wait({binary, "mesh", poly, "--spacing", spacing, "-q", "--report", json}, log);
  if (!WIFEXITED(c.status) || WEXITSTATUS(c.status) != 0) {
    std::printf("  fdrmesh-cli %s failed (status %d), see %s\n", name, c.status, log.c_str());
    return static_cast<int>(fdr::ExitCode::kInternal);
  }
  std::ifstream in(json);
  const auto j = nlohmann::json::parse(in);
  std::printf("%-12s %-10s %8zu vertices  whole %7.3f s  cpu %7.3f s  peak %7.1f MiB\n", "fdrmesh-cli", name,
              p.points.size(), c.wall, c.cpu, c.maxrss_mb);
  std::printf("  fdrmesh mesh %s.poly --spacing %s: cdt %.3f s, refine %.3f s, total %.3f s, %zu triangles\n", name,
              spacing.c_str(), j["timings_s"].value("cdt", 0.0), j["timings_s"].value("refine", 0.0),
              j["timings_s"].value("total", 0.0), j["triangles"].get<std::size_t>());
  std::remove(poly.c_str()); std::remove(json.c_str()); std::remove(log.c_str()); rmdir(dir.c_str());
  return 0;
}

}  // namespace

int run_chains(std::size_t n, const std::string& fdr_binary, bool cgal) {
  std::printf("Chain benchmark: about %zu vertices per case; whole = the child process from fork to exit (input\n"
              "  generation included), cpu = its user + system time, peak = its ru_maxrss\n", n);
  int code = 0;
  auto keep_first = [&code](int c) { if (code == 0) code = c; };
  for (const Case& c : cases(n)) {
    const fdr::pslg::Pslg p = c.make();
    const std::size_t nv = p.points.size();
    keep_first(measured("fdrmesh-cdt", c.name, nv, [&p] { return run_fdr_cdt(p); }));
    if (cgal) keep_first(measured("cgal-cdt", c.name, nv, [&p] { return run_cgal_cdt(p); }));
    if (!fdr_binary.empty()) keep_first(run_cli(c.name, p, fdr_binary));
  }
  return code;
}
