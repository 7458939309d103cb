// Every region of ../shared/data (water + open boundary, raw rings, ETOPO5) read into a clean PSLG.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "gis/crs.hpp"
#include "gis/raster_input.hpp"
#include "gis/vector_input.hpp"
#include "pslg/validate.hpp"
#include "sizing/fields.hpp"

using namespace fdr;
using namespace fdr::gis;

namespace {
const std::string kShared = FDR_SHARED_DATA_DIR;

struct Region {
  const char* name;
  std::size_t holes, open_parts, raw_rings;
};
const Region kRegions[] = {{"chesapeake_mouth", 152, 12, 156},
                           {"gulf_of_maine", 1276, 13, 1301},
                           {"west_norway", 1006, 17, 1006},
                           {"west_norway_h", 0, 16, 694}};

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
}  // namespace

TEST(SharedData, WaterOpenBoundaryAndRawRingsCleanUp) {
  for (const Region& r : kRegions) {
    const std::string dir = kShared + "/" + r.name + "/";
    if (!std::filesystem::exists(dir + r.name + ".gpkg")) GTEST_SKIP() << "shared data not present: " << dir;
    SCOPED_TRACE(r.name);
    auto t0 = std::chrono::steady_clock::now();
    DomainOptions o;
    o.domain = {dir + r.name + ".gpkg", "water", ""};
    o.open_boundary = {dir + r.name + ".gpkg", "open_boundary", ""};
    GisInput in = read_domain(o);
    const double t_read = seconds_since(t0);
    if (r.holes) {
      EXPECT_EQ(in.counts.holes, r.holes);  // all water features
    }
    EXPECT_EQ(in.counts.open_parts, r.open_parts);
    EXPECT_TRUE(pslg::find_crossings(in.pslg).empty());
    double dev = 0;
    ground_to_grid(std::make_shared<sizing::ConstantField>(1000.0), in.frame, &dev);
    // Depths over the domain box from the region's ETOPO5 tile.
    const std::string tif = dir + r.name + "_etopo5.tif";
    const Box2 box = in.frame.domain_box();
    sizing::Grid g = read_raster_to_frame(tif, in.frame, box, grid_cell_size_hint(tif, in.frame, box), &in.pslg.points);
    int filled = 0;
    std::vector<double> z = sample_depths(g, in.pslg.points, &filled);
    for (double v : z) ASSERT_TRUE(std::isfinite(v));

    t0 = std::chrono::steady_clock::now();
    DomainOptions raw;
    raw.domain = {dir + r.name + "_raw.gpkg", "rings_raw", ""};
    GisInput rin = read_domain(raw);
    EXPECT_EQ(rin.counts.polygon_features, r.raw_rings);
    EXPECT_TRUE(pslg::find_crossings(rin.pslg).empty());
    EXPECT_NO_THROW(pslg::validate(rin.pslg, r.name));
    std::printf("%-17s %-40s segs %6zu -> %6zu repairs %4zu read %.2fs | raw segs %6zu -> %6zu repairs %4zu %.2fs | max|k-1| %.2e\n",
                r.name, in.frame.name().c_str(), in.raw.segments.size(), in.pslg.segments.size(), in.repairs.size(),
                t_read, rin.raw.segments.size(), rin.pslg.segments.size(), rin.repairs.size(), seconds_since(t0), dev);
  }
}

// The coast restorer's rounds after the first examine only the segments the previous round
// changed (and those near them); Options::restore_full_rounds makes every round examine everything.
// Chesapeake with the pipeline's defaults for hmin 150 m gives up runs (so a second round runs):
// the results must be the same bit for bit.
TEST(SharedData, CoastRestorerLocalRoundsGiveTheFullResult) {
  const std::string dir = kShared + "/chesapeake_mouth/";
  if (!std::filesystem::exists(dir + "chesapeake_mouth.gpkg")) GTEST_SKIP() << "shared data not present: " << dir;
  DomainOptions o;
  o.domain = {dir + "chesapeake_mouth.gpkg", "water", ""};
  const GisInput in = read_domain(o);
  ASSERT_FALSE(in.domain_polygons.empty());
  const double hmin = 150;
  coast::Options fo;  // pipeline/gis_stage.cpp's settings, with close width hmin/4 (more runs given up)
  fo.close_width = 0.25 * hmin;
  fo.min_feature = 0.1 * hmin;
  fo.min_island_area = 0.1 * hmin * hmin;
  fo.list_area = 0.5 * hmin * hmin;
  fo.tip_clearance = 0.8 * hmin;
  const coast::Result local = coast::generalise(in.domain_polygons, fo);
  fo.restore_full_rounds = true;
  const coast::Result full = coast::generalise(in.domain_polygons, fo);
  ASSERT_EQ(local.polygons.size(), full.polygons.size());
  for (std::size_t i = 0; i < local.polygons.size(); ++i) EXPECT_EQ(local.polygons[i], full.polygons[i]) << i;
  EXPECT_EQ(local.repairs.size(), full.repairs.size());
  EXPECT_EQ(local.closed_area, full.closed_area);
  EXPECT_EQ(local.output_area, full.output_area);
}
