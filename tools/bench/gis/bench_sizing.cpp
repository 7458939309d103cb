// bench_sizing: the sizing stage of a GIS run, stage by stage, in cells per second.
// Reads a region as `fdrmesh mesh` does (pipeline::read_gis_input), builds the spacing grid the
// same way (sizing::spacing_grid_cell), then times each sizing step on it: distance to shore,
// distance rule, water mask + channel rule, DEM resampling + depth rules, min/clamp/fill, and the
// gradient limiter. Best of --repeat runs per step. Prints measurements only.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

#include "base/error.hpp"
#include "base/memory.hpp"
#include "base/threads.hpp"
#include "gis/raster_input.hpp"
#include "pipeline/gis_stage.hpp"
#include "sizing/channel_rule.hpp"
#include "sizing/gradient_limiter.hpp"
#include "sizing/raster_rules.hpp"
#include "sizing/resample_grid.hpp"
#include "sizing/spacing_grid.hpp"
#include "sizing/spacing_rules.hpp"

namespace {

void usage() {
  std::fprintf(stderr,
               "usage: bench_sizing [--region DIR/NAME] [--hmin M] [--hmax M] [--dist-grade G] [--gradation A]\n"
               "                    [--slope-rule SLP] [--cell-size M] [--repeat N] [--check]\n"
               "  DIR/NAME: NAME.gpkg (layer water) and NAME_etopo5.tif in DIR, e.g. ../shared/data/gulf_of_maine/gulf_of_maine\n"
               "  defaults: testdata/gulf_of_maine/gulf_of_maine, hmin 120, dist-grade 0.04 (bench_gis's run), repeat 3\n"
               "  --check: also the exact distance (BVH) and how far the fast transform is from it\n");
}

using Clock = std::chrono::steady_clock;

// Each run starts as the CLI's sizing stage does, on memory the allocator has given back (the
// read's purge): freed pages are purged first, so a run pays its page faults (on huge pages,
// under the HugePageArenas held in main) and not only the first one.
double best_of(int n, const std::function<void()>& f) {
  double best = 1e300;
  for (int k = 0; k < n; ++k) {
    fdr::release_free_memory();
    const auto t0 = Clock::now();
    f();
    best = std::min(best, std::chrono::duration<double>(Clock::now() - t0).count());
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace fdr;
  std::string region = std::string(FDR_TESTDATA_DIR) + "/gulf_of_maine/gulf_of_maine";
  double hmin = 120, hmax = 0, grade = 0.04, alpha = 0.15, slope = 0, cell_opt = 0;
  int repeat = 3;
  bool check = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) { usage(); std::exit(2); }
      return argv[++i];
    };
    if (a == "--region") region = next();
    else if (a == "--hmin") hmin = std::atof(next().c_str());
    else if (a == "--hmax") hmax = std::atof(next().c_str());
    else if (a == "--dist-grade") grade = std::atof(next().c_str());
    else if (a == "--gradation") alpha = std::atof(next().c_str());
    else if (a == "--slope-rule") slope = std::atof(next().c_str());
    else if (a == "--cell-size") cell_opt = std::atof(next().c_str());
    else if (a == "--check") check = true;
    else if (a == "--repeat") repeat = std::max(1, std::atoi(next().c_str()));
    else { usage(); return 2; }
  }
  try {
    pipeline::Options o;
    o.input = region + ".gpkg";
    o.layer = "water";
    o.raster = region + "_etopo5.tif";
    o.hmin = hmin;
    o.quiet = true;
    std::vector<pipeline::StageTime> stages;
    pipeline::StageClock clock(&stages);
    // As pipeline::prepare_gis_input: the allocator's new memory on huge pages from the read on.
    const HugePageArenas huge;
    const gis::GisInput g = pipeline::read_gis_input(o, clock, nullptr, nullptr);
    // The spacing grid exactly as pipeline::gis_spacing builds it.
    Box2 box = sizing::spacing_box(g.raw.bbox());
    const double diam = std::hypot(g.raw.bbox().width(), g.raw.bbox().height());
    if (hmax <= 0) hmax = diam / 20;
    const double native = gis::grid_cell_size_hint(o.raster, g.frame, box);
    const double cell = cell_opt > 0 ? cell_opt : sizing::spacing_grid_cell(box, hmin);
    const sizing::Grid zgrid = gis::read_raster_to_frame(o.raster, g.frame, box, std::max(native, cell), &g.raw.points);
    const sizing::Grid like = zgrid.dx == cell ? zgrid : sizing::spacing_grid(box, cell);
    std::vector<std::pair<Point2, Point2>> shore, boundary;
    for (const auto& s : g.raw.segments) {
      if (!s.is_boundary()) continue;
      boundary.push_back({g.raw.points[s.a], g.raw.points[s.b]});
      if (s.marker == static_cast<int>(mesh::EdgeKind::kLand) || s.marker == static_cast<int>(mesh::EdgeKind::kIsland))
        shore.push_back({g.raw.points[s.a], g.raw.points[s.b]});
    }
    const double n = static_cast<double>(like.v.size());
    std::printf("bench_sizing: %s, hmin %g m, hmax %g m, dist-grade %g, gradation %g, threads %u\n", region.c_str(), hmin,
                hmax, grade, alpha, max_threads());
    std::printf("  grid %zu x %zu = %.2f M cells of %.1f m (native raster %.0f m, domain box %.0f x %.0f km); %zu shore "
                "segments, %zu boundary segments; best of %d\n",
                like.nx, like.ny, n / 1e6, cell, native, box.width() / 1e3, box.height() / 1e3, shore.size(),
                boundary.size(), repeat);
    std::printf("  %-26s %9s %12s\n", "step", "seconds", "M cells/s");
    double total = 0;
    auto row = [&](const char* name, double s) {
      total += s;
      std::printf("  %-26s %9.4f %12.1f\n", name, s, n / s / 1e6);
    };
    sizing::Grid dist, hdist, hchan, zfine, depth, hslope, h;
    std::vector<char> water;
    row("distance to shore", best_of(repeat, [&] { dist = sizing::distance_to_shore(like, shore); }));
    if (check) {
      sizing::Grid exact;
      const double te = best_of(1, [&] { exact = sizing::distance_to_shore(like, shore, true); });
      std::size_t differ = 0;
      double worst = 0, worst_rel = 0;
      for (std::size_t k = 0; k < exact.v.size(); ++k)
        if (dist.v[k] != exact.v[k]) {
          ++differ;
          worst = std::max(worst, dist.v[k] - exact.v[k]);
          worst_rel = std::max(worst_rel, (dist.v[k] - exact.v[k]) / exact.v[k]);
          if (dist.v[k] < exact.v[k]) std::printf("  BELOW EXACT at cell %zu: %.17g < %.17g\n", k, dist.v[k], exact.v[k]);
        }
      std::size_t over[4] = {0, 0, 0, 0};
      for (std::size_t k = 0; k < exact.v.size(); ++k)
        for (int e = 0; e < 4; ++e)
          if (dist.v[k] - exact.v[k] > std::pow(10.0, -3 + e) * cell) ++over[e];
      {
        std::size_t byd[6] = {0, 0, 0, 0, 0, 0};
        double relmax[6] = {0, 0, 0, 0, 0, 0};
        const double edges[6] = {3, 10, 30, 100, 300, 1e300};
        for (std::size_t k = 0; k < exact.v.size(); ++k) {
          const double e = dist.v[k] - exact.v[k];
          int b = 0;
          while (exact.v[k] / cell > edges[b]) ++b;
          if (e > 0.1 * cell) ++byd[b];
          relmax[b] = std::max(relmax[b], e / exact.v[k]);
        }
        std::printf("    by exact distance (cells) <=3 / 10 / 30 / 100 / 300 / more: errors > 0.1 cell %zu / %zu / %zu / %zu / %zu / %zu;"
                    " largest relative %.3g / %.3g / %.3g / %.3g / %.3g / %.3g\n",
                    byd[0], byd[1], byd[2], byd[3], byd[4], byd[5], relmax[0], relmax[1], relmax[2], relmax[3], relmax[4], relmax[5]);
      }
      std::printf("    cells above exact by more than 0.001 / 0.01 / 0.1 / 1 cell: %zu / %zu / %zu / %zu\n", over[0], over[1],
                  over[2], over[3]);
      std::printf("  %-26s %9.4f %12.1f   (%zu cells differ from it = %.4f %%, largest excess %.3g m = %.3g cells, %.3g relative)\n",
                  "  (exact BVH, 1 run)", te, n / te / 1e6, differ, 100.0 * differ / n, worst, worst / cell, worst_rel);
    }
    row("distance rule", best_of(repeat, [&] { hdist = sizing::rule_distance(dist, hmin, grade); }));
    row("water mask", best_of(repeat, [&] { water = sizing::inside_mask(like, boundary); }));
    row("channel rule", best_of(repeat, [&] { hchan = sizing::rule_channel(dist, water, 2.0); }));
    std::vector<sizing::Grid> rules{hdist, hchan};
    if (slope > 0) {
      row("DEM resample", best_of(repeat, [&] { zfine = sizing::resample_like(zgrid, like); }));
      depth = zfine;
      for (auto& v : depth.v) v = -v;
      row("slope rule", best_of(repeat, [&] { hslope = sizing::rule_slope(depth, slope); }));
      rules.push_back(hslope);
    }
    row("min + clamp + fill", best_of(repeat, [&] {
          h = sizing::fill_nan(sizing::clamp(sizing::combine_min(rules), hmin, hmax), hmax);
        }));
    sizing::Grid lim;
    row("gradient limiter", best_of(repeat, [&] {
          lim = h;
          sizing::limit_gradient(lim, alpha);
        }));
    std::printf("  %-26s %9.4f %12.1f\n", "sizing total", total, n / total / 1e6);
    // The whole rule evaluation as gis_spacing runs it (spacing_from_rules + limiter).
    sizing::SpacingRules rules_opt;
    rules_opt.hmin = hmin;
    rules_opt.hmax = hmax;
    rules_opt.dist_grade = grade;
    if (slope > 0) rules_opt.slope = slope;
    rules_opt.channel_elements = 2.0;
    const double t_all = best_of(repeat, [&] {
      sizing::RuleGrid rg = sizing::spacing_from_rules(rules_opt, {&like, &shore, &zgrid, nullptr, &boundary});
      sizing::limit_gradient(rg.h, alpha);
    });
    std::printf("  %-26s %9.4f %12.1f\n", "spacing_from_rules + limit", t_all, n / t_all / 1e6);
  } catch (const Error& e) {
    std::fprintf(stderr, "ERROR %d: %s\n", e.exit_code(), e.what());
    return e.exit_code();
  }
  return 0;
}
