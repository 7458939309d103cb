// Tests of the quality metrics, FDR guarantees and report writers on hand-built meshes.
#include <gtest/gtest.h>
#include <numbers>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>
#include <nlohmann/json.hpp>

#include "base/error.hpp"
#include "quality/report.hpp"
#include "quality/rss.hpp"

namespace fdr::quality {
namespace {

const double kSqrt2 = std::sqrt(2.0);
const double kSqrt3 = std::sqrt(3.0);

class ConstantField : public sizing::SizingField {
 public:
  explicit ConstantField(double v) : v_(v) {}
  double operator()(Point2) const override { return v_; }
  double lipschitz() const override { return 0.0; }
  std::string describe() const override { return "constant"; }

 private:
  double v_;
};

// f(x, y) = x + 1: 1-Lipschitz, varies across the right triangle.
class RampField : public sizing::SizingField {
 public:
  double operator()(Point2 p) const override { return p.x + 1.0; }
  std::string describe() const override { return "x+1"; }
};

mesh::MeshView equilateral() {
  mesh::MeshView m;
  m.vertices = {{0, 0}, {1, 0}, {0.5, kSqrt3 / 2}};
  m.triangles = {{0, 1, 2}};
  return m;
}

mesh::MeshView right_isoceles() {
  mesh::MeshView m;
  m.vertices = {{0, 0}, {1, 0}, {0, 1}};
  m.triangles = {{0, 1, 2}};
  return m;
}

// 3x3 vertices on [0,2]^2, each unit square cut along its (i,j)-(i+1,j+1) diagonal: 8 triangles.
mesh::MeshView grid2x2() {
  mesh::MeshView m;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) m.vertices.push_back({double(i), double(j)});
  auto id = [](int i, int j) { return Index(j * 3 + i); };
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

TEST(Quality, EquilateralTriangle) {
  const ConstantField f(1.0);
  const auto r = compute_quality(equilateral(), &f, 0.5, 0.0, RunInfo{});
  EXPECT_EQ(r.vertices, 3u);
  EXPECT_EQ(r.triangles, 1u);
  EXPECT_NEAR(*r.min_angle_deg, 60.0, 1e-9);
  EXPECT_NEAR(*r.max_angle_deg, 60.0, 1e-9);
  EXPECT_NEAR(*r.max_radius_edge, 1.0 / kSqrt3, 1e-12);  // R = 1/sqrt(3), l = 1
  EXPECT_NEAR(*r.max_R_over_f, 1.0 / kSqrt3, 1e-12);
  EXPECT_NEAR(*r.mean_R_over_f, 1.0 / kSqrt3, 1e-12);
  EXPECT_EQ(*r.bad_triangles, 1u);  // 0.577 > B = 0.5
  EXPECT_NEAR(r.area, kSqrt3 / 4, 1e-15);
  EXPECT_EQ(r.min_angle_histogram.counts[11], 1u);  // 55-60 bin (60 lands in the closed last bin)
  EXPECT_EQ(r.max_angle_histogram.counts[0], 1u);   // 60-65
  EXPECT_NEAR(*r.conformity_min, 1.0, 1e-12);
  EXPECT_NEAR(*r.conformity_mean, 1.0, 1e-12);
  EXPECT_NEAR(*r.conformity_p05, 1.0, 1e-12);
  EXPECT_EQ(r.conformity_histogram.counts[9], 3u);
  EXPECT_NEAR(*r.el_over_f_max, 1.0, 1e-12);
  EXPECT_NEAR(*r.nn_over_f_min, 1.0, 1e-12);
  EXPECT_NEAR(*r.nn_min, 1.0, 1e-12);
  EXPECT_EQ(r.degenerate_triangles, 0u);
  EXPECT_EQ(r.inverted_triangles, 0u);

  const auto r1 = compute_quality(equilateral(), &f, 1.0, 0.0, RunInfo{});
  EXPECT_EQ(*r1.bad_triangles, 0u);
}

TEST(Quality, RightIsocelesWithRampSpacing) {
  const RampField f;
  const auto r = compute_quality(right_isoceles(), &f, 0.4, 1.0, RunInfo{});
  EXPECT_NEAR(*r.min_angle_deg, 45.0, 1e-9);
  EXPECT_NEAR(*r.max_angle_deg, 90.0, 1e-9);
  EXPECT_NEAR(*r.max_radius_edge, kSqrt2 / 2, 1e-12);
  // Circumcenter (0.5, 0.5): f = 1.5, R/f = (sqrt(2)/2) / 1.5.
  EXPECT_NEAR(*r.max_R_over_f, kSqrt2 / 3, 1e-12);
  EXPECT_EQ(*r.bad_triangles, 1u);  // 0.471 > 0.4
  EXPECT_NEAR(r.area, 0.5, 1e-15);
  EXPECT_EQ(r.min_angle_histogram.counts[9], 1u);  // 45-50
  EXPECT_EQ(r.max_angle_histogram.counts[6], 1u);  // 90-95
  // nn = 1 at every vertex; f = 1, 2, 1 -> conformity 1, 0.5, 1.
  EXPECT_NEAR(*r.conformity_min, 0.5, 1e-12);
  EXPECT_NEAR(*r.conformity_mean, 2.5 / 3, 1e-12);
  EXPECT_NEAR(*r.conformity_p05, 0.5, 1e-12);
  EXPECT_EQ(r.conformity_histogram.counts[5], 1u);
  EXPECT_EQ(r.conformity_histogram.counts[9], 2u);
  // el = sqrt(2) everywhere; el/f max at f = 1.
  EXPECT_NEAR(*r.el_over_f_max, kSqrt2, 1e-12);
  EXPECT_NEAR(*r.nn_over_f_min, 0.5, 1e-12);
  EXPECT_TRUE(r.guarantees.valid);  // alpha*B = 0.4 < 1
}

TEST(Quality, Grid2x2ConstantSpacing) {
  const ConstantField f(0.5);
  const auto r = compute_quality(grid2x2(), &f, 1.0, 0.0, RunInfo{});
  EXPECT_EQ(r.vertices, 9u);
  EXPECT_EQ(r.triangles, 8u);
  EXPECT_NEAR(r.area, 4.0, 1e-15);
  EXPECT_NEAR(*r.min_angle_deg, 45.0, 1e-9);
  EXPECT_NEAR(*r.max_angle_deg, 90.0, 1e-9);
  EXPECT_NEAR(*r.max_radius_edge, kSqrt2 / 2, 1e-12);
  EXPECT_NEAR(*r.max_R_over_f, kSqrt2, 1e-12);
  EXPECT_NEAR(*r.mean_R_over_f, kSqrt2, 1e-12);
  EXPECT_EQ(*r.bad_triangles, 8u);
  EXPECT_EQ(r.min_angle_histogram.counts[9], 8u);
  // nn = 1, f = 0.5: conformity min(2, 0.5) = 0.5 at all 9 vertices.
  EXPECT_NEAR(*r.conformity_min, 0.5, 1e-12);
  EXPECT_NEAR(*r.conformity_mean, 0.5, 1e-12);
  EXPECT_NEAR(*r.conformity_p05, 0.5, 1e-12);
  EXPECT_EQ(r.conformity_histogram.counts[5], 9u);
  EXPECT_NEAR(*r.nn_over_f_min, 2.0, 1e-12);
  EXPECT_NEAR(*r.el_over_f_max, 2 * kSqrt2, 1e-12);  // every triangle has a sqrt(2) hypotenuse
  std::uint64_t total = 0;
  for (auto c : r.min_angle_histogram.counts) total += c;
  EXPECT_EQ(total, 8u);
}

TEST(Quality, PerVertexSpacingWithoutField) {
  auto m = equilateral();
  m.f = {2.0, 2.0, 2.0};
  const auto r = compute_quality(m, nullptr, 1.0, 0.0, RunInfo{});
  EXPECT_FALSE(r.max_R_over_f.has_value());  // circumcenter values need the field itself
  EXPECT_FALSE(r.bad_triangles.has_value());
  EXPECT_NEAR(*r.conformity_min, 0.5, 1e-12);
  EXPECT_NEAR(*r.el_over_f_max, 0.5, 1e-12);
  EXPECT_EQ(r.spacing, "none");
}

TEST(Quality, NoSpacingAtAll) {
  const auto r = compute_quality(grid2x2(), nullptr, 1.0, -1.0, RunInfo{});
  EXPECT_FALSE(r.conformity_min.has_value());
  EXPECT_FALSE(r.el_over_f_max.has_value());
  EXPECT_NEAR(*r.nn_min, 1.0, 1e-12);
  EXPECT_NEAR(*r.min_angle_deg, 45.0, 1e-9);
  EXPECT_FALSE(r.guarantees.valid);
}

TEST(Quality, InvalidSpacingValuesAreCountedAndSkipped) {
  const ConstantField f(0.0);
  const auto r = compute_quality(equilateral(), &f, 1.0, 0.0, RunInfo{});
  EXPECT_EQ(r.spacing_invalid, 4u);  // one circumcenter + three vertices
  EXPECT_FALSE(r.max_R_over_f.has_value());
  EXPECT_FALSE(r.conformity_min.has_value());
}

TEST(Quality, DegenerateAndInvertedTriangles) {
  mesh::MeshView m;
  m.vertices = {{0, 0}, {1, 0}, {2, 0}, {0, 1}};
  m.triangles = {{0, 1, 2}, {0, 3, 1}};  // collinear, then clockwise
  const ConstantField f(1.0);
  const auto r = compute_quality(m, &f, 1.0, 0.0, RunInfo{});
  EXPECT_EQ(r.degenerate_triangles, 1u);
  EXPECT_EQ(r.inverted_triangles, 1u);
  EXPECT_TRUE(std::isinf(*r.max_radius_edge));
  EXPECT_EQ(*r.bad_triangles, 1u);  // the degenerate one (R infinite)
  EXPECT_NEAR(r.area, -0.5, 1e-15);
  EXPECT_NEAR(*r.max_angle_deg, 180.0, 1e-9);
  std::ostringstream js;
  write_json(r, js);
  const auto j = nlohmann::json::parse(js.str());
  EXPECT_TRUE(j["max_radius_edge"].is_null());  // inf is not JSON
  EXPECT_EQ(j["degenerate_triangles"], 1);
}

TEST(Quality, BadVertexIdThrowsInternal) {
  auto m = equilateral();
  m.triangles.push_back({0, 1, 7});
  try {
    compute_quality(m, nullptr, 1.0, 0.0, RunInfo{});
    FAIL() << "expected fdr::Error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInternal);
    EXPECT_NE(std::string(e.what()).find("triangle 1"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("vertex 7"), std::string::npos);
  }
}

TEST(Quality, NearestNeighbourIsGlobalNotMeshNeighbour) {
  // Two unit right triangles 0.1 apart and not sharing an edge: nn comes from the other one.
  mesh::MeshView m;
  m.vertices = {{0, 0}, {1, 0}, {0, 1}, {1.1, 0}, {2.1, 0}, {1.1, 1}};
  m.triangles = {{0, 1, 2}, {3, 4, 5}};
  const ConstantField f(1.0);
  const auto r = compute_quality(m, &f, 1.0, -1.0, RunInfo{});
  EXPECT_NEAR(*r.nn_min, 0.1, 1e-12);
  EXPECT_NEAR(*r.nn_over_f_min, 0.1, 1e-12);
  EXPECT_NEAR(*r.conformity_min, 0.1, 1e-12);
  EXPECT_NEAR(r.area, 1.0, 1e-15);
  // alpha unknown (-1): the field's own Lipschitz constant (0) is used.
  EXPECT_EQ(r.alpha, 0.0);
  EXPECT_TRUE(r.guarantees.valid);
  EXPECT_NEAR(r.guarantees.R_over_l_max, kSqrt2, 1e-15);
}

TEST(Quality, NearestNeighbourMatchesBruteForce) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Point2> pts;
  // Graded cloud (dense near the origin) plus exact duplicates and lattice points (ties).
  for (int i = 0; i < 1500; ++i) {
    const double s = std::pow(u(rng), 3.0);
    pts.push_back({s * u(rng), s * u(rng)});
  }
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j) pts.push_back({2.0 + i, 2.0 + j});
  pts.push_back(pts[17]);
  const auto nn = nearest_neighbour_distances(pts);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    double best = INFINITY;
    for (std::size_t k = 0; k < pts.size(); ++k)
      if (k != i) best = std::min(best, dist(pts[i], pts[k]));
    ASSERT_EQ(nn[i], best) << "vertex " << i;
  }
  EXPECT_EQ(nn[17], 0.0);
  EXPECT_TRUE(std::isinf(nearest_neighbour_distances({{1, 1}})[0]));
}

TEST(Guarantees, HandValuesAlpha01B1) {
  const auto g = compute_guarantees(0.1, 1.0);
  ASSERT_TRUE(g.valid);
  // beta = 1 / (2 sqrt 2 + 0.3) = 1 / 3.1284271 = 0.3196494
  EXPECT_NEAR(g.beta, 0.3196494, 1e-7);
  // R/l <= 3.1284271 / (2 * 0.9) = 1.7380151
  EXPECT_NEAR(g.R_over_l_max, 1.7380151, 1e-7);
  // sin(theta) >= 0.9 / 3.1284271 = 0.2876837 -> theta = 16.71938 deg
  EXPECT_NEAR(g.min_angle_deg, 16.71938, 1e-5);
  // nn/f >= 2 * 0.3196494 / (1 + 0.03196494) = 0.6194967
  EXPECT_NEAR(g.nn_over_f_min, 0.6194967, 1e-7);
  // el/f <= 2 / 1.1
  EXPECT_NEAR(g.el_over_f_max, 1.8181818, 1e-7);
  // The min-angle bound is the R/l bound restated: R/l = 1 / (2 sin theta).
  EXPECT_NEAR(1.0 / (2.0 * std::sin(g.min_angle_deg * std::numbers::pi / 180)), g.R_over_l_max, 1e-12);
}

TEST(Guarantees, ConstantSpacingGivesSqrt2) {
  const auto g = compute_guarantees(0.0, 0.7);
  ASSERT_TRUE(g.valid);
  EXPECT_NEAR(g.R_over_l_max, kSqrt2, 1e-15);  // the paper's abstract: sqrt(2) in 2D
  EXPECT_NEAR(g.min_angle_deg, 20.7048, 1e-4);  // asin(1 / (2 sqrt 2))
  EXPECT_NEAR(g.el_over_f_max, 1.4, 1e-15);
}

// Section 4: beta = min(B / (2 sqrt 2 + 3 alpha B), D / (2 + alpha D)); the theorems' bounds follow
// from that beta. A large D leaves the B-limited values; a small one weakens them.
TEST(Guarantees, ConformingMeshDLimitsBeta) {
  const auto g0 = compute_guarantees(0.1, 1.0);
  const auto big = compute_guarantees(0.1, 1.0, 5.0);
  ASSERT_TRUE(big.valid);
  EXPECT_EQ(big.beta, g0.beta);
  EXPECT_EQ(big.R_over_l_max, g0.R_over_l_max);
  EXPECT_NEAR(*big.beta_D, 5.0 / 2.5, 1e-15);
  const auto g = compute_guarantees(0.1, 1.0, 0.02);
  ASSERT_TRUE(g.valid);
  const double beta = 0.02 / (2 + 0.1 * 0.02);
  EXPECT_NEAR(g.beta, beta, 1e-15);
  EXPECT_NEAR(g.beta_B, g0.beta, 1e-15);
  EXPECT_NEAR(g.R_over_l_max, 1.0 / (2 * beta * 0.9), 1e-9);
  EXPECT_NEAR(g.nn_over_f_min, 2 * beta / (1 + 0.1 * beta), 1e-15);
  EXPECT_NEAR(1.0 / (2.0 * std::sin(g.min_angle_deg * std::numbers::pi / 180)), g.R_over_l_max, 1e-9);
  EXPECT_EQ(g.el_over_f_max, g0.el_over_f_max);  // Theorem 4.5 does not use beta
  EXPECT_NE(g.note.find("D/(2+alpha*D) <"), std::string::npos) << g.note;
  const auto z = compute_guarantees(0.1, 1.0, 0.0);  // two vertices at one point
  EXPECT_TRUE(z.valid);
  EXPECT_EQ(z.nn_over_f_min, 0.0);
  EXPECT_TRUE(std::isinf(z.R_over_l_max));
}

TEST(Guarantees, InvalidWhenAlphaBAtLeastOne) {
  for (auto [a, b] : {std::pair{0.5, 2.0}, std::pair{1.0, 1.5}}) {
    const auto g = compute_guarantees(a, b);
    EXPECT_FALSE(g.valid);
    EXPECT_NE(g.note.find(">= 1"), std::string::npos) << g.note;
  }
  EXPECT_FALSE(compute_guarantees(-1.0, 1.0).valid);  // alpha unknown
  EXPECT_FALSE(compute_guarantees(0.1, 0.0).valid);   // B must be positive
  EXPECT_TRUE(compute_guarantees(0.4, 1.0).valid);
}

TEST(Writers, JsonHasEveryRequiredField) {
  const ConstantField f(0.5);
  RunInfo run;
  run.cdt_s = 0.25;
  run.refine_s = 1.5;
  run.total_s = 2.0;
  run.peak_rss_mb = 12.5;
  run.predicate_filtered = 100;
  run.predicate_exact = 3;
  run.exempt_small_angle_triangles = 2;
  run.steiner_segment = 4;
  run.steiner_interior = 6;
  run.input_file = "square.poly";
  const auto r = compute_quality(grid2x2(), &f, 1.0, 0.1, run);
  std::ostringstream out;
  write_json(r, out);
  const auto j = nlohmann::json::parse(out.str());
  for (const char* k : {"vertices", "triangles", "min_angle_deg", "max_angle_deg", "max_radius_edge",
                        "max_R_over_f", "mean_R_over_f", "bad_triangles", "exempt_small_angle_triangles",
                        "conformity", "el_over_f_max", "min_angle_histogram", "timings_s", "peak_rss_mb",
                        "predicate_calls", "area", "bound_B", "alpha", "spacing", "guarantees", "measured",
                        "nn_over_f_min"})
    EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_EQ(j["vertices"], 9);
  EXPECT_EQ(j["triangles"], 8);
  EXPECT_EQ(j["bad_triangles"], 8);
  EXPECT_EQ(j["exempt_small_angle_triangles"], 2);
  EXPECT_NEAR(j["conformity"]["min"].get<double>(), 0.5, 1e-12);
  EXPECT_TRUE(j["conformity"].contains("mean"));
  EXPECT_TRUE(j["conformity"].contains("p05"));
  EXPECT_EQ(j["min_angle_histogram"]["bin_deg"], 5);
  ASSERT_EQ(j["min_angle_histogram"]["counts"].size(), 12u);
  EXPECT_EQ(j["min_angle_histogram"]["counts"][9], 8);
  EXPECT_EQ(j["timings_s"]["cdt"], 0.25);
  EXPECT_EQ(j["timings_s"]["refine"], 1.5);
  EXPECT_TRUE(j["timings_s"]["write"].is_null());
  EXPECT_EQ(j["timings_s"]["total"], 2.0);
  EXPECT_EQ(j["peak_rss_mb"], 12.5);
  EXPECT_EQ(j["predicate_calls"]["filtered"], 100);
  EXPECT_EQ(j["predicate_calls"]["exact"], 3);
  EXPECT_EQ(j["steiner_points"]["total"], 10);
  EXPECT_EQ(j["area"], 4.0);
  EXPECT_EQ(j["bound_B"], 1.0);
  EXPECT_EQ(j["alpha"], 0.1);
  EXPECT_EQ(j["spacing"], "constant");
  EXPECT_EQ(j["input_file"], "square.poly");
  for (const char* k : {"beta", "R_over_l_max", "min_angle_deg", "nn_over_f_min", "el_over_f_max", "valid"})
    EXPECT_TRUE(j["guarantees"].contains(k)) << k;
  // Applicable (alpha*B = 0.1), but not valid: f = 0.5 is too small for this grid (R/f(c) = 1.41 > B,
  // el/f = 2.83 above 2B/(1-alpha*B)).
  EXPECT_EQ(j["guarantees"]["applicable"], true);
  EXPECT_EQ(j["guarantees"]["valid"], false);
  EXPECT_EQ(j["guarantees"]["fdr_R_over_f_max"]["holds"], false);
  EXPECT_EQ(j["guarantees"]["theorem_4_3_R_over_l_max"]["holds"], true);
  EXPECT_NEAR(j["guarantees"]["R_over_l_max"].get<double>(), 1.7380151, 1e-7);
  for (const char* k : {"R_over_l_max", "min_angle_deg", "nn_over_f_min", "el_over_f_max"})
    EXPECT_TRUE(j["measured"].contains(k)) << k;
  EXPECT_NEAR(j["measured"]["R_over_l_max"].get<double>(), kSqrt2 / 2, 1e-12);
  EXPECT_NEAR(j["measured"]["nn_over_f_min"].get<double>(), 2.0, 1e-12);
}

TEST(Writers, JsonNullsWithoutSpacing) {
  const auto r = compute_quality(grid2x2(), nullptr, 2.0, 0.6, RunInfo{});
  std::ostringstream out;
  write_json(r, out);
  const auto j = nlohmann::json::parse(out.str());
  for (const char* k : {"max_R_over_f", "mean_R_over_f", "bad_triangles", "el_over_f_max", "peak_rss_mb"})
    EXPECT_TRUE(j[k].is_null()) << k;
  EXPECT_TRUE(j["conformity"]["min"].is_null());
  EXPECT_TRUE(j["measured"]["nn_over_f_min"].is_null());
  EXPECT_EQ(j["guarantees"]["valid"], false);  // alpha*B = 1.2
  EXPECT_TRUE(j["guarantees"]["beta"].is_null());
  EXPECT_EQ(j["spacing"], "none");
  EXPECT_NEAR(j["min_angle_deg"].get<double>(), 45.0, 1e-9);
}

TEST(Writers, TextSummary) {
  const ConstantField f(0.5);
  RunInfo run;
  run.input_file = "grid.node";
  const auto r = compute_quality(grid2x2(), &f, 2.0, 0.1, run);
  std::ostringstream out;
  write_text(r, out);
  const std::string s = out.str();
  EXPECT_NE(s.find("grid.node"), std::string::npos);
  EXPECT_NE(s.find("9 / 8"), std::string::npos);
  EXPECT_NE(s.find(" 45 -  50 deg:          8 ########################"), std::string::npos) << s;
  EXPECT_NE(s.find("Theory vs measured"), std::string::npos);
  EXPECT_NE(s.find("R/l max (Thm 4.3)"), std::string::npos);
  EXPECT_EQ(s.find("NO"), std::string::npos) << s;  // every guarantee holds on this mesh

  std::ostringstream bad;
  write_text(compute_quality(grid2x2(), &f, 20.0, 0.1, run), bad);
  EXPECT_NE(bad.str().find("no guarantee: alpha*B = 2 >= 1"), std::string::npos) << bad.str();
}

TEST(Rss, ParsesVmHwm) {
  const auto self = peak_rss_mb_value();
  ASSERT_TRUE(self.has_value());
  EXPECT_GT(*self, 0.1);
  EXPECT_NE(peak_rss_mb(), "n/a");
  const std::string path = ::testing::TempDir() + "/fdr_status_test";
  {
    std::ofstream o(path);
    o << "Name:\ttest\nVmPeak:\t  9999 kB\nVmHWM:\t    2048 kB\nVmRSS:\t 1000 kB\n";
  }
  EXPECT_DOUBLE_EQ(*peak_rss_mb_value(path), 2.0);
  EXPECT_FALSE(peak_rss_mb_value(path + ".missing").has_value());
  std::remove(path.c_str());
}


// The repairs are streamed into the JSON text (not held as one document): the file must still be
// exactly what the document would print, for no repair, one, and many with odd contents.
TEST(Quality, JsonRepairsStreamedAsTheDocumentWouldPrintThem) {
  for (int n : {0, 1, 5}) {
    QualityReport r = compute_quality(equilateral(), nullptr, 1.0, -1, RunInfo{});
    for (int i = 0; i < n; ++i) {
      QualityReport::Repair rp;
      rp.kind = i % 2 ? "snap" : "split \"crossing\"\n\u00e9";
      rp.x = i == 2 ? std::nan("") : 0.1 * i - 3e-7;
      rp.y = 1e21 * i;
      if (i % 2) rp.ids = {i, -i, 123456789012345};
      rp.reason = std::string("reason ") + std::to_string(i);
      r.repairs.push_back(rp);
    }
    std::ostringstream out;
    write_json(r, out);
    const auto j = nlohmann::ordered_json::parse(out.str());
    EXPECT_EQ(j.dump(2) + "\n", out.str()) << n << " repairs";
    ASSERT_EQ(j["repairs"].size(), static_cast<std::size_t>(n));
    if (n == 5) {
      EXPECT_EQ(j["repairs"][0]["kind"], "split \"crossing\"\n\u00e9");
      EXPECT_TRUE(j["repairs"][2]["x"].is_null());
      EXPECT_EQ(j["repairs"][3]["ids"][2], 123456789012345);
      EXPECT_TRUE(j["repairs"][4]["ids"].empty());
    }
  }
}

}  // namespace
}  // namespace fdr::quality
