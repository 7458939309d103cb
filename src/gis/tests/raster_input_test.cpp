// Tests of raster warping into the frame, depth sampling, the cell-size hint and GeoTIFF output.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include <gdal_priv.h>

#include "base/error.hpp"
#include "gis/raster_input.hpp"
#include "gis/raster_output.hpp"

using namespace fdr;
using namespace fdr::gis;

namespace {
const std::string kData = FDR_TESTDATA_DIR;
const std::string kEtopo = kData + "/chesapeake/chesapeake_mouth_etopo5.tif";

Frame chesapeake_frame() {
  return choose_frame({{-76.6, 36.75}, {-75.6, 36.75}, {-75.6, 37.75}, {-76.6, 37.75}}, "");
}
}  // namespace

TEST(Raster, WarpCoversDomainAndDepthsAreFinite) {
  Frame f = chesapeake_frame();
  const Box2 box = f.domain_box();
  const double cell = grid_cell_size_hint(kEtopo, f, box);
  // ETOPO5: 5' = 9.27 km north-south, 7.4 km east-west at 37.25 N.
  EXPECT_NEAR(cell, 7390.0, 100.0);
  sizing::Grid g = read_raster_to_frame(kEtopo, f, box, 1000.0);
  EXPECT_LE(g.extent().lo.x, box.lo.x);
  EXPECT_LE(g.extent().lo.y, box.lo.y);
  EXPECT_GE(g.extent().hi.x, box.hi.x);
  EXPECT_GE(g.extent().hi.y, box.hi.y);
  EXPECT_EQ(g.v.size(), g.nx * g.ny);
  std::vector<Point2> nodes;
  for (double x = box.lo.x; x <= box.hi.x; x += box.width() / 20)
    for (double y = box.lo.y; y <= box.hi.y; y += box.height() / 20) nodes.push_back({x, y});
  int filled = -1;
  std::vector<double> z = sample_depths(g, nodes, &filled);
  EXPECT_EQ(filled, 0);
  double lo = 1e9, hi = -1e9;
  for (double v : z) {
    ASSERT_TRUE(std::isfinite(v));
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  // README: the raster's range is -22 .. 53 m; bilinear values stay inside it.
  EXPECT_GE(lo, -22.0);
  EXPECT_LE(hi, 53.0);
  EXPECT_LT(lo, -5.0);
  // The warped value at a pixel centre of the source equals the source (bilinear at a node).
  // Pixel centres: lon -76.791667 + (i + 0.5)/12, lat 37.875 - (j + 0.5)/12.
  const double lon = -76.791667 + 7.5 / 12, lat = 37.875 - 7.5 / 12;
  sizing::Grid fine = read_raster_to_frame(kEtopo, f, box, 250.0);
  const double a = sample_depths(fine, {f.lonlat_to_local({lon, lat})})[0];
  const double b = sample_depths(g, {f.lonlat_to_local({lon, lat})})[0];
  EXPECT_NEAR(a, b, 3.0);
}

TEST(Raster, NodataBecomesNanAndIsFilledFromNearest) {
  // Luxembourg elev.tif: nodata -32768 outside the country.
  const std::string elev = kData + "/luxembourg/elev.tif";
  Frame f = choose_frame({{5.85, 49.5}, {6.45, 49.5}, {6.45, 50.1}, {5.85, 50.1}}, "");
  EXPECT_EQ(f.epsg(), 32632);
  sizing::Grid g = read_raster_to_frame(elev, f, f.domain_box(), 1000.0);
  std::size_t nan = 0, ok = 0;
  for (double v : g.v) {
    if (std::isnan(v)) ++nan;
    else {
      ++ok;
      EXPECT_GT(v, 100.0);
      EXPECT_LT(v, 560.0);
    }
  }
  EXPECT_GT(nan, 0u);
  EXPECT_GT(ok, 0u);
  // The box corners are outside Luxembourg: nodata there, filled from the nearest valid cell.
  int filled = 0;
  std::vector<double> z = sample_depths(g, {f.domain_box().lo, f.domain_box().center()}, &filled);
  EXPECT_GE(filled, 1);
  EXPECT_TRUE(std::isfinite(z[0]));
  EXPECT_GT(z[0], 100.0);
}

TEST(Raster, NotCoveringIsInvalidSpacing) {
  Frame f = choose_frame({{-71.0, 41.0}, {-70.0, 41.0}, {-70.0, 42.0}, {-71.0, 42.0}}, "");  // Cape Cod
  try {
    read_raster_to_frame(kEtopo, f, f.domain_box(), 1000.0);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidSpacing);
    EXPECT_EQ(e.exit_code(), 6);
    const std::string m = e.what();
    EXPECT_NE(m.find("does not cover"), std::string::npos) << m;
    EXPECT_NE(m.find("south-west (-70.99"), std::string::npos) << m;
  }
}

TEST(Raster, PartialCoverReportsOnlyUncoveredCorners) {
  Frame f = choose_frame({{-76.6, 36.75}, {-75.0, 36.75}, {-75.0, 37.75}, {-76.6, 37.75}}, "");
  try {
    read_raster_to_frame(kEtopo, f, f.domain_box(), 1000.0);
    FAIL();
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.find("south-west"), std::string::npos) << m;
    EXPECT_NE(m.find("south-east"), std::string::npos) << m;
    EXPECT_NE(m.find("north-east"), std::string::npos) << m;
  }
}

TEST(Raster, CoverageCheckedOnDomainVertices) {
  // Gulf of Maine: the tile covers the lon/lat region but not the projected bbox's northern corners.
  const std::string tif = kData + "/gulf_of_maine/gulf_of_maine_etopo5.tif";
  Frame f = choose_frame({{-71.0, 41.0}, {-63.5, 41.0}, {-63.5, 45.6}, {-71.0, 45.6}}, "");
  const Box2 box = f.domain_box();
  try {
    read_raster_to_frame(tif, f, box, 5000.0);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("north-west"), std::string::npos) << e.what();
  }
  std::vector<Point2> outline;
  for (double lon = -71.0; lon <= -63.5; lon += 0.5) {
    outline.push_back(f.lonlat_to_local({lon, 41.0}));
    outline.push_back(f.lonlat_to_local({lon, 45.6}));
  }
  sizing::Grid g = read_raster_to_frame(tif, f, box, 5000.0, &outline);
  int filled = 0;
  std::vector<double> z = sample_depths(g, outline, &filled);
  for (double v : z) EXPECT_TRUE(std::isfinite(v));
  EXPECT_EQ(filled, 0);
  // A vertex outside the tile is named with its lon/lat.
  outline.push_back(f.lonlat_to_local({-71.3, 45.0}));
  try {
    read_raster_to_frame(tif, f, box, 5000.0, &outline);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidSpacing);
    EXPECT_NE(std::string(e.what()).find("(-71.300000, 45.000000)"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("1 of 33 vertices"), std::string::npos) << e.what();
  }
}

TEST(Raster, Unreadable) {
  Frame f = chesapeake_frame();
  try {
    read_raster_to_frame(kData + "/chesapeake/chesapeake_mouth_water.geojson", f, f.domain_box(), 1000.0);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInputUnreadable);
    EXPECT_NE(std::string(e.what()).find("chesapeake_mouth_water.geojson: cannot open"), std::string::npos);
  }
  try {
    read_raster_to_frame(kData + "/missing.tif", f, f.domain_box(), 1000.0);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInputUnreadable);
  }
}

TEST(Raster, NodataEverywhere) {
  // A box inside elev.tif's extent but outside Luxembourg (north-west corner: all nodata).
  const std::string elev = kData + "/luxembourg/elev.tif";
  Frame f = choose_frame({{5.75, 50.10}, {5.80, 50.10}, {5.80, 50.18}, {5.75, 50.18}}, "");
  try {
    read_raster_to_frame(elev, f, f.domain_box(), 500.0);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidSpacing);
    EXPECT_NE(std::string(e.what()).find("nodata everywhere"), std::string::npos) << e.what();
  }
}

TEST(Raster, WriteGeoTiffRoundTrip) {
  Frame f = chesapeake_frame();
  sizing::Grid g = read_raster_to_frame(kEtopo, f, f.domain_box(), 2000.0);
  g.at(0, 0) = std::nan("");
  const std::string path = testing::TempDir() + "/gis_spacing.tif";
  write_grid_geotiff(g, f, path);
  ASSERT_TRUE(std::filesystem::exists(path));
  // Read back through the warper into the same grid: same values (Float32 rounding).
  sizing::Grid h = read_raster_to_frame(path, f, f.domain_box(), 2000.0);
  ASSERT_EQ(h.nx, g.nx);
  ASSERT_EQ(h.ny, g.ny);
  EXPECT_TRUE(std::isnan(h.at(0, 0)));
  for (std::size_t j = 1; j + 1 < g.ny; ++j)
    for (std::size_t i = 1; i + 1 < g.nx; ++i) EXPECT_NEAR(h.at(i, j), g.at(i, j), 1e-3);
  // Read back natively (no warp): the very same grid.
  sizing::Grid n = read_raster_native(path, f.origin());
  ASSERT_EQ(n.nx, g.nx);
  ASSERT_EQ(n.ny, g.ny);
  EXPECT_NEAR(n.x0, g.x0, 1e-6);
  EXPECT_NEAR(n.y0, g.y0, 1e-6);
  EXPECT_EQ(n.dx, g.dx);
  EXPECT_TRUE(std::isnan(n.at(0, 0)));
  for (std::size_t k = 1; k < g.v.size(); ++k) EXPECT_EQ(n.v[k], static_cast<double>(static_cast<float>(g.v[k])));
  // No temporary file left behind.
  for (const auto& e : std::filesystem::directory_iterator(testing::TempDir()))
    EXPECT_EQ(e.path().string().find("gis_spacing.tif.tmp"), std::string::npos);
  try {
    write_grid_geotiff(g, f, "/nonexistent-dir/x.tif");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kOutputError);
  }
}

TEST(Raster, NativeRotatedRasterIsResampledNorthUp) {
  GDALAllRegister();
  const std::string path = testing::TempDir() + "/gis_rotated.tif";
  {
    GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("GTiff");
    GDALDataset* ds = drv->Create(path.c_str(), 10, 10, 1, GDT_Float32, nullptr);
    ASSERT_NE(ds, nullptr);
    const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
    double gt[6] = {1000.0, 10 * c, -10 * s, 2000.0, -10 * s, -10 * c};  // 30 degree rotation
    ds->SetGeoTransform(gt);
    ds->SetProjection("EPSG:32618");
    std::vector<float> v(100, 7.0f);
    ASSERT_EQ(ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, 10, 10, v.data(), 10, 10, GDT_Float32, 0, 0), CE_None);
    GDALClose(GDALDataset::ToHandle(ds));
  }
  sizing::Grid g = read_raster_native(path, {1000.0, 2000.0});
  std::size_t valid = 0;
  for (double x : g.v)
    if (std::isfinite(x)) {
      ++valid;
      EXPECT_NEAR(x, 7.0, 1e-6);
    }
  EXPECT_GT(valid, 50u);
  EXPECT_LT(valid, g.v.size());  // the corners of the north-up box are outside the rotated raster
  EXPECT_GT(g.dx, 0);
}
