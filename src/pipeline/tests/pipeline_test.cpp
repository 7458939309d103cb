// Whole-pipeline tests on real extracts: invariants (--check), area, outputs read back, CRS, errors.
#include <gtest/gtest.h>

#include <gdal_priv.h>
#include <netcdf.h>
#include <ogrsf_frmts.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <map>
#include <random>
#include <set>

#include "base/error.hpp"
#include "io/reader.hpp"
#include "pipeline/gis_stage.hpp"
#include "pipeline/pipeline.hpp"
#include "pipeline_test_util.hpp"

using namespace fdr;
using namespace fdr::pipeline;
using namespace fdr::pipeline::testing_util;
namespace fs = std::filesystem;

namespace {

const std::string kT = FDR_TESTDATA_DIR;
const std::string kChes = kT + "/chesapeake/";

Options chesapeake(const std::string& water = kChes + "chesapeake_mouth_water.geojson",
                   const std::string& open = kChes + "chesapeake_mouth_open_boundary.geojson") {
  Options o;
  o.input = water;
  o.open_boundary = open;
  o.raster = kChes + "chesapeake_mouth_etopo5.tif";
  o.check = true;
  o.quiet = true;
  return o;
}

// Number of features of `layer` in the vector dataset `path` (-1 if the layer is missing).
long long feature_count(const std::string& path, const std::string& layer, int* epsg = nullptr) {
  GDALAllRegister();
  GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
  if (!ds) return -2;
  OGRLayer* l = ds->GetLayerByName(layer.c_str());
  if (!l) return -1;
  if (epsg) {
    *epsg = 0;
    if (const OGRSpatialReference* s = l->GetSpatialRef(); s && s->GetAuthorityCode(nullptr))
      *epsg = std::atoi(s->GetAuthorityCode(nullptr));
  }
  return l->GetFeatureCount(TRUE);
}

// Checks that two meshes have the same triangles (as vertex triples, in order).
void expect_same_topology(const mesh::MeshView& a, const mesh::MeshView& b) {
  ASSERT_EQ(a.num_vertices(), b.num_vertices());
  ASSERT_EQ(a.num_triangles(), b.num_triangles());
  for (std::size_t t = 0; t < a.num_triangles(); ++t) ASSERT_EQ(a.triangles[t], b.triangles[t]) << "triangle " << t;
}

}  // namespace

// Chesapeake mouth from GeoJSON: every output format written and read back, CRS stored,
// depths finite, mesh area = repaired domain area (independent parity sweep of the cleaned PSLG).
TEST(PipelineChesapeake, GeoJsonAllOutputsReadBack) {
  TempDir dir("ches");
  Options o = chesapeake();
  for (const char* n : {"m.gpkg", "m.2dm", "m.14", "m.nc", "m.msh"}) o.outputs.push_back(dir.file(n));
  o.report_json = dir.file("r.json");
  o.write_spacing = dir.file("f.tif");
  Result r = run(o, nullptr, nullptr);

  const mesh::MeshView& m = r.mesh;
  ASSERT_GT(m.num_triangles(), 1000u);
  EXPECT_NE(r.crs_name.find("32618"), std::string::npos) << r.crs_name;
  EXPECT_EQ(r.report.triangles, m.num_triangles());
  EXPECT_EQ(r.report.bad_triangles.value_or(1), 0u);
  EXPECT_LE(r.report.max_R_over_f.value_or(2), 1.0);
  ASSERT_EQ(m.z.size(), m.num_vertices());
  for (double z : m.z) ASSERT_TRUE(std::isfinite(z));
  // ETOPO5 in the bay: elevations between -30 and +60 m (README: -22 / 53).
  const auto [zmin, zmax] = std::minmax_element(m.z.begin(), m.z.end());
  EXPECT_GE(*zmin, -30.0);
  EXPECT_LE(*zmax, 60.0);

  // Area: the mesh covers exactly the region enclosed by the cleaned PSLG (parity).
  PreparedInput in = prepare_gis_input(o, nullptr, nullptr);
  const double a_mesh = mesh_area(m), a_pslg = parity_area(in.pslg);
  EXPECT_NEAR(a_mesh / a_pslg, 1.0, 1e-9);
  // ... and the domain area within the coast resampling tolerance (the model-ready default
  // closes sub-resolution water and resamples the coast to f; the issue allows 1 %).
  EXPECT_NEAR(a_mesh / metadata_double(in, "domain_area_m2"), 1.0, 2e-3);
  EXPECT_NEAR(a_mesh / 5894.49e6, 1.0, 2e-3);

  // GeoPackage: feature counts equal the report counts, EPSG:32618 stored.
  int epsg = 0;
  EXPECT_EQ(feature_count(dir.file("m.gpkg"), "nodes", &epsg), static_cast<long long>(r.report.vertices));
  EXPECT_EQ(epsg, 32618);
  EXPECT_EQ(feature_count(dir.file("m.gpkg"), "triangles", &epsg), static_cast<long long>(r.report.triangles));
  EXPECT_EQ(epsg, 32618);
  EXPECT_GT(feature_count(dir.file("m.gpkg"), "boundaries"), 0);
  EXPECT_EQ(feature_count(dir.file("m.gpkg"), "repairs"), static_cast<long long>(r.repairs));
  EXPECT_GT(feature_count(dir.file("m.gpkg"), "metadata"), 0);

  // 2DM, fort.14, msh: same mesh read back (world coordinates, same triangles, same area).
  for (const char* n : {"m.2dm", "m.14", "m.msh"}) {
    SCOPED_TRACE(n);
    mesh::MeshView b = io::read_mesh(dir.file(n));
    expect_same_topology(m, b);
    double max_dxy = 0;
    for (std::size_t v = 0; v < m.num_vertices(); ++v) {
      const Point2 w = m.world(static_cast<Index>(v)), q = b.world(static_cast<Index>(v));
      max_dxy = std::max({max_dxy, std::fabs(w.x - q.x), std::fabs(w.y - q.y)});
    }
    EXPECT_LT(max_dxy, 1e-3);  // metres; every format keeps at least millimetres
    EXPECT_NEAR(mesh_area(b) / a_mesh, 1.0, 1e-9);
    if (std::string(n) != "m.msh") {
      ASSERT_EQ(b.z.size(), m.num_vertices());
      for (std::size_t v = 0; v < m.num_vertices(); ++v) ASSERT_NEAR(b.z[v], m.z[v], 1e-3);
    }
  }

  // UGRID through netCDF: node/face counts and the crs variable.
  {
    int nc = -1;
    ASSERT_EQ(nc_open(dir.file("m.nc").c_str(), NC_NOWRITE, &nc), NC_NOERR);
    int d = -1;
    std::size_t len = 0;
    ASSERT_EQ(nc_inq_dimid(nc, "nmesh2d_node", &d), NC_NOERR);
    nc_inq_dimlen(nc, d, &len);
    EXPECT_EQ(len, m.num_vertices());
    ASSERT_EQ(nc_inq_dimid(nc, "nmesh2d_face", &d), NC_NOERR);
    nc_inq_dimlen(nc, d, &len);
    EXPECT_EQ(len, m.num_triangles());
    int vcrs = -1, code = 0;
    ASSERT_EQ(nc_inq_varid(nc, "crs", &vcrs), NC_NOERR);
    ASSERT_EQ(nc_get_att_int(nc, vcrs, "epsg", &code), NC_NOERR);
    EXPECT_EQ(code, 32618);
    std::vector<int> faces(3 * m.num_triangles());
    int vf = -1;
    ASSERT_EQ(nc_inq_varid(nc, "mesh2d_face_nodes", &vf), NC_NOERR);
    ASSERT_EQ(nc_get_var_int(nc, vf, faces.data()), NC_NOERR);
    int start = 0;
    if (nc_get_att_int(nc, vf, "start_index", &start) != NC_NOERR) start = 0;
    for (std::size_t t = 0; t < m.num_triangles(); ++t)
      for (int k = 0; k < 3; ++k) ASSERT_EQ(static_cast<Index>(faces[3 * t + k] - start), m.triangles[t][k]);
    nc_close(nc);
  }

  // Report JSON: same counts as the in-memory report.
  {
    std::ifstream js(dir.file("r.json"));
    const auto j = nlohmann::json::parse(js);
    EXPECT_EQ(j.at("vertices").get<std::size_t>(), r.report.vertices);
    EXPECT_EQ(j.at("triangles").get<std::size_t>(), r.report.triangles);
  }

  // --write-spacing: a GeoTIFF in EPSG:32618 whose values lie in [hmin, hmax].
  {
    GDALDatasetUniquePtr ds(GDALDataset::Open(dir.file("f.tif").c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
    ASSERT_TRUE(ds);
    const OGRSpatialReference* s = ds->GetSpatialRef();
    ASSERT_TRUE(s && s->GetAuthorityCode(nullptr));
    EXPECT_STREQ(s->GetAuthorityCode(nullptr), "32618");
    double mm[2];
    ASSERT_EQ(ds->GetRasterBand(1)->ComputeRasterMinMax(FALSE, mm), CE_None);
    EXPECT_GT(mm[0], 200.0);   // hmin: the ETOPO5 cell size projected, ~287 m
    EXPECT_LT(mm[1], 7200.0);  // hmax: a twentieth of the domain diagonal
    EXPECT_LT(mm[0], mm[1]);
  }

  // Stage timings: every stage named once, in pipeline order.
  std::vector<std::string> names;
  for (const auto& s : r.stages) {
    names.push_back(s.name);
    EXPECT_GE(s.seconds, 0.0);
  }
  // ("listing": the wait for the filter's removed-water listing after the refinement.)
  EXPECT_EQ(names, (std::vector<std::string>{"read", "raster", "sizing", "limit", "repair", "resample", "cdt", "refine",
                                             "listing", "smooth", "check", "depths", "report", "write"}));
  EXPECT_EQ(r.written.size(), 6u);
  EXPECT_EQ(dir.list(), (std::set<std::string>{"m.gpkg", "m.2dm", "m.14", "m.nc", "m.msh", "r.json", "f.tif"}));
}

// The same water and open boundary as Shapefile and as GeoPackage layers: same domain, same mesh size.
TEST(PipelineChesapeake, ShapefileAndGpkgInputsAgreeWithGeoJson) {
  Result gj = run(chesapeake(), nullptr, nullptr);
  Options shp = chesapeake(kChes + "shp/chesapeake_mouth_water.shp", kChes + "shp/chesapeake_mouth_open_boundary.shp");
  Result rs = run(shp, nullptr, nullptr);
  Options gp = chesapeake(kChes + "chesapeake_mouth.gpkg", kChes + "chesapeake_mouth.gpkg");
  gp.layer = "water";
  gp.open_boundary_layer = "open_boundary";
  Result rg = run(gp, nullptr, nullptr);
  for (const Result* r : {&rs, &rg}) {
    EXPECT_EQ(r->crs_name, gj.crs_name);
    // (GeoJSON keeps fewer digits: the widened banks, new coast, differ by that rounding)
    EXPECT_NEAR(mesh_area(r->mesh) / mesh_area(gj.mesh), 1.0, 1e-6);
    EXPECT_NEAR(static_cast<double>(r->mesh.num_triangles()) / static_cast<double>(gj.mesh.num_triangles()), 1.0, 0.02);
    EXPECT_EQ(r->report.bad_triangles.value_or(1), 0u);
    // Open-boundary edges found in every encoding.
    std::size_t open = 0;
    for (const auto& e : r->mesh.edges) open += e.marker == static_cast<int>(mesh::EdgeKind::kOpen);
    EXPECT_GT(open, 12u);
  }
  // Without --open-boundary-layer the first layer of the GPKG (water polygons) is not a line layer.
  gp.open_boundary_layer.clear();
  try {
    run(gp, nullptr, nullptr);
    ADD_FAILURE() << "polygons as open boundary accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidGeometry) << e.what();
    EXPECT_NE(std::string(e.what()).find("chesapeake_mouth.gpkg"), std::string::npos) << e.what();
  }
}

// --output-crs EPSG:4326: lon/lat nodes in the region box, same triangles as the projected mesh.
TEST(PipelineChesapeake, OutputCrsLonLatKeepsTopology) {
  TempDir dir("crs");
  Options o = chesapeake();
  o.check = false;
  o.outputs = {dir.file("utm.2dm")};
  Result a = run(o, nullptr, nullptr);
  o.output_crs = "EPSG:4326";
  o.outputs = {dir.file("ll.2dm"), dir.file("ll.gpkg")};
  Result b = run(o, nullptr, nullptr);
  mesh::MeshView mu = io::read_mesh(dir.file("utm.2dm")), ml = io::read_mesh(dir.file("ll.2dm"));
  expect_same_topology(mu, ml);
  expect_same_topology(a.mesh, mu);
  // Steiner points on the open boundary lie on straight UTM chords of the box's meridians and
  // parallels; a parallel's image curves (radius ~ R / tan(lat) ~ 8000 km), so a 40 km chord
  // sags about 30 m (3e-4 deg) off the lon/lat box.
  const double tol = 1e-3;
  for (std::size_t v = 0; v < ml.num_vertices(); ++v) {
    const Point2 p = ml.world(static_cast<Index>(v));
    ASSERT_TRUE(p.x >= -76.6 - tol && p.x <= -75.6 + tol && p.y >= 36.75 - tol && p.y <= 37.75 + tol)
        << "vertex " << v << " at (" << p.x << ", " << p.y << ")";
  }
  // Every triangle stays counter-clockwise in lon/lat (UTM is conformal, no folds).
  for (const auto& t : ml.triangles) {
    const Point2 p = ml.vertices[t[0]], q = ml.vertices[t[1]], s = ml.vertices[t[2]];
    ASSERT_GT((q.x - p.x) * (s.y - p.y) - (q.y - p.y) * (s.x - p.x), 0.0);
  }
  int epsg = 0;
  EXPECT_EQ(feature_count(dir.file("ll.gpkg"), "triangles", &epsg), static_cast<long long>(b.report.triangles));
  EXPECT_EQ(epsg, 4326);
  EXPECT_EQ(a.report.triangles, b.report.triangles);
}

// Raw, unrepaired GSHHG rings (Boothbay, with a figure-eight ring): repaired, meshed, repairs layer written.
TEST(PipelineRaw, BoothbayRingsRawAreRepairedAndMeshed) {
  TempDir dir("raw");
  Options o;
  o.input = kT + "/raw/gulf_of_maine_boothbay_raw.gpkg";
  o.layer = "rings_raw";
  o.check = true;
  o.outputs = {dir.file("raw.gpkg")};
  Result r = run(o, nullptr, nullptr);
  EXPECT_GT(r.repairs, 0u);
  EXPECT_EQ(feature_count(dir.file("raw.gpkg"), "repairs"), static_cast<long long>(r.repairs));
  EXPECT_EQ(feature_count(dir.file("raw.gpkg"), "triangles"), static_cast<long long>(r.mesh.num_triangles()));
  PreparedInput in = prepare_gis_input(o, nullptr, nullptr);
  EXPECT_EQ(in.repairs.size(), r.repairs);
  EXPECT_NEAR(mesh_area(r.mesh) / parity_area(in.pslg), 1.0, 1e-9);
  // The raw area counts the figure-eight's lobes with opposite signs; repair changes it little.
  EXPECT_NEAR(mesh_area(r.mesh) / metadata_double(in, "domain_area_m2"), 1.0, 0.01);
}

// Gulf of Maine with WDBII rivers (not snapped to the coast) as breaklines.
TEST(PipelineGulfOfMaine, RiversAsBreaklines) {
  const std::string g = kT + "/gulf_of_maine/gulf_of_maine.gpkg";
  Options o;
  o.input = g;
  o.layer = "water";
  o.open_boundary = g;
  o.open_boundary_layer = "open_boundary";
  o.breaklines = g;
  o.breaklines_layer = "rivers_h";
  o.raster = kT + "/gulf_of_maine/gulf_of_maine_etopo5.tif";
  o.check = true;
  Result r = run(o, nullptr, nullptr);
  std::size_t brk = 0;
  for (const auto& e : r.mesh.edges) brk += e.marker == static_cast<int>(mesh::EdgeKind::kBreakline);
  EXPECT_GT(brk, 0u);
  PreparedInput in = prepare_gis_input(o, nullptr, nullptr);
  EXPECT_NEAR(mesh_area(r.mesh) / parity_area(in.pslg), 1.0, 1e-9);
  EXPECT_NEAR(mesh_area(r.mesh) / metadata_double(in, "domain_area_m2"), 1.0, 2e-3);
  // Rivers are clipped a hair (5 % of --close-width) inside the filtered coast and their ends are
  // put back on it: the coast segment is split there (within 10 % of --close-width).
  std::size_t snapped = 0;
  for (const auto& rep : in.repairs) snapped += rep.kind == "snap_to_segment" && rep.size <= 0.1 * 0.25 * 6900;
  EXPECT_GE(snapped, 1u);
  for (double z : r.mesh.z) ASSERT_TRUE(std::isfinite(z));
}

// Luxembourg terrain: cantons as the domain, their borders as breaklines, DEM curvature rule.
TEST(PipelineLuxembourg, TerrainWithCantonBordersAsBreaklines) {
  const std::string l = kT + "/luxembourg/";
  Options o;
  o.input = l + "lux.shp";
  o.breaklines = l + "lux_borders.gpkg";
  o.raster = l + "elev.tif";
  o.vertical_tol = 5.0;
  o.check = true;
  Result r = run(o, nullptr, nullptr);
  std::size_t brk = 0;
  for (const auto& e : r.mesh.edges) brk += e.marker == static_cast<int>(mesh::EdgeKind::kBreakline);
  EXPECT_GT(brk, 500u);  // borders resampled to f (about 800 edges; 1300+ with --keep-coast)
  PreparedInput in = prepare_gis_input(o, nullptr, nullptr);
  // Cantons share borders: the domain is their union (2565.5 km^2); breaklines must not cut cantons out.
  // (domain_area_m2 is measured on the raw rings; cleaning snaps 1706 shared-border vertices, which
  // moves the area by about 2e-6 relative.)
  EXPECT_NEAR(mesh_area(r.mesh) / metadata_double(in, "domain_area_m2"), 1.0, 2e-3);
  EXPECT_NEAR(mesh_area(r.mesh) / 2565.53e6, 1.0, 2e-3);
  ASSERT_EQ(r.mesh.z.size(), r.mesh.num_vertices());
  for (double z : r.mesh.z) {
    ASSERT_TRUE(std::isfinite(z));
    ASSERT_GE(z, 100.0);  // DEM range 141..547 m
    ASSERT_LE(z, 600.0);
  }
  EXPECT_NE(r.crs_name.find("32632"), std::string::npos) << r.crs_name;
  // The report carries the TIN's vertical error against the DEM; the curvature rule keeps the RMS
  // within the tolerance (the maximum can exceed it where hmin caps the refinement).
  ASSERT_TRUE(r.report.vertical_error_rms_m.has_value());
  EXPECT_LE(*r.report.vertical_error_rms_m, 5.0);
  EXPECT_GE(*r.report.vertical_error_max_m, *r.report.vertical_error_rms_m);
}

// ---- error cases: exit code, message naming the file, no output left behind ----

struct ErrorCase {
  const char* name;
  std::function<void(Options&, const TempDir&)> setup;
  ExitCode code;
  std::function<std::string(const Options&)> must_name;  // substring the message must contain
};

void PrintTo(const ErrorCase& c, std::ostream* os) { *os << c.name; }

class PipelineErrors : public ::testing::TestWithParam<ErrorCase> {};

TEST_P(PipelineErrors, ExitCodeMessageAndNoOutput) {
  const ErrorCase& c = GetParam();
  TempDir dir("err");
  Options o = chesapeake();
  o.check = false;
  o.outputs = {dir.file("m.gpkg"), dir.file("m.2dm")};
  o.report_json = dir.file("r.json");
  o.write_spacing = dir.file("f.tif");
  c.setup(o, dir);
  const std::set<std::string> before = dir.list();
  try {
    run(o, nullptr, nullptr);
    ADD_FAILURE() << c.name << ": no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), c.code) << e.what();
    const std::string want = c.must_name(o);
    EXPECT_NE(std::string(e.what()).find(want), std::string::npos) << "message '" << e.what() << "' lacks '" << want << "'";
  }
  EXPECT_EQ(dir.list(), before);  // nothing written, no temporary left
}

std::string base(const std::string& p) { return fs::path(p).filename().string(); }

INSTANTIATE_TEST_SUITE_P(
    Cases, PipelineErrors,
    ::testing::Values(
        ErrorCase{"missing_file", [](Options& o, const TempDir&) { o.input = kChes + "no_such_water.geojson"; },
                  ExitCode::kInputUnreadable, [](const Options& o) { return base(o.input); }},
        ErrorCase{"missing_open_boundary", [](Options& o, const TempDir&) { o.open_boundary = kChes + "nope.shp"; },
                  ExitCode::kInputUnreadable, [](const Options& o) { return base(o.open_boundary); }},
        ErrorCase{"unreadable_layer",
                  [](Options& o, const TempDir&) {
                    o.input = kChes + "chesapeake_mouth.gpkg";
                    o.layer = "no_such_layer";
                  },
                  ExitCode::kInputUnreadable, [](const Options&) { return std::string("no_such_layer"); }},
        ErrorCase{"not_a_vector_file",
                  [](Options& o, const TempDir& d) {
                    std::ofstream(d.file("garbage.geojson")) << "{ this is not json";
                    o.input = d.file("garbage.geojson");
                  },
                  ExitCode::kInputUnreadable, [](const Options& o) { return base(o.input); }},
        ErrorCase{"no_polygons",
                  [](Options& o, const TempDir&) { o.input = kChes + "chesapeake_mouth_open_boundary.geojson"; },
                  ExitCode::kInvalidGeometry, [](const Options& o) { return base(o.input); }},
        ErrorCase{"empty_selection", [](Options& o, const TempDir&) { o.where = "id = 99999"; },
                  ExitCode::kInvalidGeometry, [](const Options& o) { return base(o.input); }},
        ErrorCase{"raster_not_covering",
                  [](Options& o, const TempDir&) { o.raster = kT + "/luxembourg/elev.tif"; },
                  ExitCode::kInvalidSpacing, [](const Options& o) { return base(o.raster); }},
        ErrorCase{"nodata_everywhere",
                  [](Options& o, const TempDir& d) {
                    o.raster = d.file("nodata.tif");
                    write_nodata_raster(o.raster, -76.8, 36.6, 0.1, 14, 13);
                  },
                  ExitCode::kInvalidSpacing, [](const Options& o) { return base(o.raster); }},
        ErrorCase{"negative_hmin", [](Options& o, const TempDir&) { o.hmin = -5.0; }, ExitCode::kInvalidSpacing,
                  [](const Options&) { return std::string("hmin"); }},
        ErrorCase{"zero_hmax", [](Options& o, const TempDir&) { o.hmin = 0.0; o.hmax = 0.0; },
                  ExitCode::kInvalidSpacing, [](const Options&) { return std::string("hmin"); }},
        ErrorCase{"negative_spacing_expression",
                  [](Options& o, const TempDir&) {
                    o.raster.clear();
                    o.write_spacing.clear();
                    o.spacing = "-100";
                  },
                  ExitCode::kInvalidSpacing, [](const Options&) { return std::string("-100"); }},
        ErrorCase{"unknown_t_srs", [](Options& o, const TempDir&) { o.t_srs = "EPSG:999999"; }, ExitCode::kCrsError,
                  [](const Options&) { return std::string("EPSG:999999"); }},
        ErrorCase{"unknown_output_crs", [](Options& o, const TempDir&) { o.output_crs = "EPSG:123456789"; },
                  ExitCode::kCrsError, [](const Options&) { return std::string("EPSG:123456789"); }},
        ErrorCase{"output_folder_missing",
                  [](Options& o, const TempDir& d) { o.outputs = {d.file("m.2dm"), d.file("no/such/dir/m.gpkg")}; },
                  ExitCode::kOutputError, [](const Options&) { return std::string("no/such/dir/m.gpkg"); }}),
    [](const ::testing::TestParamInfo<ErrorCase>& i) { return std::string(i.param.name); });

// Issue 10: a messy .poly is resolved (repairs in the JSON report and the GeoPackage repairs
// layer, with kinds, world coordinates and input ids); --strict refuses it and writes nothing.
TEST(PipelinePoly, MessyConstraintsResolvedAndReported) {
  TempDir dir("messy");
  Options o;
  o.input = kT + "/poly/messy_star.poly";
  o.check = true;
  o.quiet = true;
  o.outputs = {dir.file("m.gpkg")};
  o.report_json = dir.file("r.json");
  Result r = run(o, nullptr, nullptr);
  EXPECT_EQ(r.repairs, 17u);
  EXPECT_EQ(feature_count(dir.file("m.gpkg"), "repairs"), 17);
  std::ifstream in(dir.file("r.json"));
  const auto j = nlohmann::json::parse(in);
  ASSERT_TRUE(j.contains("repairs"));
  ASSERT_EQ(j["repairs"].size(), 17u);
  std::map<std::string, int> kinds;
  for (const auto& rp : j["repairs"]) {
    ++kinds[rp["kind"].get<std::string>()];
    EXPECT_TRUE(rp["x"].is_number() && rp["y"].is_number());
    EXPECT_FALSE(rp["ids"].empty()) << rp.dump();
  }
  EXPECT_EQ(kinds["crossing_split"], 9);
  EXPECT_EQ(kinds["duplicate_vertex"], 1);
  EXPECT_EQ(kinds["duplicate_segment"], 1);
  EXPECT_EQ(kinds["zero_length"], 1);
  EXPECT_EQ(kinds["vertex_on_segment"], 5);
  // The duplicate vertex 8 of vertex 0, named by input ids.
  for (const auto& rp : j["repairs"])
    if (rp["kind"] == "duplicate_vertex") { EXPECT_EQ(rp["ids"], nlohmann::json::array({8, 0})); }

  Options s = o;
  s.strict = true;
  s.outputs = {dir.file("s.gpkg")};
  s.report_json = dir.file("s.json");
  try {
    run(s, nullptr, nullptr);
    FAIL() << "--strict accepted a messy PSLG";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidGeometry);
    EXPECT_NE(std::string(e.what()).find("vertices 0 and 8 are both at (0, 0)"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir.file("s.gpkg")));
  EXPECT_FALSE(fs::exists(dir.file("s.json")));
}

// --convex-hull: survey points with a dangling breakline mesh (Triangle -c); without it the
// empty-domain error suggests the option.
TEST(PipelinePoly, ConvexHullForPointsAndDanglingBreaklines) {
  Options o;
  o.input = kT + "/poly/points_breakline.poly";
  o.check = true;
  o.quiet = true;
  try {
    run(o, nullptr, nullptr);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--convex-hull"), std::string::npos) << e.what();
  }
  o.convex_hull = true;
  Result r = run(o, nullptr, nullptr);
  EXPECT_GT(r.mesh.num_triangles(), 6u);
  EXPECT_NEAR(mesh_area(r.mesh), 52.5, 1e-9);  // hull (0,0) (8,0) (9,6) (1,7): shoelace area
}
