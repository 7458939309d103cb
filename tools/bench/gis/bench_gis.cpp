// bench_gis: one end-to-end GIS run (Gulf of Maine + ETOPO5 distance sizing, ~1M triangles by
// default) printing wall time and peak memory (VmHWM) per pipeline stage, and for the whole
// process: wall clock from main() to exit and the process's VmHWM (not an increase).
#include <chrono>
#include <sys/resource.h>
#include <cstdio>
#include <sstream>
#include <vector>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include "base/error.hpp"
#include "pipeline/pipeline.hpp"

namespace {
void usage() {
  std::fprintf(stderr,
               "usage: bench_gis [--data DIR] [--hmin M] [--dist-grade G] [--out FILE.gpkg] [--formats LIST] [--no-write]\n"
               "                 [--check]\n"
               "  LIST: comma-separated output extensions written to temporary files, e.g. gpkg,2dm,14 (default gpkg)\n"
               "  DIR holds gulf_of_maine.gpkg (layers water, open_boundary) and gulf_of_maine_etopo5.tif\n"
               "  defaults: DIR = testdata/gulf_of_maine, hmin 120 m, dist-grade 0.04 (about 1.1M triangles),\n"
               "  out = a temporary GPKG removed at the end\n");
}
}  // namespace

long vm_hwm_kb() {
  FILE* f = std::fopen("/proc/self/status", "r");
  if (!f) return 0;
  char line[256];
  long kb = 0;
  while (std::fgets(line, sizeof line, f))
    if (std::strncmp(line, "VmHWM:", 6) == 0) kb = std::atol(line + 6);
  std::fclose(f);
  return kb;
}

int main(int argc, char** argv) {
  using namespace fdr;
  const auto t_main = std::chrono::steady_clock::now();
  std::string formats = "gpkg";
  std::string data = std::string(FDR_TESTDATA_DIR) + "/gulf_of_maine";
  double hmin = 120, grade = 0.04;
  std::string out;
  bool write = true, check = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) { usage(); std::exit(2); }
      return argv[++i];
    };
    if (a == "--data") data = next();
    else if (a == "--hmin") hmin = std::atof(next().c_str());
    else if (a == "--dist-grade") grade = std::atof(next().c_str());
    else if (a == "--out") out = next();
    else if (a == "--no-write") write = false;
    else if (a == "--formats") formats = next();
    else if (a == "--check") check = true;
    else { usage(); return 2; }
  }
  const bool temp_out = write && out.empty();
  std::vector<std::string> outs;
  if (write && !temp_out) outs.push_back(out);
  if (temp_out) {
    std::stringstream ss(formats);
    for (std::string ext; std::getline(ss, ext, ',');)
      outs.push_back((std::filesystem::temp_directory_path() / ("bench_gis_" + std::to_string(getpid()) + "." + ext)).string());
  }
  auto cleanup = [&] {
    if (!temp_out) return;
    for (const auto& p : outs) {
      std::filesystem::remove(p);
      if (p.size() > 5 && p.compare(p.size() - 5, 5, ".node") == 0) std::filesystem::remove(p.substr(0, p.size() - 5) + ".ele");
    }
  };

  pipeline::Options o;
  o.input = data + "/gulf_of_maine.gpkg";
  o.layer = "water";
  o.open_boundary = o.input;
  o.open_boundary_layer = "open_boundary";
  o.raster = data + "/gulf_of_maine_etopo5.tif";
  o.hmin = hmin;
  o.dist_grade = grade;
  o.check = check;
  o.quiet = true;
  if (write) o.outputs = outs;
  try {
    const pipeline::Result r = pipeline::run(o, nullptr, nullptr);
    std::printf("bench_gis: Gulf of Maine, hmin %g m, dist-grade %g, %s\n", hmin, grade, r.crs_name.c_str());
    std::printf("  vertices %zu, triangles %zu, repairs %zu\n", r.mesh.num_vertices(), r.mesh.num_triangles(), r.repairs);
    std::printf("  %-8s %9s %12s %13s\n", "stage", "seconds", "peak MiB", "minor faults");
    double total = 0;
    for (const auto& s : r.stages) {
      std::printf("  %-8s %9.3f %12.1f %13ld\n", s.name.c_str(), s.seconds, s.peak_rss_mb, s.minor_faults);
      total += s.seconds;
    }
    std::printf("  %-8s %9.3f %12.1f\n", "stages", total, r.stages.empty() ? 0.0 : r.stages.back().peak_rss_mb);
    double refine_s = 0;
    for (const auto& s : r.stages)
      if (s.name == "refine") refine_s = s.seconds;
    cleanup();
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_main).count();
    const double hwm_mb = vm_hwm_kb() / 1024.0;
    const double nt = static_cast<double>(r.mesh.num_triangles());
    std::printf("  whole process: wall %.3f s (%.2fx refine), peak RSS (VmHWM) %.1f MiB = %.0f B/triangle; outputs %s\n",
                wall, refine_s > 0 ? wall / refine_s : 0.0, hwm_mb, hwm_mb * 1048576.0 / nt,
                write ? (temp_out ? formats.c_str() : out.c_str()) : "none");
    std::printf("  (%.0f ns per triangle end to end)\n", 1e9 * wall / nt);
    // Process CPU time (every thread, user + system) over the wall time: how much of the second
    // core the run used. The system part apart: page faults, giving pages back (madvise, whose TLB
    // shootdowns interrupt the other threads) and the writers' copies into the page cache.
    rusage ru{};
    getrusage(RUSAGE_SELF, &ru);
    const double user = static_cast<double>(ru.ru_utime.tv_sec) + 1e-6 * static_cast<double>(ru.ru_utime.tv_usec);
    const double sys = static_cast<double>(ru.ru_stime.tv_sec) + 1e-6 * static_cast<double>(ru.ru_stime.tv_usec);
    const double cpu = user + sys;
    std::printf("  process CPU %.3f s (user %.3f + system %.3f) = %.2f cores busy on average; %ld minor page faults\n",
                cpu, user, sys, wall > 0 ? cpu / wall : 0.0, ru.ru_minflt);
  } catch (const Error& e) {
    std::fprintf(stderr, "ERROR %d: %s\n", e.exit_code(), e.what());
    cleanup();
    return e.exit_code();
  }
  return 0;
}
