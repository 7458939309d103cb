// bench_gis: one end-to-end GIS run (by default Gulf of Maine + ETOPO5 distance sizing, ~1M
// triangles) printing wall time and peak memory (VmHWM) per pipeline stage, and for the whole
// process: wall clock from main() to exit and the process's VmHWM (not an increase). --case picks
// one of the shared regions or the continental case (the Baltic Sea) instead; one case per
// process, so that the whole-process figures are that case's.
#include <chrono>
#include <sys/resource.h>
#include <cstdio>
#include <sstream>
#include <vector>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include "base/error.hpp"
#include "pipeline/pipeline.hpp"

namespace {
void usage() {
  std::fprintf(stderr,
               "usage: bench_gis [--case NAME] [--data DIR] [--hmin M] [--hmax M] [--dist-grade G] [--out FILE.gpkg]\n"
               "                 [--formats LIST] [--no-write] [--check]\n"
               "  NAME: gulf_of_maine (default), chesapeake_mouth, west_norway, west_norway_h, baltic\n"
               "  LIST: comma-separated output extensions written to temporary files, e.g. gpkg,2dm,14 (default gpkg)\n"
               "  DIR holds NAME.gpkg (layers water, open_boundary) and NAME_etopo5.tif; default\n"
               "  testdata/gulf_of_maine for gulf_of_maine, else ../shared/data/NAME\n"
               "  defaults per case: gulf_of_maine hmin 120 m, dist-grade 0.04 (about 1.1M triangles);\n"
               "  chesapeake_mouth hmin 150, hmax 5000; west_norway(_h) hmin 100; baltic hmin 1000, hmax 25000\n"
               "  (the shared regions as the pinned meshes run them, with their open boundary; the Baltic with\n"
               "  --raster --hmin --hmax only, every boundary coast, as the continental targets are stated);\n"
               "  out = a temporary GPKG removed at the end\n");
}

// A case's input and the options the defaults are measured with.
struct Case {
  const char* name;
  const char* title;
  bool in_testdata;    // testdata/NAME rather than ../shared/data/NAME
  bool open_boundary;  // the open_boundary layer given (else every boundary is coast)
  double hmin;
  std::optional<double> hmax, dist_grade;
};

const Case kCases[] = {
    {"gulf_of_maine", "Gulf of Maine", true, true, 120, std::nullopt, 0.04},
    {"chesapeake_mouth", "Chesapeake Bay mouth", false, true, 150, 5000, std::nullopt},
    {"west_norway", "West Norway (GSHHG f)", false, true, 100, std::nullopt, std::nullopt},
    {"west_norway_h", "West Norway (GSHHG h)", false, true, 100, std::nullopt, std::nullopt},
    {"baltic", "Baltic Sea (continental)", false, false, 1000, 25000, std::nullopt},
};

const Case* find_case(const std::string& name) {
  for (const Case& c : kCases)
    if (name == c.name) return &c;
  return nullptr;
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
  const Case* bench = &kCases[0];
  std::string data;
  std::optional<double> hmin, hmax, grade;
  std::string out;
  bool write = true, check = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) { usage(); std::exit(2); }
      return argv[++i];
    };
    if (a == "--case") {
      bench = find_case(next());
      if (!bench) { usage(); return 2; }
    }
    else if (a == "--data") data = next();
    else if (a == "--hmin") hmin = std::atof(next().c_str());
    else if (a == "--hmax") hmax = std::atof(next().c_str());
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

  if (data.empty())
    data = std::string(bench->in_testdata ? FDR_TESTDATA_DIR : FDR_SHARED_DATA_DIR) + "/" + bench->name;
  const std::string name = bench->name;
  pipeline::Options o;
  o.input = data + "/" + name + ".gpkg";
  o.layer = "water";
  if (bench->open_boundary) {
    o.open_boundary = o.input;
    o.open_boundary_layer = "open_boundary";
  }
  o.raster = data + "/" + name + "_etopo5.tif";
  o.hmin = hmin.value_or(bench->hmin);
  o.hmax = hmax ? hmax : bench->hmax;
  o.dist_grade = grade ? grade : bench->dist_grade;
  o.check = check;
  o.quiet = true;
  if (write) o.outputs = outs;
  try {
    const pipeline::Result r = pipeline::run(o, nullptr, nullptr);
    auto opt = [](std::optional<double> v, const char* unit) {
      if (!v) return std::string("default");
      char buf[64];
      std::snprintf(buf, sizeof buf, "%g%s", *v, unit);
      return std::string(buf);
    };
    std::printf("bench_gis: %s, hmin %g m, hmax %s, dist-grade %s, %s\n", bench->title, *o.hmin,
                opt(o.hmax, " m").c_str(), opt(o.dist_grade, "").c_str(), r.crs_name.c_str());
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
