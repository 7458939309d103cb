// Tests of the working frame: CRS choice, round trips, scale factors, ground -> grid spacing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <GeographicLib/TransverseMercator.hpp>
#include <ogr_spatialref.h>

#include "base/error.hpp"
#include "gis/crs.hpp"
#include "sizing/fields.hpp"
#include "sizing/grid_field.hpp"

using namespace fdr;
using namespace fdr::gis;

namespace {
std::vector<LonLat> box(double w, double s, double e, double n) {
  return {{w, s}, {e, s}, {e, n}, {w, n}};
}
}  // namespace

TEST(Frame, ChesapeakeIsUtm18N) {
  Frame f = choose_frame(box(-76.6, 36.75, -75.6, 37.75), "");
  EXPECT_EQ(f.epsg(), 32618);
  EXPECT_NE(f.name().find("18N"), std::string::npos) << f.name();
  // The origin is a round number near the centre, so local coordinates are small.
  EXPECT_EQ(std::fmod(f.origin().x, 1000.0), 0.0);
  EXPECT_EQ(std::fmod(f.origin().y, 1000.0), 0.0);
  const Box2 b = f.domain_box();
  EXPECT_LT(std::max({std::abs(b.lo.x), std::abs(b.hi.x), std::abs(b.lo.y), std::abs(b.hi.y)}), 100e3);
  EXPECT_GT(b.width(), 80e3);
  EXPECT_NE(f.wkt().find("UTM zone 18N"), std::string::npos);
  EXPECT_NE(f.projjson().find("\"ProjectedCRS\""), std::string::npos);
}

TEST(Frame, SouthernHemisphereUtm) {
  Frame f = choose_frame(box(151.0, -34.2, 151.5, -33.7), "");  // Sydney
  EXPECT_EQ(f.epsg(), 32756);
}

TEST(Frame, WideDomainIsCentredTransverseMercator) {
  Frame f = choose_frame(box(-80.0, 30.0, -60.0, 45.0), "");
  EXPECT_EQ(f.epsg(), 0);
  EXPECT_NE(f.name().find("Transverse Mercator"), std::string::npos) << f.name();
  // Centred: k = 1 on the central meridian -70, larger 10 degrees away.
  EXPECT_NEAR(f.scale_factor(f.lonlat_to_local({-70.0, 37.5})), 1.0, 1e-9);
  const double k_edge = f.scale_factor(f.lonlat_to_local({-60.0, 37.5}));
  EXPECT_GT(k_edge, 1.005);
  EXPECT_LT(k_edge, 1.02);
}

TEST(Frame, TooWideIsRefused) {
  try {
    choose_frame(box(-170.0, 0.0, 10.0, 10.0), "");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kCrsError);
    EXPECT_NE(std::string(e.what()).find("--t_srs"), std::string::npos);
  }
}

TEST(Frame, ExplicitTsrs) {
  Frame f = choose_frame(box(-76.6, 36.75, -75.6, 37.75), "EPSG:32617");
  EXPECT_EQ(f.epsg(), 32617);
  Frame g = choose_frame(box(-76.6, 36.75, -75.6, 37.75), "+proj=laea +lat_0=37 +lon_0=-76 +datum=WGS84 +units=m");
  EXPECT_EQ(g.epsg(), 0);
  // LAEA: not conformal; the reported factor is sqrt(areal scale) = 1.
  EXPECT_NEAR(g.scale_factor(g.lonlat_to_local({-75.7, 37.7})), 1.0, 1e-9);
  for (const char* bad : {"EPSG:999999", "not a crs", "EPSG:4326"}) {
    try {
      choose_frame(box(-76.6, 36.75, -75.6, 37.75), bad);
      FAIL() << bad;
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ExitCode::kCrsError) << bad;
      EXPECT_EQ(e.exit_code(), 9);
    }
  }
}

TEST(Frame, RoundTripLonLatLocal) {
  Frame f = choose_frame(box(-76.6, 36.75, -75.6, 37.75), "");
  for (double lon = -76.6; lon <= -75.6; lon += 0.25)
    for (double lat = 36.75; lat <= 37.75; lat += 0.25) {
      const Point2 p = f.lonlat_to_local({lon, lat});
      const LonLat q = f.to_lonlat(p);
      EXPECT_NEAR(q.lon_deg, lon, 1e-10);
      EXPECT_NEAR(q.lat_deg, lat, 1e-10);
    }
  // to_local from an arbitrary source CRS agrees with lonlat_to_local.
  OGRSpatialReference ll;
  ll.importFromEPSG(4326);  // authority order lat, lon: to_local must still take x = lon
  const Point2 a = f.to_local(-76.0, 37.0, ll);
  const Point2 b = f.lonlat_to_local({-76.0, 37.0});
  EXPECT_NEAR(a.x, b.x, 1e-6);
  EXPECT_NEAR(a.y, b.y, 1e-6);
  std::vector<Point2> pts{{-76.0, 37.0}, {-75.7, 37.2}};
  f.to_local_batch(pts, ll, "test");
  EXPECT_NEAR(pts[0].x, b.x, 1e-6);
}

TEST(Frame, UtmScaleFactorOnCentralMeridian) {
  Frame f = choose_frame(box(-76.6, 36.75, -75.6, 37.75), "");
  EXPECT_NEAR(f.scale_factor(f.lonlat_to_local({-75.0, 37.0})), 0.9996, 1e-7);
  // About 180 km east of the central meridian k is back near 1.
  const double k = f.scale_factor(f.lonlat_to_local({-73.0, 37.0}));
  EXPECT_GT(k, 0.9999);
  EXPECT_LT(k, 1.0002);
}

TEST(Frame, GroundToGrid) {
  auto c = std::make_shared<sizing::ConstantField>(100.0);
  // Chesapeake in UTM 18N: k within 0.9996..0.99975 -> |k-1| < 1e-3: unchanged.
  Frame f = choose_frame(box(-76.6, 36.75, -75.6, 37.75), "");
  double dev = -1;
  sizing::SizingPtr g = ground_to_grid(c, f, &dev);
  EXPECT_EQ(g.get(), c.get());
  EXPECT_GT(dev, 2e-4);
  EXPECT_LT(dev, 1e-3);
  // A 20-degree-wide domain: f_grid = f_ground * k, interpolated k close to PROJ's.
  Frame w = choose_frame(box(-80.0, 30.0, -60.0, 45.0), "");
  sizing::SizingPtr gw = ground_to_grid(c, w, &dev);
  EXPECT_NE(gw.get(), c.get());
  EXPECT_GT(dev, 5e-3);
  for (const LonLat ll : {LonLat{-70, 37.5}, LonLat{-61, 31}, LonLat{-79, 44}, LonLat{-65.3, 40.1}}) {
    const Point2 p = w.lonlat_to_local(ll);
    EXPECT_NEAR((*gw)(p), 100.0 * w.scale_factor(p), 100.0 * 2e-5);
  }
  EXPECT_NE(gw->describe().find("scale factor"), std::string::npos);
}

// The corrected spacing f * k states a Lipschitz constant and an upper bound when f does (the
// smoothing decides most R/f(c) <= B tests from them): both hold on random pairs of points.
TEST(Frame, GroundToGridLipschitzBound) {
  Frame w = choose_frame(box(-80.0, 30.0, -60.0, 45.0), "");
  const Box2 b = w.domain_box();
  sizing::Grid g;
  g.nx = 40;
  g.ny = 30;
  g.dx = b.width() / 40;
  g.dy = b.height() / 30;
  g.x0 = b.lo.x;
  g.y0 = b.lo.y;
  g.v.resize(g.nx * g.ny);
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i) g.v[j * g.nx + i] = 5000.0 + 0.1 * g.dx * ((i * 7 + j * 3) % 11);
  auto f = std::make_shared<sizing::GridField>(g, "test");
  ASSERT_GT(f->lipschitz(), 0);
  EXPECT_DOUBLE_EQ(f->upper_bound(), *std::max_element(g.v.begin(), g.v.end()));
  double dev = 0;
  sizing::SizingPtr fk = ground_to_grid(f, w, &dev);
  ASSERT_NE(fk.get(), f.get());
  const double L = fk->lipschitz();
  ASSERT_GE(L, f->lipschitz());
  unsigned s = 12345;
  auto rnd = [&s] { s = s * 1103515245u + 12345u; return ((s >> 8) & 0xffff) / 65535.0; };
  for (int k = 0; k < 20000; ++k) {
    const Point2 p{b.lo.x + rnd() * b.width(), b.lo.y + rnd() * b.height()};
    const double r = (k % 2 ? 0.3 : 0.003) * g.dx;
    const Point2 q{p.x + r * (rnd() - 0.5), p.y + r * (rnd() - 0.5)};
    const double d = std::sqrt(norm2(q - p));
    ASSERT_LE(std::abs((*fk)(p) - (*fk)(q)), L * d * (1 + 1e-9) + 1e-9) << k;
    ASSERT_LE((*fk)(p), fk->upper_bound());
  }
  // Unknown when f has no upper bound (paper-f1 grows without one).
  EXPECT_LT(ground_to_grid(std::make_shared<sizing::PaperF1Field>(1000.0), w, &dev)->lipschitz(), 0);
}

TEST(Frame, ScaleFactorAgreesWithGeographicLib) {
  // Independent check of PROJ's factors: GeographicLib's UTM (Karney's series) gives k directly.
  Frame f = choose_frame(box(-76.6, 36.75, -75.6, 37.75), "");
  const auto& utm = GeographicLib::TransverseMercator::UTM();
  for (const LonLat ll : {LonLat{-76.6, 36.75}, LonLat{-75.6, 37.75}, LonLat{-72.5, 40.0}, LonLat{-77.9, 30.0}}) {
    double x, y, gamma, k;
    utm.Forward(-75.0, ll.lat_deg, ll.lon_deg, x, y, gamma, k);
    EXPECT_NEAR(f.scale_factor(f.lonlat_to_local(ll)), k, 1e-9) << ll.lon_deg << " " << ll.lat_deg;
    // And the projected coordinates agree (GeographicLib's x is relative to the central meridian).
    const Point2 w = f.to_world(f.lonlat_to_local(ll));
    EXPECT_NEAR(w.x, x + 500000.0, 1e-3);
    EXPECT_NEAR(w.y, y, 1e-3);
  }
}
