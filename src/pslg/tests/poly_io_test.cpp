// Triangle .poly/.node I/O: round trips, the index-base and .node conventions, every error path.
#include <gtest/gtest.h>
#include <numbers>
#include <random>
#include "pslg/poly_io.hpp"
#include "pslg/validate.hpp"
#include "test_util.hpp"

using namespace fdr;
using namespace fdr::pslg;
using namespace fdr::pslg::test;

namespace {

void expect_equal(const Pslg& a, const Pslg& b) {
  EXPECT_EQ(a.origin, b.origin);
  ASSERT_EQ(a.points.size(), b.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) EXPECT_EQ(a.points[i], b.points[i]) << i;
  EXPECT_EQ(a.point_markers, b.point_markers);
  ASSERT_EQ(a.segments.size(), b.segments.size());
  for (std::size_t i = 0; i < a.segments.size(); ++i) {
    EXPECT_EQ(a.segments[i].a, b.segments[i].a);
    EXPECT_EQ(a.segments[i].b, b.segments[i].b);
    EXPECT_EQ(a.segments[i].marker, b.segments[i].marker);
  }
  ASSERT_EQ(a.holes.size(), b.holes.size());
  for (std::size_t i = 0; i < a.holes.size(); ++i) EXPECT_EQ(a.holes[i], b.holes[i]);
  ASSERT_EQ(a.regions.size(), b.regions.size());
  for (std::size_t i = 0; i < a.regions.size(); ++i) {
    EXPECT_EQ(a.regions[i].seed, b.regions[i].seed);
    EXPECT_EQ(a.regions[i].attribute, b.regions[i].attribute);
    EXPECT_EQ(a.regions[i].max_area, b.regions[i].max_area);
  }
}

Pslg random_pslg(std::mt19937_64& rng, bool markers) {
  std::uniform_real_distribution<double> u(-1e6, 1e6);
  Pslg g;
  g.origin = {u(rng) * 1e3, u(rng)};
  const int n = 50;
  for (int i = 0; i < n; ++i) {
    g.points.push_back({u(rng) * 1e-7, u(rng)});
    if (markers) g.point_markers.push_back(static_cast<std::int32_t>(rng() % 7) - 3);
  }
  for (int i = 0; i < 40; ++i)
    g.segments.push_back({static_cast<Index>(rng() % n), static_cast<Index>(rng() % n),
                          static_cast<std::int32_t>(rng() % 5), -1});
  g.holes.push_back({u(rng), -0.1});
  g.regions.push_back({{u(rng), 1e-300}, 3.5, -1});
  g.regions.push_back({{1, 2}, -7, 12.25});
  return g;
}

}  // namespace

TEST(PolyIo, RoundTripIsBitExact) {
  std::mt19937_64 rng(11);
  for (int k = 0; k < 20; ++k) {
    const Pslg g = random_pslg(rng, k % 2 == 0);
    const std::string p = temp_path("round_trip.poly");
    write_poly(g, p);
    EXPECT_FALSE(std::filesystem::exists(p + ".tmp"));
    expect_equal(g, read_poly(p));
  }
}

TEST(PolyIo, RoundTripPointsOnly) {
  // (A PSLG with no points is not representable: Triangle reads a 0-vertex .poly's vertices
  // from the .node file.)
  Pslg g;
  g.points = {{0.1, 0.2}, {-3, 1e-310}};
  const std::string p = temp_path("empty.poly");
  write_poly(g, p);
  expect_equal(g, read_poly(p));
}

TEST(PolyIo, SquareWithHoleOneBased) {
  const Pslg g = read_poly(testdata("poly/square_with_hole.poly"));
  ASSERT_EQ(g.points.size(), 8u);
  ASSERT_EQ(g.segments.size(), 8u);
  EXPECT_EQ(g.points[0], (Point2{0, 0}));
  EXPECT_EQ(g.points[6], (Point2{7, 7}));
  EXPECT_EQ(g.segments[3].a, 3u);  // "4 4 1" in 1-based ids
  EXPECT_EQ(g.segments[3].b, 0u);
  EXPECT_EQ(g.segments[7].marker, 2);
  EXPECT_EQ(g.point_markers, (std::vector<std::int32_t>{1, 1, 1, 1, 2, 2, 2, 2}));
  ASSERT_EQ(g.holes.size(), 1u);
  EXPECT_EQ(g.holes[0], (Point2{5, 5}));
  EXPECT_TRUE(g.regions.empty());
  EXPECT_NO_THROW(validate(g, "square_with_hole"));
}

TEST(PolyIo, InteriorSegmentWithRegionAndComments) {
  const Pslg g = read_poly(testdata("poly/interior_segment.poly"));
  ASSERT_EQ(g.points.size(), 6u);
  EXPECT_TRUE(g.point_markers.empty());
  ASSERT_EQ(g.segments.size(), 5u);
  EXPECT_EQ(g.segments[4].marker, kBreaklineMarker);
  EXPECT_EQ(g.segments[1].marker, 3);
  ASSERT_EQ(g.regions.size(), 1u);
  EXPECT_EQ(g.regions[0].seed, (Point2{10, 1}));
  EXPECT_EQ(g.regions[0].attribute, 7);
  EXPECT_EQ(g.regions[0].max_area, 2.5);
  EXPECT_NO_THROW(validate(g, "interior_segment"));
}

TEST(PolyIo, WedgeIsValid) {
  const Pslg g = read_poly(testdata("poly/wedge_1deg.poly"));
  ASSERT_EQ(g.points.size(), 3u);
  const double ang = std::atan2(g.points[2].y, g.points[2].x) * 180 / std::numbers::pi;
  EXPECT_NEAR(ang, 1.0, 1e-12);
  EXPECT_NO_THROW(validate(g, "wedge"));
}

TEST(PolyIo, VerticesFromSiblingNodeFile) {
  const Pslg g = read_poly(testdata("poly/from_node.poly"));
  ASSERT_EQ(g.points.size(), 4u);
  EXPECT_EQ(g.points[2], (Point2{1, 1}));
  EXPECT_EQ(g.point_markers, (std::vector<std::int32_t>{1, 1, 1, 1}));
  ASSERT_EQ(g.segments.size(), 4u);
  EXPECT_EQ(g.segments[3].a, 3u);
  EXPECT_EQ(g.segments[3].b, 0u);
  const Pslg n = read_node(testdata("poly/from_node.node"));
  EXPECT_EQ(n.points.size(), 4u);
  EXPECT_TRUE(n.segments.empty());
}

TEST(PolyIo, HeaderDefaultsAndPlusSigns) {
  // Triangle lets headers omit trailing fields (dimension 2, no attributes, no markers).
  const std::string p = write_temp("short_headers.poly", "3\n0 +1 0\n1 2 0\n2 1 1.5e0\n3\n0 0 1\n1 1 2\n2 2 0\n0\n");
  const Pslg g = read_poly(p);
  EXPECT_EQ(g.points[0], (Point2{1, 0}));
  EXPECT_EQ(g.segments.size(), 3u);
  EXPECT_EQ(g.segments[0].marker, 0);
}

TEST(PolyIo, TestdataBadFiles) {
  struct Case {
    const char* file;
    int line;
    const char* what;
  };
  const Case cases[] = {
      {"bad_count.poly", 10, "file ends early"},  {"bad_fields.poly", 4, "too many fields"},
      {"bad_number.poly", 5, "not a number"},     {"bad_index.poly", 8, "out of range"},
      {"bad_nan.poly", 3, "not finite"},          {"bad_inf.poly", 4, "not finite"},
      {"bad_dimension.poly", 2, "dimension"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.file);
    expect_error([&] { read_poly(testdata(std::string("poly/") + c.file)); }, ExitCode::kInputMalformed,
                 {std::string(c.file) + ":" + std::to_string(c.line) + ":", c.what});
  }
}

TEST(PolyIo, MalformedInline) {
  struct Case {
    const char* text;
    int line;
    const char* what;
  };
  const Case cases[] = {
      {"", 0, "file ends early"},
      {"# only a comment\n\n", 2, "file ends early"},
      {"3 2 0 0\n0 0 0\n1 1 0\n", 3, "expected 3 vertices"},
      {"2 2 0 0 9\n", 1, "too many fields"},
      {"2 2 0 2\n", 1, "out of range"},
      {"2 2 -1 0\n", 1, "out of range"},
      {"-2 2 0 0\n", 1, "out of range"},
      {"x 2 0 0\n", 1, "not an integer"},
      {"2 2 0 0\n0 0 0\n1 1\n", 3, "too few fields"},
      {"2 2 0 0\n2 0 0\n3 1 1\n", 2, "first vertex id"},
      {"2 2 0 0\n0 0 0\n2 1 1\n", 3, "consecutive"},
      {"2 2 0 0\n0 0 0\n1 1 1e999\n", 3, "out of range"},
      {"2 2 0 0\n0 0 0\n1 1 1x\n", 3, "not a number"},
      {"2 2 0 0\n0 0 0\n1 1 -inf\n", 3, "not finite"},
      {"2 2 0 1\n0 0 0 1\n1 1 1 z\n", 3, "not an integer"},
      {"2 2 1 0\n0 0 0 nan\n1 1 1 0\n", 2, "not finite"},
      {"2 2 0 0\n0 0 0\n1 1 1\n1 1\n0 0 1\n", 5, "too few fields"},
      {"2 2 0 0\n0 0 0\n1 1 1\n1 0\n0 0 -1\n", 5, "out of range"},
      {"2 2 0 0\n0 0 0\n1 1 1\n1 0\n0 0 1\n", 5, "hole header"},
      {"2 2 0 0\n0 0 0\n1 1 1\n1 0\n0 0 1\n1\n", 6, "expected 1 holes"},
      {"2 2 0 0\n0 0 0\n1 1 1\n1 0\n0 0 1\n1\n0 0.5 inf\n", 7, "not finite"},
      {"2 2 0 0\n0 0 0\n1 1 1\n1 0\n0 0 1\n0\n1\n0 1 1 3\n", 8, "too few fields"},
      {"2 2 0 0\n0 0 0\n1 1 1\n1 0\n0 0 1\n0\n0\n5\n", 8, "unexpected content"},
      {"2 2 0 0\n0 0 0\n1 1 1\n1 0\n0 0 1\n0 3\n", 6, "too many fields"},
      {"# fdrmesh-origin 1 q\n", 1, "fdrmesh-origin"},
  };
  int k = 0;
  for (const auto& c : cases) {
    SCOPED_TRACE(c.text);
    const std::string name = "inline_" + std::to_string(k++) + ".poly";
    const std::string p = write_temp(name, c.text);
    expect_error([&] { read_poly(p); }, ExitCode::kInputMalformed, {name + ":" + std::to_string(c.line) + ":", c.what});
  }
}

TEST(PolyIo, MissingFiles) {
  expect_error([] { read_poly("/nonexistent/dir/nothing.poly"); }, ExitCode::kInputUnreadable,
               {"/nonexistent/dir/nothing.poly"});
  expect_error([] { read_node("/nonexistent/x.node"); }, ExitCode::kInputUnreadable, {"/nonexistent/x.node"});
  const std::string dir = temp_path("a_directory.poly");
  std::filesystem::create_directories(dir);
  expect_error([&] { read_poly(dir); }, ExitCode::kInputUnreadable, {"a_directory.poly"});
  // A .poly with no vertices whose .node sibling is missing names the .node file.
  const std::string p = write_temp("orphan.poly", "0 2 0 0\n0 0\n0\n");
  expect_error([&] { read_poly(p); }, ExitCode::kInputUnreadable, {"orphan.node"});
}

TEST(PolyIo, WriteErrors) {
  Pslg g;
  g.points = {{0, 0}, {1, 0}};
  expect_error([&] { write_poly(g, "/nonexistent/dir/out.poly"); }, ExitCode::kOutputError, {"/nonexistent/dir/out.poly"});
}

// Found by fuzzing (tools/fuzz, target poly_reader): headers claiming billions of vertices made
// the reader reserve that many entries first (std::bad_alloc: "ERROR 7: out of memory" for a
// 26-byte file; 3 GB allocations under ASan). Reservations are now capped by the file's size,
// and the file is reported as malformed.
TEST(PolyIo, FuzzHugeCountsAreMalformedNotOutOfMemory) {
  for (int k = 1; k <= 3; ++k) {
    const std::string path = std::string(FDR_TESTDATA_DIR) + "/regress/fuzz_poly_reader_" + std::to_string(k) + ".poly";
    try {
      (void)fdr::pslg::read_poly(path);
      ADD_FAILURE() << path << " was accepted";
    } catch (const fdr::Error& e) {
      EXPECT_EQ(e.code(), fdr::ExitCode::kInputMalformed) << path << ": " << e.what();
    }
  }
}
