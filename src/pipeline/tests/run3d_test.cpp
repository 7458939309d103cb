// The 3D run: usage errors before any I/O, what it writes, cancellation leaving nothing.
#include <gtest/gtest.h>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>
#include "base/error.hpp"
#include "pipeline/run3d.hpp"

namespace fdr::pipeline {
namespace {

namespace fs = std::filesystem;
const std::string kData = FDR_TESTDATA_DIR;

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("fdr_run3d_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

int usage_code(const Options& o) {
  try {
    check_3d_options(o);
    return 0;
  } catch (const Error& e) {
    return e.exit_code();
  }
}

TEST(Run3d, TwoDimensionalOptionsAreUsageErrors) {
  Options o;
  o.input = kData + "/3d/cube.poly";
  EXPECT_EQ(usage_code(o), 0);
  Options a = o;
  a.hmin = 1.0;
  EXPECT_EQ(usage_code(a), 2);
  Options b = o;
  b.min_angle_deg = 20;
  EXPECT_EQ(usage_code(b), 2);
  Options c = o;
  c.raster = "dem.tif";
  EXPECT_EQ(usage_code(c), 2);
  Options d = o;
  d.outputs = {"m.vtu", "m.2dm"};
  EXPECT_EQ(usage_code(d), 2);
  Options e = o;
  e.bound = 0;
  e.bound_given = true;
  EXPECT_EQ(usage_code(e), 2);
  Options f = o;
  f.bound = 0.8;
  f.bound_given = true;
  f.outputs = {"m.vtu", "m.msh", "m.node"};
  EXPECT_EQ(usage_code(f), 0);
}

TEST(Run3d, SliverOptionsAreChecked) {
  Options o;
  o.input = kData + "/3d/cube.poly";
  o.no_sliver_removal = true;
  EXPECT_EQ(usage_code(o), 0);
  o.sliver_angle_deg = 10;
  EXPECT_EQ(usage_code(o), 2);  // both at once contradict
  o.no_sliver_removal = false;
  EXPECT_EQ(usage_code(o), 0);
  for (double bad : {0.0, -5.0, 31.0, std::nan("")}) {
    o.sliver_angle_deg = bad;
    EXPECT_EQ(usage_code(o), 2) << bad;
  }
}

TEST(Run3d, IsThreeDimensional) {
  Options o;
  o.input = kData + "/3d/cube.poly";
  EXPECT_TRUE(is_3d_run(o));
  o.input = kData + "/3d/square2d.poly";
  EXPECT_FALSE(is_3d_run(o));
}

TEST(Run3d, WritesEveryOutputAndTheReport) {
  const fs::path d = fresh_dir("write");
  Options o;
  o.input = kData + "/3d/cube.poly";
  o.spacing = "0.5";
  o.outputs = {(d / "c.vtu").string(), (d / "c.node").string()};
  o.report_json = (d / "c.json").string();
  const Result3 r = run3d(o, {}, {});
  EXPECT_TRUE(r.measured);
  for (const char* f : {"c.vtu", "c.node", "c.ele", "c.face", "c.json"}) EXPECT_TRUE(fs::exists(d / f)) << f;
  EXPECT_EQ(r.written.size(), 3u);
  EXPECT_EQ(r.report.tets, r.mesh.tets.size());
  EXPECT_NEAR(r.report.volume, 1.0, 1e-12);
  // The VTU carries the per-tetrahedron figures.
  ASSERT_EQ(r.mesh.cell_fields.size(), 3u);
  EXPECT_EQ(r.mesh.cell_fields[0].second.size(), r.mesh.tets.size());
  std::ostringstream s;
  write_summary3(r, s);
  EXPECT_NE(s.str().find("wrote " + (d / "c.json").string()), std::string::npos);
  fs::remove_all(d);
}

TEST(Run3d, CancelledRunWritesNothing) {
  const fs::path d = fresh_dir("cancel");
  Options o;
  o.input = kData + "/3d/cube.poly";
  o.spacing = "0.5";
  o.outputs = {(d / "c.vtu").string()};
  o.report_json = (d / "c.json").string();
  try {
    (void)run3d(o, [](double f, std::string_view) { return f < 0.85; }, {});
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.exit_code(), static_cast<int>(ExitCode::kCancelled));
  }
  EXPECT_TRUE(fs::is_empty(d));
  fs::remove_all(d);
}

}  // namespace
}  // namespace fdr::pipeline
