// Terrain volumes with wells (--wells), the domain from the DEM (no INPUT), and bad inputs with
// their exit codes and messages, on the synthetic rasters of testdata/terrain.
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <unistd.h>
#include <gdal_priv.h>
#include <gdal_utils.h>
#include <ogrsf_frmts.h>
#include "base/error.hpp"
#include "pipeline/run3d.hpp"
#include "pipeline/terrain_run.hpp"

namespace fdr::pipeline {
namespace {

namespace fs = std::filesystem;
const std::string kTerrain = std::string(FDR_TESTDATA_DIR) + "/terrain/";

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("fdr_terrain_wells_" + name + "_" + std::to_string(::getpid()));
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

// The exit code and message of a run, and its warnings.
struct Outcome {
  int code = 0;
  std::string message, warnings;
};

Outcome run_outcome(const Options& o) {
  Outcome out;
  const LogFn log = [&](LogLevel l, std::string_view m) {
    if (l == LogLevel::kWarning) out.warnings += std::string(m) + "\n";
  };
  try {
    run3d(o, {}, log);
  } catch (const Error& e) {
    out.code = e.exit_code();
    out.message = e.what();
  }
  return out;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Rows of a TetGen file as written (1-based ids), the header row dropped.
std::vector<std::vector<double>> tetgen_rows(const fs::path& p) {
  std::ifstream in(p);
  std::vector<std::vector<double>> rows;
  std::string line;
  bool header = true;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ls(line);
    std::vector<double> r;
    for (double v; ls >> v;) r.push_back(v);
    if (!header) rows.push_back(std::move(r));
    header = false;
  }
  return rows;
}

double circumradius(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  const Point3 u = b - a, v = c - a, w = d - a;
  const Point3 n = dot(u, u) * cross(v, w) + dot(v, v) * cross(w, u) + dot(w, w) * cross(u, v);
  return std::sqrt(dot(n, n)) / std::abs(2 * dot(u, cross(v, w)));
}

TEST(TerrainWells, SegmentsAreMeshEdgesAndTheTetsAroundThemSmall) {
  const fs::path dir = fresh_dir("two");
  Options o = synthetic(dir);
  o.wells = kTerrain + "synthetic_wells.geojson";
  o.well_spacing = 40;
  o.check = true;
  o.outputs.push_back((dir / "top.gpkg").string());
  o.outputs.push_back((dir / "m.node").string());
  const Outcome oc = run_outcome(o);  // for the warnings: BH1's top is above the DEM
  ASSERT_EQ(oc.code, 0) << oc.message;
  EXPECT_NE(oc.warnings.find("BH1) at (501000, 5501000): clipped to the DEM"), std::string::npos) << oc.warnings;
  const Result3 r = run3d(o, {}, {});
  // The written mesh (TetGen .node/.ele/.edge), the markers' names from the run.
  tet::TetMesh m;
  m.marker_names = r.mesh.marker_names;
  for (const auto& row : tetgen_rows(dir / "m.node")) m.points.push_back({row.at(1), row.at(2), row.at(3)});
  for (const auto& row : tetgen_rows(dir / "m.ele"))
    m.tets.push_back({static_cast<VertexId>(row.at(1) - 1), static_cast<VertexId>(row.at(2) - 1),
                      static_cast<VertexId>(row.at(3) - 1), static_cast<VertexId>(row.at(4) - 1)});
  EXPECT_EQ(m.points, r.mesh.points);
  EXPECT_EQ(m.tets.size(), r.mesh.tets.size());
  ASSERT_GE(m.marker_names.size(), 7u);
  std::map<std::int32_t, std::vector<std::array<VertexId, 2>>> by_well;
  for (const auto& row : tetgen_rows(dir / "m.edge")) {
    const auto marker = static_cast<std::int32_t>(row.at(3));
    if (m.marker_names.at(marker).rfind("well_", 0) == 0)
      by_well[marker].push_back({static_cast<VertexId>(row.at(1) - 1), static_cast<VertexId>(row.at(2) - 1)});
  }
  ASSERT_EQ(by_well.size(), 2u);
  // Each well is a chain of mesh edges on one vertical, from the DEM (BH1, clipped) or 20 m below
  // it (BH2) down to its bottom, without gaps; every piece no longer than the well spacing allows.
  std::set<VertexId> on_well;
  for (auto& [marker, edges] : by_well) {
    const std::string name = m.marker_names[marker];
    std::vector<std::pair<double, double>> spans;
    const Point3 p0 = m.points[edges[0][0]];
    for (const auto& e : edges) {
      const Point3 a = m.points[e[0]], b = m.points[e[1]];
      EXPECT_EQ(a.x, p0.x);
      EXPECT_EQ(b.y, p0.y);
      spans.push_back(std::minmax(a.z, b.z));
      on_well.insert(e[0]), on_well.insert(e[1]);
    }
    std::sort(spans.begin(), spans.end());
    for (std::size_t k = 1; k < spans.size(); ++k) EXPECT_EQ(spans[k].first, spans[k - 1].second) << name;
    if (name == "well_BH1") {
      EXPECT_EQ(spans.front().first, -150);
      EXPECT_GT(spans.back().second, 270);  // the DEM there
    } else {
      EXPECT_EQ(name, "well_BH2");
      EXPECT_NEAR(spans.back().second - spans.front().first, 230, 1e-6);
    }
  }
  // R <= B f(c) and f(c) <= f(p) + alpha |c - p| for p on the well give R <= B h / (1 - alpha B).
  const double B = r.report.bound_B, alpha = o.gradation;
  ASSERT_LT(alpha * B, 1);
  const double rmax = B * *o.well_spacing / (1 - alpha * B);
  std::size_t near = 0;
  for (const auto& t : m.tets) {
    if (std::none_of(t.begin(), t.end(), [&](VertexId v) { return on_well.count(v) > 0; })) continue;
    ++near;
    EXPECT_LE(circumradius(m.points[t[0]], m.points[t[1]], m.points[t[2]], m.points[t[3]]), rmax);
  }
  EXPECT_GT(near, 20u);
  const std::string msh = slurp(dir / "m.msh");
  EXPECT_NE(msh.find("\"well_BH1\""), std::string::npos);
  EXPECT_NE(msh.find("\"well_BH2\""), std::string::npos);
  GDALAllRegister();
  GDALDataset* ds = GDALDataset::Open((dir / "top.gpkg").c_str(), GDAL_OF_VECTOR);
  ASSERT_NE(ds, nullptr);
  OGRLayer* wells = ds->GetLayerByName("wells");
  ASSERT_NE(wells, nullptr);
  EXPECT_EQ(wells->GetFeatureCount(), 2);
  GDALClose(ds);
  fs::remove_all(dir);
}

TEST(TerrainWells, UsageErrors) {
  Options o = synthetic(fs::temp_directory_path());
  o.wells = kTerrain + "synthetic_wells.geojson";
  EXPECT_NO_THROW(check_terrain_options(o));
  Options a = o;
  a.points = o.wells;
  EXPECT_THROW(check_terrain_options(a), Error);
  Options b = o;
  b.well_spacing = 0;
  EXPECT_THROW(check_terrain_options(b), Error);
  Options c = synthetic(fs::temp_directory_path());
  c.well_spacing = 10;
  EXPECT_THROW(check_terrain_options(c), Error);
  Options d;
  d.wells = "w.gpkg";
  EXPECT_THROW(check_no_terrain_options(d), Error);
}

TEST(TerrainWells, DomainFromTheDemsValidData) {
  const fs::path dir = fresh_dir("extent");
  Options o = synthetic(dir);
  o.input.clear();
  o.horizons.clear();
  o.hmin = 300;
  o.hmax = 600;
  const Result3 r = run3d(o, {}, {});
  ASSERT_FALSE(r.mesh.points.empty());
  Box3 box;
  for (const Point3& p : r.mesh.points) box.add(p);
  // The DEM: 24 x 24 cells of 100 m from (500000, 5502400); the domain joins the outer cells' centres.
  EXPECT_EQ(box.lo.x, 500050);
  EXPECT_EQ(box.hi.x, 502350);
  EXPECT_EQ(box.lo.y, 5500050);
  EXPECT_EQ(box.hi.y, 5502350);
  EXPECT_EQ(r.report.input_file, o.dem);
  fs::remove_all(dir);
}

// A copy of a synthetic raster warped to another CRS (Web Mercator).
std::string warped(const std::string& src, const fs::path& dir) {
  GDALAllRegister();
  const std::string out = (dir / "warped.tif").string();
  GDALDatasetH in = GDALOpen(src.c_str(), GA_ReadOnly);
  char* argv[] = {const_cast<char*>("-t_srs"), const_cast<char*>("EPSG:3857"), nullptr};
  GDALWarpAppOptions* opts = GDALWarpAppOptionsNew(argv, nullptr);
  int err = 0;
  GDALDatasetH o = GDALWarp(out.c_str(), nullptr, 1, &in, opts, &err);
  GDALWarpAppOptionsFree(opts);
  GDALClose(o);
  GDALClose(in);
  return out;
}

TEST(TerrainWells, BadInputsExitCodesAndMessages) {
  const fs::path dir = fresh_dir("bad");
  const fs::path out = dir / "out";
  fs::create_directories(out);
  // A horizon above the DEM in places: clamped, the vertices counted in a warning.
  Options partial = synthetic(out);
  partial.horizons = {kTerrain + "synthetic_pinch.tif"};
  partial.min_thickness = 80;
  partial.outputs = {(out / "m.vtu").string()};
  const Outcome p = run_outcome(partial);
  EXPECT_EQ(p.code, 0) << p.message;
  EXPECT_NE(p.warnings.find("lowered onto the surface above"), std::string::npos) << p.warnings;
  fs::remove_all(out);
  fs::create_directories(out);
  struct Case {
    const char* what;
    Options o;
    int code;
    std::string needle;
  };
  std::vector<Case> cases;
  Options high = synthetic(out);
  high.horizons = {kTerrain + "synthetic_high.tif"};
  cases.push_back({"horizon above the DEM everywhere", high, 5, "synthetic_high"});
  Options base = synthetic(out);
  base.base = "330";
  cases.push_back({"base above the surface", base, 5, "base"});
  Options nocrs = synthetic(out);
  nocrs.horizons = {kTerrain + "synthetic_nocrs.tif"};
  cases.push_back({"raster without a CRS", nocrs, 9, "--horizon " + kTerrain + "synthetic_nocrs.tif"});
  Options nodata = synthetic(out);
  nodata.horizons = {kTerrain + "synthetic_nodata.tif"};
  cases.push_back({"all-nodata raster", nodata, 6, "--horizon " + kTerrain + "synthetic_nodata.tif"});
  Options dem_nodata = synthetic(out);
  dem_nodata.input.clear();
  dem_nodata.dem = kTerrain + "synthetic_nodata.tif";
  cases.push_back({"all-nodata DEM as the domain", dem_nodata, 6, "no valid cell (all nodata)"});
  Options outside = synthetic(out);
  outside.wells = kTerrain + "synthetic_wells_outside.geojson";
  cases.push_back({"well outside the domain", outside, 5, "(far) at (503500, 5503500): the well lies outside the domain"});
  Options deep = synthetic(out);
  deep.wells = kTerrain + "synthetic_wells.geojson";
  deep.base = "400";  // the base above the DEM: refused before any well
  cases.push_back({"base above the surface with wells", deep, 5, "base"});
  for (const Case& c : cases) {
    const Outcome oc = run_outcome(c.o);
    EXPECT_EQ(oc.code, c.code) << c.what << ": " << oc.message;
    EXPECT_NE(oc.message.find(c.needle), std::string::npos) << c.what << ": " << oc.message;
  }
  EXPECT_TRUE(fs::is_empty(out));
  // A horizon in another CRS is warped into the working CRS: the same layers.
  Options other = synthetic(out);
  other.horizons = {warped(kTerrain + "synthetic_h1.tif", dir)};
  const Outcome w = run_outcome(other);
  EXPECT_EQ(w.code, 0) << w.message;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace fdr::pipeline
