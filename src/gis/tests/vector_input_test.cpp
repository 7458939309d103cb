// Tests of read_domain on real GSHHG extracts: formats, markers, open boundary, raw rings, errors.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include <gdal_utils.h>
#include <gdal_priv.h>

#include "base/error.hpp"
#include "gis/vector_input.hpp"
#include "base/edge_kind.hpp"
#include "pslg/validate.hpp"

using namespace fdr;
using namespace fdr::gis;
using fdr::EdgeKind;

namespace {

const std::string kData = FDR_TESTDATA_DIR;
const std::string kChes = kData + "/chesapeake/";

std::map<int, std::size_t> marker_counts(const pslg::Pslg& p) {
  std::map<int, std::size_t> m;
  for (const auto& s : p.segments) ++m[s.marker];
  return m;
}

std::size_t distinct_parts(const pslg::Pslg& p, EdgeKind k) {
  std::set<int> s;
  for (const auto& seg : p.segments)
    if (seg.marker == static_cast<int>(k)) s.insert(seg.part);
  return s.size();
}

DomainOptions chesapeake(const std::string& water, const std::string& open, const std::string& water_layer = "",
                         const std::string& open_layer = "") {
  DomainOptions o;
  o.domain = {water, water_layer, ""};
  o.open_boundary = {open, open_layer, ""};
  return o;
}

template <class F>
Error expect_error(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e;
  }
  ADD_FAILURE() << "no fdr::Error thrown";
  return Error(ExitCode::kOk, "");
}

void expect_contains(const std::string& s, const std::string& part) {
  EXPECT_NE(s.find(part), std::string::npos) << "'" << part << "' not in: " << s;
}

}  // namespace

TEST(ReadDomain, ChesapeakeGeoJsonCountsAndMarkers) {
  GisInput in = read_domain(chesapeake(kChes + "chesapeake_mouth_water.geojson",
                                       kChes + "chesapeake_mouth_open_boundary.geojson"));
  EXPECT_EQ(in.frame.epsg(), 32618);
  EXPECT_EQ(in.pslg.origin, in.frame.origin());
  EXPECT_EQ(in.counts.polygon_features, 5u);
  EXPECT_EQ(in.counts.outer_rings, 5u);
  EXPECT_EQ(in.counts.holes, 152u);
  EXPECT_EQ(in.counts.densified_segments, 0u);  // --densify is off by default (chords, as GDAL)
  EXPECT_EQ(in.counts.boundary_segments, 1984u);  // 2141 points - 157 closing points
  EXPECT_EQ(in.counts.open_features, 12u);
  EXPECT_EQ(in.counts.open_parts, 12u);
  EXPECT_EQ(in.counts.open_segments, 14u);  // 26 open-boundary points in 12 lines
  const auto m = marker_counts(in.raw);
  EXPECT_EQ(m.at(int(EdgeKind::kOpen)), 14u);
  EXPECT_EQ(m.at(int(EdgeKind::kLand)) + m.at(int(EdgeKind::kIsland)) + 14u, 1984u);
  EXPECT_EQ(distinct_parts(in.raw, EdgeKind::kIsland), 152u);
  EXPECT_EQ(distinct_parts(in.raw, EdgeKind::kOpen), 12u);
  // Every part id resolves to its source.
  for (const auto& s : in.raw.segments) {
    ASSERT_GE(s.part, 0);
    ASSERT_LT(static_cast<std::size_t>(s.part), in.parts.size());
  }
  for (const auto& s : in.raw.segments) {
    if (s.marker == int(EdgeKind::kOpen)) {
      EXPECT_EQ(in.parts[s.part].role, "open boundary");
    }
  }
  // Area: the README's geodesic 5897.871 km^2, within UTM's scale distortion (k^2 ~ 0.9994).
  EXPECT_NEAR(in.domain_area_m2 / 1e6, 5897.871 * 0.9994, 5897.871 * 1e-3);
  // Cleaned: valid PSLG, markers kept, no segment lost beyond cleaning repairs.
  EXPECT_TRUE(pslg::find_crossings(in.pslg).empty());
  EXPECT_NO_THROW(pslg::validate(in.pslg, "chesapeake"));
  EXPECT_EQ(marker_counts(in.pslg).at(int(EdgeKind::kOpen)), 14u);
  EXPECT_GE(in.snap_distance_m, 0.01);
}

TEST(ReadDomain, SameResultFromGeoJsonShapefileGpkg) {
  GisInput a = read_domain(chesapeake(kChes + "chesapeake_mouth_water.geojson",
                                      kChes + "chesapeake_mouth_open_boundary.geojson"));
  GisInput b = read_domain(chesapeake(kChes + "shp/chesapeake_mouth_water.shp",
                                      kChes + "shp/chesapeake_mouth_open_boundary.shp"));
  GisInput c = read_domain(chesapeake(kChes + "chesapeake_mouth.gpkg", kChes + "chesapeake_mouth.gpkg", "water",
                                      "open_boundary"));
  for (const GisInput* x : {&b, &c}) {
    EXPECT_EQ(x->counts.boundary_segments, a.counts.boundary_segments);
    EXPECT_EQ(x->counts.outer_rings, a.counts.outer_rings);
    EXPECT_EQ(x->counts.holes, a.counts.holes);
    EXPECT_EQ(x->counts.open_parts, a.counts.open_parts);
    EXPECT_EQ(marker_counts(x->raw), marker_counts(a.raw));
    EXPECT_EQ(marker_counts(x->pslg), marker_counts(a.pslg));
    EXPECT_EQ(x->pslg.points.size(), a.pslg.points.size());
    EXPECT_NEAR(x->domain_area_m2, a.domain_area_m2, 1.0);
    EXPECT_EQ(x->frame.origin(), a.frame.origin());
  }
}

TEST(ReadDomain, WhereClauseSelectsMainWaterBody) {
  DomainOptions o = chesapeake(kChes + "chesapeake_mouth.gpkg", kChes + "chesapeake_mouth.gpkg", "water",
                               "open_boundary");
  o.domain.where = "id = 0";
  GisInput in = read_domain(o);
  EXPECT_EQ(in.counts.polygon_features, 1u);
  EXPECT_EQ(in.counts.holes, 152u);
  EXPECT_EQ(in.counts.boundary_segments, 1962u);  // README: main body 1962 vertices (excl. closing)
  EXPECT_GE(in.counts.open_parts, 1u);
  EXPECT_LT(in.counts.open_parts, 12u);  // the 4 cut-off creeks carry the other open parts
}

TEST(ReadDomain, RawRingsCleanIntoValidPslg) {
  DomainOptions o;
  o.domain = {kData + "/raw/chesapeake_mouth_raw.gpkg", "rings_raw", ""};
  GisInput in = read_domain(o);
  EXPECT_EQ(in.counts.polygon_features, 156u);
  EXPECT_EQ(in.counts.boundary_segments, 1063u - 156u);
  EXPECT_TRUE(pslg::find_crossings(in.pslg).empty());
  EXPECT_NO_THROW(pslg::validate(in.pslg, "rings_raw"));
}

TEST(ReadDomain, InvalidRawRingsBoothbayAreSplitNotRepairedInOgr) {
  // Gulf of Maine raw rings around Boothbay: one ring is a figure eight (GEOS: invalid).
  DomainOptions o;
  o.domain = {kData + "/raw/gulf_of_maine_boothbay_raw.gpkg", "rings_raw", ""};
  GisInput in = read_domain(o);
  EXPECT_EQ(in.counts.polygon_features, 58u);
  EXPECT_FALSE(pslg::find_crossings(in.raw).empty());  // the raw input does cross itself
  EXPECT_TRUE(pslg::find_crossings(in.pslg).empty());
  EXPECT_NO_THROW(pslg::validate(in.pslg, "boothbay"));
  bool split = false;
  for (const auto& r : in.repairs) split |= r.repair.kind == "crossing_split";
  EXPECT_TRUE(split);
  // Repairs are reported in world (UTM 19N) coordinates and lon/lat near Boothbay.
  for (const auto& r : in.repairs) {
    EXPECT_GT(r.repair.where.x, 100e3);
    EXPECT_GT(r.repair.where.y, 4.8e6);
    EXPECT_NEAR(r.lonlat.lat_deg, 43.8, 0.2);
    EXPECT_NEAR(r.lonlat.lon_deg, -69.76, 0.2);
  }
}

TEST(ReadDomain, BreaklinesAreClippedInsideTheDomain) {
  DomainOptions o;
  const std::string gom = kData + "/gulf_of_maine/gulf_of_maine.gpkg";
  o.domain = {gom, "water", ""};
  o.open_boundary = {gom, "open_boundary", ""};
  o.breaklines = {gom, "rivers_h", ""};
  GisInput in = read_domain(o);
  EXPECT_EQ(in.frame.epsg(), 0);  // 7.5 degrees wide: centred TM, not UTM
  EXPECT_EQ(in.counts.breakline_features, 14u);
  EXPECT_EQ(in.counts.open_parts, 13u);
  // README: 3 of the 14 rivers cross into the water polygon.
  std::set<int> parts;
  for (const auto& s : in.raw.segments)
    if (s.marker == int(EdgeKind::kBreakline)) parts.insert(s.part);
  EXPECT_EQ(parts.size(), 3u);
  EXPECT_GT(in.counts.breakline_segments, 0u);
  EXPECT_TRUE(pslg::find_crossings(in.pslg).empty());
  EXPECT_GT(marker_counts(in.pslg).at(int(EdgeKind::kBreakline)), 0u);
}

TEST(ReadDomain, LandMinusExtentMarksBoxEdgesOpen) {
  DomainOptions o;
  o.land = {kChes + "shp/chesapeake_mouth_land.shp", "", ""};
  o.extent = std::array<double, 4>{-76.6, 36.75, -75.6, 37.75};
  GisInput in = read_domain(o);
  EXPECT_EQ(in.frame.epsg(), 32618);
  // Same domain as the water layer: the same area (5897.871 km^2 geodesic).
  EXPECT_NEAR(in.domain_area_m2 / 1e6, 5897.871 * 0.9994, 5897.871 * 1e-3);
  EXPECT_EQ(in.counts.holes, 152u);
  EXPECT_EQ(in.counts.open_parts, 12u);
  EXPECT_TRUE(pslg::find_crossings(in.pslg).empty());
}

TEST(ReadDomain, FixedPointsInsideOnly) {
  // Points layer = the open-boundary lines' vertices would be on the boundary; use the
  // Luxembourg cantons instead: points from a GeoJSON written here.
  const std::string path = testing::TempDir() + "/gis_points.geojson";
  FILE* f = std::fopen(path.c_str(), "w");
  ASSERT_NE(f, nullptr);
  std::fputs(R"({"type":"FeatureCollection","features":[
{"type":"Feature","properties":{},"geometry":{"type":"Point","coordinates":[-76.2,37.2]}},
{"type":"Feature","properties":{},"geometry":{"type":"Point","coordinates":[-76.0,37.0]}},
{"type":"Feature","properties":{},"geometry":{"type":"Point","coordinates":[-77.5,37.0]}}]})", f);
  std::fclose(f);
  DomainOptions o = chesapeake(kChes + "chesapeake_mouth_water.geojson", kChes + "chesapeake_mouth_open_boundary.geojson");
  o.points = {path, "", ""};
  GisInput in = read_domain(o);
  EXPECT_EQ(in.counts.fixed_points + in.counts.points_outside, 3u);
  EXPECT_GE(in.counts.points_outside, 1u);  // -77.5 is outside the region
  EXPECT_GE(in.counts.fixed_points, 1u);    // open bay water at (-76.0, 37.0)
  // The fixed point survives cleaning as a vertex.
  const Point2 p = in.frame.lonlat_to_local({-76.0, 37.0});
  bool found = false;
  for (const auto& q : in.pslg.points) found |= dist(p, q) < 1e-6;
  EXPECT_TRUE(found);
}

TEST(ReadDomain, LuxembourgCantonsShareBoundaries) {
  // 12 conforming cantons: the shared boundaries cancel by parity in cleaning.
  DomainOptions o;
  o.domain = {kData + "/luxembourg/lux.shp", "", ""};
  GisInput in = read_domain(o);
  EXPECT_EQ(in.frame.epsg(), 32632);  // centre 6.1 E: zone 32
  EXPECT_EQ(in.counts.polygon_features, 12u);
  EXPECT_LT(in.pslg.segments.size(), in.raw.segments.size());
  EXPECT_TRUE(pslg::find_crossings(in.pslg).empty());
}

TEST(ReadDomainErrors, MissingFile) {
  DomainOptions o;
  o.domain = {kData + "/nope/missing.gpkg", "", ""};
  Error e = expect_error([&] { read_domain(o); });
  EXPECT_EQ(e.code(), ExitCode::kInputUnreadable);
  EXPECT_EQ(e.exit_code(), 3);
  expect_contains(e.what(), "missing.gpkg: cannot open");
}

TEST(ReadDomainErrors, BadLayerListsLayers) {
  DomainOptions o;
  o.domain = {kChes + "chesapeake_mouth.gpkg", "coast", ""};
  Error e = expect_error([&] { read_domain(o); });
  EXPECT_EQ(e.code(), ExitCode::kInputUnreadable);
  expect_contains(e.what(), "no layer 'coast'");
  expect_contains(e.what(), "water");
  expect_contains(e.what(), "open_boundary");
}

TEST(ReadDomainErrors, EmptyWhere) {
  DomainOptions o;
  o.domain = {kChes + "chesapeake_mouth.gpkg", "water", "id > 1000"};
  Error e = expect_error([&] { read_domain(o); });
  EXPECT_EQ(e.code(), ExitCode::kInvalidGeometry);
  EXPECT_EQ(e.exit_code(), 5);
  expect_contains(e.what(), "id > 1000");
  expect_contains(e.what(), "selects no features");
  o.domain.where = "no_such_field = 3";
  Error e2 = expect_error([&] { read_domain(o); });
  EXPECT_EQ(e2.code(), ExitCode::kUsage);
}

TEST(ReadDomainErrors, WrongGeometryTypeNamesFeature) {
  DomainOptions o;
  o.domain = {kChes + "chesapeake_mouth.gpkg", "open_boundary", ""};
  Error e = expect_error([&] { read_domain(o); });
  EXPECT_EQ(e.code(), ExitCode::kInvalidGeometry);
  expect_contains(e.what(), "layer 'open_boundary'");
  expect_contains(e.what(), "FID 1");
  expect_contains(e.what(), "LINESTRING");
  expect_contains(e.what(), "at (-");
}

TEST(ReadDomainErrors, NoCrs) {
  const std::string path = testing::TempDir() + "/gis_nocrs.csv";
  FILE* f = std::fopen(path.c_str(), "w");
  ASSERT_NE(f, nullptr);
  std::fputs("id,WKT\n1,\"POLYGON ((500000 4100000,501000 4100000,501000 4101000,500000 4100000))\"\n", f);
  std::fclose(f);
  DomainOptions o;
  o.domain = {path, "", ""};
  Error e = expect_error([&] { read_domain(o); });
  EXPECT_EQ(e.code(), ExitCode::kCrsError);
  expect_contains(e.what(), "has no CRS");
  o.s_srs = "EPSG:32618";
  GisInput in = read_domain(o);
  EXPECT_EQ(in.counts.boundary_segments, 3u);
  EXPECT_EQ(in.frame.epsg(), 32618);
}

TEST(ReadDomainErrors, NoDomainIsUsageError) {
  DomainOptions o;
  Error e = expect_error([&] { read_domain(o); });
  EXPECT_EQ(e.code(), ExitCode::kUsage);
  o.land = {kChes + "shp/chesapeake_mouth_land.shp", "", ""};
  Error e2 = expect_error([&] { read_domain(o); });
  EXPECT_EQ(e2.code(), ExitCode::kUsage);
  expect_contains(e2.what(), "--extent");
}

TEST(ReadDomain, MixedCrsOpenBoundaryIsReprojected) {
  // The open boundary in Web Mercator while the water is in lon/lat: same 12 open parts.
  GDALAllRegister();
  const std::string out = testing::TempDir() + "/gis_open_3857.geojson";
  std::remove(out.c_str());
  const char* argv[] = {"-t_srs", "EPSG:3857", "-lco", "RFC7946=NO", "-lco", "COORDINATE_PRECISION=15", nullptr};
  GDALVectorTranslateOptions* opt = GDALVectorTranslateOptionsNew(const_cast<char**>(argv), nullptr);
  GDALDatasetH src = GDALOpenEx((kChes + "chesapeake_mouth_open_boundary.geojson").c_str(), GDAL_OF_VECTOR, nullptr,
                                nullptr, nullptr);
  ASSERT_NE(src, nullptr);
  GDALDatasetH dst = GDALVectorTranslate(out.c_str(), nullptr, 1, &src, opt, nullptr);
  ASSERT_NE(dst, nullptr);
  GDALClose(dst);
  GDALClose(src);
  GDALVectorTranslateOptionsFree(opt);
  GisInput in = read_domain(chesapeake(kChes + "chesapeake_mouth_water.geojson", out));
  EXPECT_EQ(in.counts.open_parts, 12u);
  EXPECT_EQ(in.counts.open_segments, 14u);
  // With --densify 0.1: 14 source segments, 29 after densification (3 sides get 15 points); the
  // Mercator lines are densified in the water layer's lon/lat, so they get the polygon's points
  // and every densified piece matches.
  DomainOptions d = chesapeake(kChes + "chesapeake_mouth_water.geojson", out);
  d.densify_deg = 0.1;
  GisInput dn = read_domain(d);
  EXPECT_EQ(dn.counts.densify_points, 2u * 15u);
  EXPECT_EQ(dn.counts.boundary_segments, 1984u + 15u);
  EXPECT_EQ(dn.counts.open_parts, 12u);
  EXPECT_EQ(dn.counts.open_segments, 29u);
}

TEST(ReadDomain, CurvesLinearizedAndZDropped) {
  // A curved polygon with Z in UTM 18N (a CSV with WKT, CRS from --s_srs).
  const std::string path = testing::TempDir() + "/gis_curve.csv";
  FILE* f = std::fopen(path.c_str(), "w");
  ASSERT_NE(f, nullptr);
  std::fputs("id,WKT\n1,\"CURVEPOLYGON Z (CIRCULARSTRING Z (400000 4100000 5,401000 4101000 5,400000 4102000 5,"
             "399000 4101000 5,400000 4100000 5))\"\n", f);
  std::fclose(f);
  DomainOptions o;
  o.domain = {path, "", ""};
  o.s_srs = "EPSG:32618";
  GisInput in = read_domain(o);
  EXPECT_GT(in.counts.boundary_segments, 16u);  // linearized arc
  // The area of a 1 km radius circle, up to the chord error.
  EXPECT_NEAR(in.domain_area_m2, M_PI * 1e6, 0.01 * M_PI * 1e6);
  for (const auto& p : in.raw.points) EXPECT_NEAR(dist(p + in.raw.origin, {400000, 4101000}), 1000.0, 1e-6);
}

TEST(ReadDomain, LongLonLatEdgeDensifiedAlikeInPolygonAndOpenLine) {
  // --densify 0.1. A 10 x 4 degree lon/lat box; its bottom side (one 10-degree segment) is the open boundary,
  // drawn in the opposite direction. Both are densified to 0.1 degree: 100 pieces each, and every
  // piece of the ring matches a piece of the line (bitwise the same points: the matching
  // tolerance here is 1e-7 of the domain size, far below a chord's sagitta of ~10 m).
  const std::string dir = testing::TempDir();
  const std::string poly = dir + "/gis_longbox.geojson", line = dir + "/gis_longbox_open.geojson";
  FILE* f = std::fopen(poly.c_str(), "w");
  ASSERT_NE(f, nullptr);
  std::fputs(R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{},"geometry":)"
             R"({"type":"Polygon","coordinates":[[[-80,20],[-70,20],[-70,24],[-80,24],[-80,20]]]}}]})", f);
  std::fclose(f);
  f = std::fopen(line.c_str(), "w");
  ASSERT_NE(f, nullptr);
  std::fputs(R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{},"geometry":)"
             R"({"type":"LineString","coordinates":[[-70,20],[-80,20]]}}]})", f);
  std::fclose(f);
  DomainOptions o;
  o.domain = {poly, "", ""};
  o.open_boundary = {line, "", ""};
  GisInput chords = read_domain(o);  // default: no densification, the 4 sides are chords (counted)
  EXPECT_EQ(chords.counts.densified_segments, 0u);
  EXPECT_EQ(chords.counts.long_chords, 4u);
  EXPECT_EQ(chords.counts.open_segments, 1u);
  o.densify_deg = 0.1;
  GisInput in = read_domain(o);
  EXPECT_EQ(in.counts.long_chords, 0u);
  EXPECT_EQ(in.counts.densified_segments, 4u + 1u);         // 4 box sides + the open line
  EXPECT_EQ(in.counts.densify_points, 2u * (99u + 39u) + 99u);
  EXPECT_EQ(in.counts.boundary_segments, 2u * (100u + 40u));  // 4 source segments
  EXPECT_EQ(in.counts.open_parts, 1u);
  EXPECT_EQ(in.counts.open_segments, 100u);
  // The densified side follows the parallel: its middle point is at latitude 20 exactly.
  const Point2 mid = in.frame.lonlat_to_local({-75.0, 20.0});
  bool found = false;
  for (const auto& p : in.raw.points) found |= dist(p, mid) < 1e-6;
  EXPECT_TRUE(found);
}
