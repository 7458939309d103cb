// The run's plan (stage parameters made from the options, usage errors before any I/O), the
// allocator policy per phase, and what the write stage returns.
#include <gtest/gtest.h>
#include <filesystem>
#include "base/error.hpp"
#include "pipeline/memory_policy.hpp"
#include "pipeline/pipeline.hpp"
#include "pipeline/plan.hpp"

namespace {
using namespace fdr::pipeline;
const std::string kT = FDR_TESTDATA_DIR;

Options poly_options() {
  Options o;
  o.input = kT + "/poly/square10.poly";
  o.spacing = "1";
  return o;
}

fdr::ExitCode usage_code(const Options& o) {
  try {
    plan_run(o);
  } catch (const fdr::Error& e) {
    return static_cast<fdr::ExitCode>(e.exit_code());
  }
  return fdr::ExitCode::kOk;
}

TEST(Plan, PolyRunStageParameters) {
  Options o = poly_options();
  o.outputs = {"a.node", "b.vtu"};
  o.report_json = "r.json";
  o.bound = 0.9;
  const Plan p = plan_run(o);
  EXPECT_FALSE(p.gis);
  EXPECT_EQ(p.triangulate.min_angle_deg, 0.0);  // .poly: no automatic angle bound
  EXPECT_EQ(p.triangulate.smooth_passes, 0);
  EXPECT_EQ(p.triangulate.frontal_radius, 0.0);  // .poly: the paper's circumcentre rule
  EXPECT_TRUE(p.measure.vertex_f);              // .node carries f at the vertices
  EXPECT_FALSE(p.measure.keep_adjacency);       // neither output has boundary lists
  EXPECT_FALSE(p.measure.gis);
  EXPECT_EQ(p.measure.triangulate.bound, 0.9);
  EXPECT_TRUE(p.triangle_values);               // the VTU stores per-triangle values
  ASSERT_EQ(p.write.formats.size(), 2u);
  EXPECT_EQ(p.write.formats[0], fdr::io::Format::kNode);
  EXPECT_EQ(p.write.outputs, o.outputs);
  EXPECT_EQ(p.write.report_json, "r.json");
  EXPECT_EQ(p.write.bound, 0.9);
  EXPECT_EQ(p.write.source, o.input);
}

TEST(Plan, GisDefaultsAndBoundaryOutputs) {
  Options o;
  o.input = kT + "/chesapeake/chesapeake_mouth_water.geojson";
  o.outputs = {"m.14"};
  o.telemac_open = "5,5,5";
  const Plan p = plan_run(o);  // no file is read
  EXPECT_TRUE(p.gis);
  EXPECT_EQ(p.triangulate.min_angle_deg, 30.0);
  EXPECT_EQ(p.triangulate.frontal_radius, 0.75);
  o.frontal_radius = 0;  // --frontal 0: circumcentres only
  EXPECT_EQ(plan_run(o).triangulate.frontal_radius, 0.0);
  o.frontal_radius = 1;  // the triangle made on the front would be bad
  EXPECT_EQ(usage_code(o), fdr::ExitCode::kUsage);
  o.frontal_radius = -1;
  EXPECT_TRUE(p.measure.keep_adjacency);  // fort.14 lists its boundaries
  EXPECT_FALSE(p.measure.vertex_f);
  EXPECT_EQ(p.write.telemac_codes, (std::array<int, 3>{5, 5, 5}));
  EXPECT_EQ(p.write.min_angle_deg, 30.0);
}

TEST(Plan, UsageErrorsBeforeAnyRead) {
  Options o = poly_options();
  o.input = "/nonexistent/x.poly";  // never opened: the plan fails first
  o.bound = 0;
  EXPECT_EQ(usage_code(o), fdr::ExitCode::kUsage);
  o = poly_options();
  o.outputs = {"x.ll"};  // hgrid.ll needs a CRS
  EXPECT_EQ(usage_code(o), fdr::ExitCode::kUsage);
  o = poly_options();
  o.outputs = {"x.unknown-format"};
  EXPECT_EQ(usage_code(o), fdr::ExitCode::kUsage);
  o = poly_options();
  o.no_sliver_removal = true;  // a 3D option
  EXPECT_EQ(usage_code(o), fdr::ExitCode::kUsage);
  o = poly_options();
  o.sliver_angle_deg = 10;
  EXPECT_EQ(usage_code(o), fdr::ExitCode::kUsage);
  EXPECT_EQ(usage_code(poly_options()), fdr::ExitCode::kOk);
  o = poly_options();
  o.dem = "dem.tif";  // a terrain volume is a 3D run
  EXPECT_EQ(usage_code(o), fdr::ExitCode::kUsage);
  o = poly_options();
  o.horizons = {"h.tif"};  // terrain options without --dem
  EXPECT_EQ(usage_code(o), fdr::ExitCode::kUsage);
}

TEST(Plan, ReportReadOnlyWhenSomethingReadsIt) {
  Options o = poly_options();
  EXPECT_TRUE(report_is_read(o, {}));  // library callers read Result::report
  o.report_only_if_read = true;
  EXPECT_TRUE(report_is_read(o, {}));  // printed
  o.quiet = true;
  EXPECT_FALSE(report_is_read(o, {fdr::io::Format::k2dm}));
  EXPECT_TRUE(report_is_read(o, {fdr::io::Format::kGpkg}));  // stored with the mesh
  o.report_json = "r.json";
  EXPECT_TRUE(report_is_read(o, {}));
}

TEST(MemoryPolicy, OneChoicePerPhase) {
  auto flags = [](MemoryPolicy p) { return int(p.keep_freed) + int(p.huge_pages); };
  EXPECT_EQ(flags(policy_for(MemoryPhase::kMesh, false)), 0);
  EXPECT_TRUE(policy_for(MemoryPhase::kMesh, true).keep_freed);
  EXPECT_TRUE(policy_for(MemoryPhase::kGisRead, true).keep_freed);
  EXPECT_TRUE(policy_for(MemoryPhase::kGisInput, true).huge_pages);
  for (auto ph : {MemoryPhase::kMesh, MemoryPhase::kGisRead, MemoryPhase::kGisInput})
    EXPECT_EQ(flags(policy_for(ph, true)), 1);
  const PhaseMemory held(MemoryPhase::kMesh, false);  // a no-op under glibc's malloc
}

TEST(Write, ReturnsThePathsWritten) {
  const auto dir = std::filesystem::temp_directory_path() / "fdr_plan_test";
  std::filesystem::create_directories(dir);
  Options o = poly_options();
  o.outputs = {(dir / "m.node").string()};
  o.report_json = (dir / "r.json").string();
  const Result r = run(o, nullptr, nullptr);
  EXPECT_EQ(r.written, (std::vector<std::string>{o.outputs[0], o.report_json}));
  EXPECT_TRUE(std::filesystem::exists(dir / "m.ele"));  // beside the .node, not listed
  EXPECT_GT(r.report.run.total_s, 0.0);                 // set before the report was written
  std::filesystem::remove_all(dir);
}

}  // namespace
