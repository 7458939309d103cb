// fdr::triangulate and fdr::Triangulator: one-shot == step-wise, refining further, errors.
#include <gtest/gtest.h>
#include <cmath>
#include "api/core_stages.hpp"
#include "api/triangulate.hpp"

namespace {
const std::string kSquare = std::string(FDR_TESTDATA_DIR) + "/poly/square10.poly";

bool same(const fdr::MeshView& a, const fdr::MeshView& b) {
  if (a.vertices.size() != b.vertices.size() || a.triangles != b.triangles) return false;
  for (std::size_t i = 0; i < a.vertices.size(); ++i)
    if (a.vertices[i].x != b.vertices[i].x || a.vertices[i].y != b.vertices[i].y) return false;
  return true;
}

TEST(Api, OneShotEqualsStepWise) {
  const fdr::Pslg g = fdr::read_pslg(kSquare);
  const auto f = fdr::make_spacing("paper-f1");
  const fdr::Mesh a = fdr::triangulate(g, *f);
  fdr::Triangulator t(g);
  const fdr::MeshView cdt = t.view();
  EXPECT_LT(cdt.triangles.size(), a.view.triangles.size());
  const fdr::Mesh b = t.refine(f).mesh();
  EXPECT_TRUE(same(a.view, b.view));
  EXPECT_EQ(a.report.bad_triangles.value_or(1), 0u);
  EXPECT_GT(a.report.triangles, 100u);
  EXPECT_FALSE(a.f);  // the reference form keeps no pointer to the caller's f
  EXPECT_TRUE(b.f);
}

TEST(Api, RefineFurther) {
  const fdr::Pslg g = fdr::read_pslg(kSquare);
  fdr::TriangulateOptions o;
  o.check = true;  // the invariants hold after each refinement (Error(kCheckFailed) otherwise)
  fdr::Triangulator t(g, o);
  t.refine(fdr::make_spacing("1.0"));
  const std::size_t coarse = t.view().triangles.size();
  t.refine(fdr::make_spacing("0.4"));
  const fdr::Mesh m = t.mesh();
  EXPECT_GT(m.view.triangles.size(), 3 * coarse);
  EXPECT_EQ(m.report.bad_triangles.value_or(1), 0u);
}

TEST(Api, LargeCoordinatesAreShiftedLikeTheCli) {
  fdr::Pslg g = fdr::read_pslg(kSquare);
  for (auto& p : g.points) p = {p.x + 5e5, p.y + 4e6};
  const fdr::Mesh m = fdr::triangulate(g, fdr::make_spacing("2"));
  EXPECT_NE(m.view.origin.x, 0.0);
  EXPECT_EQ(m.report.bad_triangles.value_or(1), 0u);
}

TEST(Api, Errors) {
  const fdr::Pslg g = fdr::read_pslg(kSquare);
  fdr::TriangulateOptions o;
  o.bound = -1;
  try {
    fdr::triangulate(g, *fdr::make_spacing("1"), o);
    FAIL();
  } catch (const fdr::Error& e) {
    EXPECT_EQ(e.exit_code(), 2);
  }
  o = {};
  o.max_steiner = 10;
  EXPECT_THROW(fdr::triangulate(g, *fdr::make_spacing("0.01"), o), fdr::Error);
  EXPECT_THROW(fdr::read_pslg(std::string(FDR_TESTDATA_DIR) + "/poly/does_not_exist.poly"), fdr::Error);
  EXPECT_THROW(fdr::make_spacing("x +* y"), fdr::Error);
}

TEST(Api, ReportJson) {
  const fdr::Mesh m = fdr::triangulate(fdr::read_pslg(kSquare), *fdr::make_spacing("2"));
  const std::string js = fdr::report_json(m.report);
  EXPECT_NE(js.find("\"triangles\""), std::string::npos);
}
}  // namespace

// The adjacency outlives the report when the boundary lists' writers will read it (one array
// read per half-edge instead of regrouping every half-edge: io/boundaries.cpp).
TEST(Api, MeasureMeshKeepsTheAdjacencyOnlyWhenAsked) {
  const fdr::Pslg g = fdr::read_pslg(kSquare);
  const auto f = fdr::make_spacing("1");
  fdr::Triangulator t(g);
  t.refine(f);
  for (const bool keep : {true, false}) {
    fdr::MeshView m = t.view();
    ASSERT_EQ(m.neighbours.size(), 3 * m.triangles.size());
    const fdr::QualityReport r = fdr::measure_mesh(m, f.get(), fdr::TriangulateOptions{}, fdr::RunFigures{}, nullptr, keep);
    EXPECT_EQ(r.triangles, m.triangles.size());
    EXPECT_EQ(m.neighbours.size(), keep ? 3 * m.triangles.size() : 0u) << "keep " << keep;
  }
}
