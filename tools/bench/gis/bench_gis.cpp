// bench_gis: one end-to-end GIS run (Gulf of Maine + ETOPO5 distance sizing, ~1M triangles by
// default) printing wall time and peak memory (VmHWM) per pipeline stage.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include "base/error.hpp"
#include "pipeline/pipeline.hpp"

namespace {
void usage() {
  std::fprintf(stderr,
               "usage: bench_gis [--data DIR] [--hmin M] [--dist-grade G] [--out FILE.gpkg] [--no-write] [--check]\n"
               "  DIR holds gulf_of_maine.gpkg (layers water, open_boundary) and gulf_of_maine_etopo5.tif\n"
               "  defaults: DIR = testdata/gulf_of_maine, hmin 120 m, dist-grade 0.04 (about 1.1M triangles),\n"
               "  out = a temporary GPKG removed at the end\n");
}
}  // namespace

int main(int argc, char** argv) {
  using namespace fdr;
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
    else if (a == "--check") check = true;
    else { usage(); return 2; }
  }
  const bool temp_out = write && out.empty();
  if (temp_out) out = (std::filesystem::temp_directory_path() / ("bench_gis_" + std::to_string(getpid()) + ".gpkg")).string();

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
  if (write) o.outputs = {out};
  try {
    const pipeline::Result r = pipeline::run(o, nullptr, nullptr);
    std::printf("bench_gis: Gulf of Maine, hmin %g m, dist-grade %g, %s\n", hmin, grade, r.crs_name.c_str());
    std::printf("  vertices %zu, triangles %zu, repairs %zu\n", r.mesh.num_vertices(), r.mesh.num_triangles(), r.repairs);
    std::printf("  %-8s %9s %12s\n", "stage", "seconds", "peak MiB");
    double total = 0;
    for (const auto& s : r.stages) {
      std::printf("  %-8s %9.3f %12.1f\n", s.name.c_str(), s.seconds, s.peak_rss_mb);
      total += s.seconds;
    }
    std::printf("  %-8s %9.3f %12.1f\n", "total", total, r.stages.empty() ? 0.0 : r.stages.back().peak_rss_mb);
    std::printf("  (%.0f ns per triangle end to end)\n", 1e9 * total / static_cast<double>(r.mesh.num_triangles()));
  } catch (const Error& e) {
    std::fprintf(stderr, "ERROR %d: %s\n", e.exit_code(), e.what());
    if (temp_out) std::filesystem::remove(out);
    return e.exit_code();
  }
  if (temp_out) std::filesystem::remove(out);
  return 0;
}
