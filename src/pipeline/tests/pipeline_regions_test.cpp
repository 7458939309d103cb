// Every region of ../shared/data meshed with default options (water + open boundary + ETOPO5,
// raw GSHHG rings, Luxembourg terrain): --check invariants and mesh area = cleaned-PSLG area.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "base/error.hpp"
#include "pipeline/gis_stage.hpp"
#include "pipeline/pipeline.hpp"
#include "pipeline_test_util.hpp"

using namespace fdr;
using namespace fdr::pipeline;
using namespace fdr::pipeline::testing_util;

namespace {
const std::string kShared = FDR_SHARED_DATA_DIR;

struct Case {
  std::string name;
  Options options;
};

std::vector<Case> cases() {
  std::vector<Case> v;
  for (const char* r : {"chesapeake_mouth", "gulf_of_maine", "west_norway_h", "west_norway"}) {
    const std::string d = kShared + "/" + r + "/";
    Options o;
    o.input = d + r + ".gpkg";
    o.layer = "water";
    o.open_boundary = o.input;
    o.open_boundary_layer = "open_boundary";
    o.raster = d + r + "_etopo5.tif";
    v.push_back({r, o});
    Options raw;
    raw.input = d + r + "_raw.gpkg";
    raw.layer = "rings_raw";
    raw.raster = o.raster;
    v.push_back({std::string(r) + "_raw", raw});
  }
  for (const char* rivers : {"rivers_h", "rivers_f"}) {
    Options o = v[2].options;  // gulf_of_maine
    o.breaklines = o.input;
    o.breaklines_layer = rivers;
    v.push_back({std::string("gulf_of_maine_") + rivers, o});
  }
  Options lux;
  lux.input = kShared + "/luxembourg/lux.shp";
  lux.raster = kShared + "/luxembourg/elev.tif";
  lux.vertical_tol = 5.0;
  v.push_back({"luxembourg", lux});
  return v;
}
}  // namespace

class PipelineRegions : public ::testing::TestWithParam<std::size_t> {};

TEST_P(PipelineRegions, DefaultOptionsMeshAndCheck) {
  const Case c = cases()[GetParam()];
  if (!std::filesystem::exists(c.options.input)) GTEST_SKIP() << "shared data not present: " << c.options.input;
  Options o = c.options;
  o.check = true;
  const auto t0 = std::chrono::steady_clock::now();
  Result r;
  try {
    r = run(o, nullptr, nullptr);
  } catch (const Error& e) {
    FAIL() << c.name << ": exit " << e.exit_code() << ": " << e.what();
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(r.report.bad_triangles.value_or(1), 0u);
  PreparedInput in = prepare_gis_input(o, nullptr, nullptr);
  EXPECT_NEAR(mesh_area(r.mesh) / parity_area(in.pslg), 1.0, 1e-9);
  for (double z : r.mesh.z) ASSERT_TRUE(std::isfinite(z));
  std::printf("| %s | %.2f | %zu | %zu | %.2f | %zu | %s |\n", c.name.c_str(), s, r.mesh.num_vertices(), r.mesh.num_triangles(),
              r.report.min_angle_deg.value_or(0), r.repairs, r.crs_name.c_str());
}

INSTANTIATE_TEST_SUITE_P(Shared, PipelineRegions, ::testing::Range<std::size_t>(0, 11),
                         [](const ::testing::TestParamInfo<std::size_t>& i) { return cases()[i.param].name; });
