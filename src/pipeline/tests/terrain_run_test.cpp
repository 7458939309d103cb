// Terrain volumes (--dem): usage errors, the synthetic DEM with a horizon (layers, groups, volumes,
// --check), a pinch-out, bad inputs (exit codes, nothing written).
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string_view>
#include <unistd.h>
#include "api/tetrahedralize.hpp"
#include "base/error.hpp"
#include "pipeline/run3d.hpp"
#include "pipeline/terrain_gpkg.hpp"
#include "pipeline/terrain_run.hpp"
#include "quality/report3d.hpp"
#include "sizing/spacing3d_make.hpp"
#include "terrain/surfaces.hpp"
#include "terrain/terrain_plc.hpp"

namespace fdr::pipeline {
namespace {

namespace fs = std::filesystem;
const std::string kData = FDR_TESTDATA_DIR;
const std::string kTerrain = kData + "/terrain/";

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("fdr_terrain_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

Options synthetic(const fs::path& dir) {
  Options o;
  o.input = kTerrain + "synthetic_domain.geojson";
  o.dem = kTerrain + "synthetic_dem.tif";
  o.base = "-200";
  o.horizons = {kTerrain + "synthetic_h1.tif"};
  o.hmin = 150;
  o.hmax = 400;
  o.quiet = true;
  o.outputs = {(dir / "m.vtu").string(), (dir / "m.msh").string()};
  return o;
}

int run_code(const Options& o) {
  try {
    run3d(o, {}, {});
    return 0;
  } catch (const Error& e) {
    return e.exit_code();
  }
}

int usage_code(const Options& o) {
  try {
    check_terrain_options(o);
    return 0;
  } catch (const Error& e) {
    return e.exit_code();
  }
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(TerrainRun, UsageErrors) {
  const Options o = synthetic(fs::temp_directory_path());
  EXPECT_TRUE(is_3d_run(o));
  EXPECT_EQ(usage_code(o), 0);
  Options a = o;
  a.base.clear();
  EXPECT_EQ(usage_code(a), 2);
  Options b = o;
  b.raster = o.dem;
  EXPECT_EQ(usage_code(b), 2);
  Options c = o;
  c.outputs = {"m.2dm"};
  EXPECT_EQ(usage_code(c), 2);
  Options d = o;
  d.depth_grade = -1;
  EXPECT_EQ(usage_code(d), 2);
  Options e = o;
  e.input.clear();  // the DEM's valid data is the domain
  EXPECT_EQ(usage_code(e), 0);
  Options f = o;
  f.outputs = {"m.vtu", "m.poly"};
  EXPECT_EQ(usage_code(f), 0);
  f.outputs = {"m.vtu", "top.GPKG"};
  EXPECT_EQ(usage_code(f), 0);
  // Terrain options without --dem, on a 3D PLC and in the 2D plan.
  Options g;
  g.input = kData + "/3d/cube.poly";
  g.base = "-500";
  EXPECT_THROW(check_3d_options(g), Error);
  Options h;
  h.horizons = {"h.tif"};
  EXPECT_THROW(check_no_terrain_options(h), Error);
}

TEST(TerrainRun, BaseElevation) {
  EXPECT_EQ(base_elevation("-500"), -500.0);
  EXPECT_EQ(base_elevation("1e2"), 100.0);
  EXPECT_FALSE(base_elevation("base.tif"));
  EXPECT_FALSE(base_elevation("12m"));
  EXPECT_FALSE(base_elevation(""));
}

TEST(TerrainRun, SyntheticDemWithAHorizon) {
  const fs::path dir = fresh_dir("synthetic");
  Options o = synthetic(dir);
  o.check = true;
  o.report_json = (dir / "r.json").string();
  const Result3 r = run3d(o, {}, {});
  ASSERT_EQ(r.layers.size(), 2u);
  EXPECT_EQ(r.layers[0].name, "top-synthetic_h1");
  EXPECT_EQ(r.layers[1].name, "synthetic_h1-base");
  for (const LayerFigures& l : r.layers) {
    EXPECT_GT(l.tets, 0u);
    EXPECT_NEAR(l.volume, l.expected, 1e-3 * l.expected) << l.name;
  }
  ASSERT_TRUE(r.report.check_passed.has_value());
  EXPECT_TRUE(*r.report.check_passed);
  EXPECT_LE(r.report.max_R_over_f, r.report.bound_B * (1 + 1e-9));
  // World coordinates (UTM 32N) and every surface a physical group.
  const auto [lo, hi] = std::minmax_element(r.mesh.points.begin(), r.mesh.points.end(),
                                            [](const Point3& a, const Point3& b) { return a.x < b.x; });
  EXPECT_GE(lo->x, 500000.0);  // the mesh is made in world coordinates
  EXPECT_LE(hi->x, 502400.0);
  for (std::int32_t m : {1, 2, 3, 4})
    EXPECT_NE(std::find(r.mesh.face_marker.begin(), r.mesh.face_marker.end(), m), r.mesh.face_marker.end()) << m;
  const std::string msh = slurp(dir / "m.msh");
  for (const char* g : {"\"top\"", "\"base\"", "\"side\"", "\"synthetic_h1\"", "\"top-synthetic_h1\"", "\"synthetic_h1-base\""})
    EXPECT_NE(msh.find(g), std::string::npos) << g;
  EXPECT_TRUE(fs::exists(dir / "m.vtu"));
  EXPECT_NE(slurp(dir / "r.json").find("\"layers\""), std::string::npos);
  fs::remove_all(dir);
}

TEST(TerrainRun, PinchOutCollapsesThinLayers) {
  const fs::path dir = fresh_dir("pinch");
  Options o = synthetic(dir);
  o.horizons = {kTerrain + "synthetic_pinch.tif"};
  // About hmin / 2: thinner wedges at the pinch-out make the 3D core fail (testdata/terrain/pinch_nan.poly).
  o.min_thickness = 80;
  o.check = true;
  const Result3 r = run3d(o, {}, {});
  ASSERT_EQ(r.layers.size(), 2u);
  for (const LayerFigures& l : r.layers) EXPECT_NEAR(l.volume, l.expected, 1e-3 * l.expected) << l.name;
  fs::remove_all(dir);
}

// Without --min-thickness the layers thinner than 0.15 hmin collapse (at --hmin 150: 22.5 m), so
// the pinch-out ends in a wedge of at least that over a TIN edge and the run takes seconds.
TEST(TerrainRun, DefaultMinThicknessCollapsesBelowTheResolution) {
  const fs::path dir = fresh_dir("pinch_default");
  Options o = synthetic(dir);
  o.horizons = {kTerrain + "synthetic_pinch.tif"};
  o.outputs = {(dir / "t.poly").string()};  // the PLC only: the clamping is what is tested here
  std::string warnings;
  const LogFn log = [&](LogLevel l, std::string_view m) {
    if (l == LogLevel::kWarning) warnings += std::string(m) + "\n";
  };
  run3d(o, {}, log);
  EXPECT_NE(warnings.find("thinner than 22.5 m"), std::string::npos) << warnings;
  EXPECT_EQ(warnings.find(" 0 moved onto the surface above or the base"), std::string::npos) << warnings;
  o.min_thickness = 0;  // keeps every layer: nothing collapses
  warnings.clear();
  run3d(o, {}, log);
  EXPECT_NE(warnings.find(" 0 moved onto the surface above or the base where a layer is thinner than 0 m"), std::string::npos)
      << warnings;
  fs::remove_all(dir);
}

// A synthetic pinch-out PLC (a 7 x 3 lattice TIN of 50 m, a layer thinning from 30 m to zero between
// x = 200 and 250 against a sloping top), its pinch-out ended at a wall (terrain::end_pinch_outs):
// meshed at a 15 m spacing, every tetrahedron has its dihedral angles at 5 degrees or more and
// radius-edge at most 2.
TEST(TerrainRun, PinchOutPlcEndedAtAWallMeshesWithoutSlivers) {
  terrain::Tin tin;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 7; ++i) tin.xy.push_back({50.0 * i, 50.0 * j});
  for (VertexId j = 0; j < 2; ++j)
    for (VertexId i = 0; i < 6; ++i) {
      const VertexId a = j * 7 + i, b = a + 1, c = a + 8, d = a + 7;
      tin.triangles.push_back({a, b, c});
      tin.triangles.push_back({a, c, d});
    }
  std::vector<terrain::Surface> stack{{"top", {}}, {"h1", {}}, {"base", {}}};
  for (const Point2 q : tin.xy) {
    const double top = 100 + 0.05 * q.x + 0.02 * q.y;
    stack[0].z.push_back(top);
    stack[1].z.push_back(top - std::max(0.0, 30 - 0.12 * q.x) + 0.01 * q.y);  // 6 m at x = 200, zero from 250
    stack[2].z.push_back(0);
  }
  terrain::clamp_surfaces(stack, tin, {});
  const terrain::PinchOutRepair r = terrain::end_pinch_outs(tin, stack);
  EXPECT_GT(r.triangles[0], 0u);
  const terrain::TerrainPlc tp = terrain::build_terrain_plc(tin, stack, r.layering);
  const TetResult t = fdr::tetrahedralize(tp.plc, "15");
  const auto f = sizing::make_spacing3("15");
  quality::TetValues v;
  quality::measure_tets(t.mesh, *f, t.stats, &v);
  ASSERT_FALSE(v.min_dihedral_deg.empty());
  EXPECT_GE(*std::min_element(v.min_dihedral_deg.begin(), v.min_dihedral_deg.end()), 5.0);
  EXPECT_LE(*std::max_element(v.radius_edge.begin(), v.radius_edge.end()), 2.0);
}

TEST(TerrainRun, PlcOnly) {
  const fs::path dir = fresh_dir("plc");
  Options o = synthetic(dir);
  o.outputs = {(dir / "t.poly").string()};
  const Result3 r = run3d(o, {}, {});
  EXPECT_TRUE(r.mesh.tets.empty());
  EXPECT_NE(slurp(dir / "t.poly").find("500"), std::string::npos);
  fs::remove_all(dir);
}

TEST(TerrainRun, IsGpkgPath) {
  EXPECT_TRUE(is_gpkg_path("top.gpkg"));
  EXPECT_TRUE(is_gpkg_path("dir/Top.GPKG"));
  EXPECT_FALSE(is_gpkg_path(".gpk"));
  EXPECT_FALSE(is_gpkg_path("top.gpkg.vtu"));
}

// The top surface's GeoPackage goes with the volume: written beside it, removed when a later
// output cannot be written.
TEST(TerrainRun, TopGpkgAllOrNothing) {
  const fs::path dir = fresh_dir("gpkg");
  Options o = synthetic(dir);
  o.outputs = {(dir / "top.gpkg").string(), (dir / "m.vtu").string()};
  const Result3 r = run3d(o, {}, {});
  EXPECT_TRUE(fs::exists(dir / "top.gpkg"));
  EXPECT_EQ(r.written, o.outputs);
  const auto meta = terrain_metadata(r, {"top", "synthetic_h1", "base"});
  const std::vector<std::pair<std::string, std::string>> names = {
      {"terrain_surfaces", "top,synthetic_h1,base"}, {"terrain_marker_1", "top"}, {"terrain_marker_2", "base"},
      {"terrain_marker_3", "side"}, {"terrain_marker_4", "synthetic_h1"}, {"terrain_layer_1", "top-synthetic_h1"},
      {"terrain_layer_2", "synthetic_h1-base"}};
  for (const auto& kv : names) EXPECT_NE(std::find(meta.begin(), meta.end(), kv), meta.end()) << kv.first;
  EXPECT_EQ(meta.back().first, "terrain_layers");
  fs::remove_all(dir);
  fs::create_directories(dir);
  o.outputs = {(dir / "top.gpkg").string(), (dir / "no_such_dir" / "m.vtu").string()};
  EXPECT_EQ(run_code(o), 8);
  EXPECT_TRUE(fs::is_empty(dir));
  fs::remove_all(dir);
}

TEST(TerrainRun, BadInputsWriteNothing) {
  const fs::path dir = fresh_dir("bad");
  Options high = synthetic(dir);
  high.horizons = {kTerrain + "synthetic_high.tif"};  // above the DEM everywhere
  EXPECT_EQ(run_code(high), 5);
  Options base = synthetic(dir);
  base.base = "330";  // above the DEM in places
  EXPECT_EQ(run_code(base), 5);
  Options nocrs = synthetic(dir);
  nocrs.horizons = {kTerrain + "synthetic_nocrs.tif"};
  EXPECT_EQ(run_code(nocrs), 9);
  Options nodata = synthetic(dir);
  nodata.horizons = {kTerrain + "synthetic_nodata.tif"};
  EXPECT_EQ(run_code(nodata), 6);
  Options missing = synthetic(dir);
  missing.base = kTerrain + "no_such_base.tif";
  EXPECT_EQ(run_code(missing), 3);
  EXPECT_TRUE(fs::is_empty(dir));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace fdr::pipeline
