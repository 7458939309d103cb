// Wells read from OGR (the attribute names, 3D lines, refusals naming the feature), the in-memory
// point layer read back exactly, and the DEM's valid-data box as a domain; on files the test makes.
#include <gtest/gtest.h>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <gdal_priv.h>
#include <ogrsf_frmts.h>
#include "base/error.hpp"
#include "gis/crs.hpp"
#include "terrain/wells_gis.hpp"

namespace fdr::terrain {
namespace {

namespace fs = std::filesystem;

std::string tmp(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("fdr_wells_gis_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return (d / name).string();
}

// A feature of the test layer: a geometry (WKT) and optional numeric fields.
struct Row {
  std::string wkt;
  std::vector<std::pair<std::string, double>> fields;
  std::string name;
};

std::string make_layer(const std::string& file, const std::vector<Row>& rows, bool with_crs = true) {
  GDALAllRegister();
  const std::string path = tmp(file);
  fs::remove(path);
  // A GeoPackage layer always has some CRS (an undefined one at least): a shapefile without .prj has none.
  GDALDriver* drv = GetGDALDriverManager()->GetDriverByName(with_crs ? "GPKG" : "ESRI Shapefile");
  GDALDataset* ds = drv->Create(path.c_str(), 0, 0, 0, GDT_Unknown, nullptr);
  OGRSpatialReference srs;
  srs.importFromEPSG(32632);
  OGRLayer* l = ds->CreateLayer("wells", with_crs ? &srs : nullptr, wkbUnknown, nullptr);
  for (const char* f : {"top", "bottom", "depth_from", "depth_to"}) {
    OGRFieldDefn d(f, OFTReal);
    l->CreateField(&d);
  }
  OGRFieldDefn n("name", OFTString);
  l->CreateField(&n);
  for (const Row& r : rows) {
    OGRFeature f(l->GetLayerDefn());
    OGRGeometry* g = nullptr;
    OGRGeometryFactory::createFromWkt(r.wkt.c_str(), nullptr, &g);
    f.SetGeometryDirectly(g);
    for (const auto& [k, v] : r.fields) f.SetField(k.c_str(), v);
    if (!r.name.empty()) f.SetField("name", r.name.c_str());
    if (l->CreateFeature(&f) != OGRERR_NONE) ADD_FAILURE() << r.wkt;
  }
  GDALClose(ds);
  return path;
}

ExitCode code_of(const std::function<void()>& f, std::string* what) {
  try {
    f();
  } catch (const Error& e) {
    *what = e.what();
    return e.code();
  }
  return ExitCode::kOk;
}

const gis::Frame& frame() {
  static const gis::Frame f = gis::Frame::from_crs("EPSG:32632", {300000, 5500000});
  return f;
}

TEST(ReadWells, PointsWithElevationsOrDepthsAndA3dLine) {
  const std::string p = make_layer("good.gpkg", {{"POINT (300100 5500200)", {{"top", 50}, {"bottom", -100}}, "BH1"},
                                                 {"POINT (300300 5500400)", {{"depth_from", 5}, {"depth_to", 80}}, ""},
                                                 {"LINESTRING Z (300500 5500600 40, 300500 5500600 -60)", {}, "L"}});
  const std::vector<Well> w = read_wells({p, "", ""}, frame(), 1.0);
  ASSERT_EQ(w.size(), 3u);
  EXPECT_EQ(w[0].name, "BH1");
  EXPECT_EQ(w[0].kind, WellRangeKind::kElevation);
  EXPECT_EQ(w[0].upper, 50);
  EXPECT_EQ(w[0].lower, -100);
  EXPECT_NEAR(w[0].xy.x, 100, 1e-6);
  EXPECT_NEAR(w[0].xy.y, 200, 1e-6);
  EXPECT_EQ(w[1].name, "FID 2");
  EXPECT_EQ(w[1].kind, WellRangeKind::kDepth);
  EXPECT_EQ(w[1].upper, 5);
  EXPECT_EQ(w[1].lower, 80);
  EXPECT_EQ(w[2].upper, 40);
  EXPECT_EQ(w[2].lower, -60);
}

TEST(ReadWells, BadFeaturesAreErrorsNamingThem) {
  std::string what;
  const std::string nofield = make_layer("nofield.gpkg", {{"POINT (300100 5500200)", {{"top", 50}}, "X"}});
  EXPECT_EQ(code_of([&] { read_wells({nofield, "", ""}, frame(), 1.0); }, &what), ExitCode::kInvalidGeometry);
  EXPECT_NE(what.find("FID 1 (X)"), std::string::npos) << what;
  EXPECT_NE(what.find("depth_from"), std::string::npos) << what;
  const std::string poly = make_layer("poly.gpkg", {{"POLYGON ((0 0, 1 0, 1 1, 0 0))", {}, ""}});
  EXPECT_EQ(code_of([&] { wells_point_layer({poly, "", ""}); }, &what), ExitCode::kInvalidGeometry);
  EXPECT_NE(what.find("POLYGON"), std::string::npos) << what;
  const std::string deviated = make_layer("dev.gpkg", {{"LINESTRING Z (300500 5500600 40, 300520 5500600 -60)", {}, ""}});
  EXPECT_EQ(code_of([&] { read_wells({deviated, "", ""}, frame(), 5.0); }, &what), ExitCode::kInvalidGeometry);
  EXPECT_NE(what.find("vertical"), std::string::npos) << what;
  const std::string nocrs = make_layer("nocrs.shp", {{"POINT (1 2)", {{"top", 1}, {"bottom", 0}}, ""}}, false);
  EXPECT_EQ(code_of([&] { wells_point_layer({nocrs, "", ""}); }, &what), ExitCode::kCrsError);
  EXPECT_EQ(code_of([&] { wells_point_layer({tmp("missing.gpkg"), "", ""}); }, &what), ExitCode::kInputUnreadable);
}

TEST(WellsPointLayer, ReadsBackTheSameCoordinates) {
  const std::string p = make_layer("exact.gpkg", {{"POINT (300100.123456789 5500200.987654321)", {{"top", 1}, {"bottom", 0}}, ""}});
  const MemLayer mem = wells_point_layer({p, "", ""});
  GDALDataset* ds = GDALDataset::Open(mem.path().c_str(), GDAL_OF_VECTOR);
  ASSERT_NE(ds, nullptr);
  OGRLayer* l = ds->GetLayer(0);
  ASSERT_EQ(l->GetFeatureCount(), 1);
  l->ResetReading();
  OGRFeature* f = l->GetNextFeature();
  const OGRPoint* pt = f->GetGeometryRef()->toPoint();
  EXPECT_EQ(pt->getX(), 300100.123456789);
  EXPECT_EQ(pt->getY(), 5500200.987654321);
  OGRFeature::DestroyFeature(f);
  GDALClose(ds);
}

// A 6 x 5 GeoTIFF with 10 m cells from (1000, 2000) down, nodata (-9999) except the cells in
// columns c0..c1, rows r0..r1 (none when c1 < c0).
std::string make_dem(const std::string& file, int c0, int c1, int r0, int r1, bool with_crs = true) {
  GDALAllRegister();
  const std::string path = tmp(file);
  GDALDataset* ds = GetGDALDriverManager()->GetDriverByName("GTiff")->Create(path.c_str(), 6, 5, 1, GDT_Float32, nullptr);
  double gt[6] = {1000, 10, 0, 2000, 0, -10};
  ds->SetGeoTransform(gt);
  if (with_crs) {
    OGRSpatialReference srs;
    srs.importFromEPSG(32632);
    ds->SetSpatialRef(&srs);
  }
  GDALRasterBand* b = ds->GetRasterBand(1);
  b->SetNoDataValue(-9999);
  std::vector<float> v(30, -9999.0f);
  for (int j = r0; j <= r1; ++j)
    for (int i = c0; i <= c1; ++i) v[static_cast<std::size_t>(j * 6 + i)] = 100.0f;
  if (b->RasterIO(GF_Write, 0, 0, 6, 5, v.data(), 6, 5, GDT_Float32, 0, 0) != CE_None) ADD_FAILURE();
  GDALClose(ds);
  return path;
}

TEST(DemExtent, TheBoxOfTheValidCellsCentres) {
  const MemLayer mem = dem_extent_layer(make_dem("dem.tif", 1, 4, 1, 3));
  GDALDataset* ds = GDALDataset::Open(mem.path().c_str(), GDAL_OF_VECTOR);
  ASSERT_NE(ds, nullptr);
  OGRLayer* l = ds->GetLayer(0);
  ASSERT_NE(l->GetSpatialRef(), nullptr);
  OGREnvelope e;
  ASSERT_EQ(l->GetExtent(&e), OGRERR_NONE);
  EXPECT_EQ(e.MinX, 1015);
  EXPECT_EQ(e.MaxX, 1045);
  EXPECT_EQ(e.MaxY, 1985);
  EXPECT_EQ(e.MinY, 1965);
  GDALClose(ds);
}

TEST(DemExtent, AllNodataAndNoCrsAreErrors) {
  std::string what;
  const std::string empty = make_dem("empty.tif", 1, 0, 0, 4);
  EXPECT_EQ(code_of([&] { dem_extent_layer(empty); }, &what), ExitCode::kInvalidSpacing);
  EXPECT_NE(what.find("--dem"), std::string::npos) << what;
  EXPECT_NE(what.find("nodata"), std::string::npos) << what;
  const std::string nocrs = make_dem("nocrs.tif", 0, 5, 0, 4, false);
  EXPECT_EQ(code_of([&] { dem_extent_layer(nocrs); }, &what), ExitCode::kCrsError);
}

}  // namespace
}  // namespace fdr::terrain
