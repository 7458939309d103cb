// clean() on raw GSHHG shoreline pieces (testdata extracts): the result validates, the known
// self-intersections are split, exact duplicates at bin edges are merged, runs are deterministic.
#include <gtest/gtest.h>
#include <chrono>
#include <cstring>
#include "pslg/clean.hpp"
#include "pslg/poly_io.hpp"
#include "pslg/validate.hpp"
#include "test_util.hpp"

using namespace fdr;
using namespace fdr::pslg;
using namespace fdr::pslg::test;

namespace {
std::size_t count_kind(const std::vector<Repair>& r, const std::string& kind) {
  std::size_t n = 0;
  for (const auto& x : r) n += x.kind == kind;
  return n;
}
}  // namespace

TEST(RealData, BoothbayRawIsRepaired) {
  // Box -69.85/-69.65/43.70/43.90 holds GSHHG's figure-eight ring and two crossing pieces.
  const Pslg in = read_poly(testdata("gulf_of_maine/boothbay_raw.poly"));
  EXPECT_THROW(validate(in, "raw"), Error);  // raw pieces repeat their joining points
  std::vector<Repair> rep;
  const Pslg out = clean(in, {}, &rep);
  EXPECT_NO_THROW(validate(out, "boothbay"));
  EXPECT_GT(count_kind(rep, "snap"), 0u);
  EXPECT_EQ(count_kind(rep, "crossing_split"), 2u);
  // The data README's crossings: (-69.76511, 43.84251) between two pieces, local (-1213, 4727) m,
  // and the figure-eight at (-69.75368, 43.77472), local (-295, -2811) m.
  const Point2 known[2] = {{-1212.67, 4726.90}, {-295.34, -2811.01}};
  for (const Point2 k : known) {
    bool found = false;
    for (const auto& r : rep)
      if (r.kind == "crossing_split" && dist(r.where, k) < 5) found = true;
    EXPECT_TRUE(found) << k.x << " " << k.y;
  }
  const Pslg again = clean(in, {}, nullptr);
  ASSERT_EQ(again.points.size(), out.points.size());
  EXPECT_EQ(std::memcmp(again.points.data(), out.points.data(), out.points.size() * sizeof(Point2)), 0);
}

TEST(RealData, ChesapeakeRawWithTinyIslands) {
  const Pslg in = read_poly(testdata("chesapeake_mouth/chesapeake_raw.poly"));
  CleanOptions opt;
  opt.snap_distance = 0.5;
  opt.min_island_area_factor = 1.0;
  opt.spacing = [](Point2) { return 200.0; };  // drops islands below 40000 m^2
  opt.simplify_factor = 0.5;
  opt.simplify_tolerance = 5.0;
  std::vector<Repair> rep;
  const auto t0 = std::chrono::steady_clock::now();
  const Pslg out = clean(in, opt, &rep);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("chesapeake raw: %zu -> %zu points, %zu -> %zu segments, %zu repairs, %.3f s\n", in.points.size(),
              out.points.size(), in.segments.size(), out.segments.size(), rep.size(), s);
  EXPECT_NO_THROW(validate(out, "chesapeake"));
  EXPECT_GT(count_kind(rep, "tiny_island"), 0u);
  for (const auto& r : rep) {
    if (r.kind == "tiny_island") { EXPECT_LT(r.size, 40000.0); }
    if (r.kind == "simplify") { EXPECT_LT(r.size, 5.0); }
  }
}
