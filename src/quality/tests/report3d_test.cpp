// The 3D report (measure_tets, compute_guarantees3) and the --check steps (check3d) on small
// meshes whose answers are known: the unit cube in six Kuhn tetrahedra, a regular tetrahedron,
// and broken copies of them.
#include <gtest/gtest.h>
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include "base/error.hpp"
#include "predicates/predicates3d.hpp"
#include "quality/check3d.hpp"
#include "quality/report3d.hpp"

namespace fdr::quality {
namespace {

class Const3 final : public sizing::SizingField3 {
 public:
  explicit Const3(double h) : h_(h) {}
  double operator()(Point3) const override { return h_; }
  double lipschitz() const override { return 0; }
  std::string describe() const override { return "constant"; }

 private:
  double h_;
};

const std::vector<Point3> kCube = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};

// The marker of the cube side a boundary triangle lies on (testdata/3d/cube.poly's markers).
std::int32_t side_marker(Point3 a, Point3 b, Point3 c) {
  auto all = [&](auto get, double v) { return get(a) == v && get(b) == v && get(c) == v; };
  auto X = [](Point3 p) { return p.x; };
  auto Y = [](Point3 p) { return p.y; };
  auto Z = [](Point3 p) { return p.z; };
  if (all(Z, 0)) return 1;
  if (all(Z, 1)) return 2;
  if (all(Y, 0)) return 3;
  if (all(X, 1)) return 4;
  if (all(Y, 1)) return 5;
  return 6;
}

// The cube in six tetrahedra around the diagonal (0,0,0)-(1,1,1), positively oriented, with its
// twelve boundary triangles as subfacets.
tet::TetMesh kuhn_cube() {
  tet::TetMesh m;
  m.points = kCube;
  m.tets = {{0, 1, 2, 6}, {0, 1, 5, 6}, {0, 3, 2, 6}, {0, 3, 7, 6}, {0, 4, 5, 6}, {0, 4, 7, 6}};
  for (auto& t : m.tets)
    if (predicates::orient3d(m.points[t[0]], m.points[t[1]], m.points[t[2]], m.points[t[3]]) < 0) std::swap(t[2], t[3]);
  m.tet_material.assign(m.tets.size(), 0);
  std::map<std::array<VertexId, 3>, int> count;
  for (const auto& t : m.tets)
    for (int k = 0; k < 4; ++k) {
      std::array<VertexId, 3> f{t[(k + 1) % 4], t[(k + 2) % 4], t[(k + 3) % 4]};
      std::sort(f.begin(), f.end());
      ++count[f];
    }
  for (const auto& [f, n] : count)
    if (n == 1) {
      m.faces.push_back(f);
      m.face_marker.push_back(side_marker(m.points[f[0]], m.points[f[1]], m.points[f[2]]));
    }
  return m;
}

plc::Plc cube_plc() {
  plc::Plc p;
  p.points = kCube;
  const std::vector<std::vector<VertexId>> sides = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                                     {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  for (std::size_t i = 0; i < sides.size(); ++i) p.facets.push_back({{sides[i]}, {}, static_cast<std::int32_t>(i + 1)});
  p.source = "cube";
  return p;
}

TEST(Report3, RegularTetrahedronDihedralAngles) {
  const Point3 a{1, 1, 1}, b{1, -1, -1}, c{-1, 1, -1}, d{-1, -1, 1};
  const auto [lo, hi] = dihedral_range_deg(a, b, c, d);
  const double expect = std::acos(1.0 / 3.0) * 180.0 / M_PI;
  EXPECT_NEAR(lo, expect, 1e-9);
  EXPECT_NEAR(hi, expect, 1e-9);
}

TEST(Report3, KuhnCubeFigures) {
  const tet::TetMesh m = kuhn_cube();
  tet::TetStats st;
  st.bound = 1.0;
  st.tet_splits = 3;
  TetValues v;
  const Report3 r = measure_tets(m, Const3(1.0), st, &v);
  EXPECT_EQ(r.vertices, 8u);
  EXPECT_EQ(r.tets, 6u);
  EXPECT_EQ(r.subfacets, 12u);
  ASSERT_EQ(r.materials.size(), 1u);
  EXPECT_NEAR(r.materials[0].volume, 1.0, 1e-15);
  EXPECT_NEAR(r.volume, 1.0, 1e-15);
  // Every Kuhn tetrahedron has the cube's circumsphere (R = sqrt(3)/2) and shortest edge 1.
  EXPECT_NEAR(r.max_R_over_f, std::sqrt(3.0) / 2, 1e-12);
  EXPECT_NEAR(r.max_radius_edge, std::sqrt(3.0) / 2, 1e-12);
  EXPECT_EQ(r.bad_tets, 0u);
  EXPECT_NEAR(r.min_dihedral_deg, 45.0, 1e-9);
  EXPECT_NEAR(r.max_dihedral_deg, 90.0, 1e-9);
  EXPECT_EQ(r.tets_under_10deg, 0u);
  EXPECT_NEAR(r.min_l_over_f, 1.0, 1e-15);
  EXPECT_NEAR(r.max_l_over_f, std::sqrt(3.0), 1e-12);
  EXPECT_EQ(v.r_over_f.size(), 6u);
  EXPECT_EQ(r.stats.tet_splits, 3u);
  std::size_t hist = 0;
  for (auto c : r.dihedral_hist) hist += c;
  EXPECT_EQ(hist, 6u);
  // alpha = 0, B = 1: beta = 1/4 and Theorem 4.3 gives radius-edge <= 2.
  ASSERT_TRUE(r.guarantees.valid);
  EXPECT_DOUBLE_EQ(r.guarantees.beta, 0.25);
  EXPECT_DOUBLE_EQ(r.guarantees.R_over_l_max, 2.0);
  for (const auto& t : r.theorems) EXPECT_TRUE(t.holds) << t.key;
  std::ostringstream text, json;
  write_text3(r, text);
  write_json3(r, json);
  EXPECT_NE(text.str().find("R/l max (Thm 4.3)"), std::string::npos);
  EXPECT_NE(json.str().find("\"theorem_4_4_nn_over_f_min\""), std::string::npos);
}

TEST(Report3, SliverRemovalBeforeAndAfter) {
  const tet::TetMesh m = kuhn_cube();
  tet::TetStats st;
  st.bound = 1.0;
  std::ostringstream off_text, off_json;
  const Report3 off = measure_tets(m, Const3(1.0), st);
  write_text3(off, off_text);
  write_json3(off, off_json);
  EXPECT_NE(off_text.str().find("sliver removal: off"), std::string::npos);
  EXPECT_NE(off_json.str().find("\"enabled\": false"), std::string::npos);
  st.sliver_angle_deg = 15;
  st.slivers_before = 7;
  st.slivers_left = 1;
  st.sliver_splits = 5;
  st.sliver_yields = 2;
  st.min_dihedral_before_deg = 1.5;
  st.dihedral_hist_before.assign(18, 0);
  st.dihedral_hist_before[0] = 3;
  st.dihedral_hist_before[4] = 3;
  st.slivers_listed.push_back({{0.5, 0.25, 0}, "sliver left with smallest dihedral angle 9 deg (centroid given)"});
  const Report3 r = measure_tets(m, Const3(1.0), st);
  std::ostringstream text, json;
  write_text3(r, text);
  write_json3(r, json);
  const std::string t = text.str(), j = json.str();
  EXPECT_NE(t.find("sliver removal (smallest dihedral under 15 deg): 7 before (min 1.50 deg), 1 left; 5 points inserted, "
                   "2 times split the boundary instead"),
            std::string::npos)
      << t;
  EXPECT_NE(t.find("before sliver removal: [0,10) 3 [40,50) 3"), std::string::npos) << t;
  EXPECT_NE(t.find("sliver at (0.5, 0.25, 0)"), std::string::npos) << t;
  for (const char* key : {"\"slivers\"", "\"angle_deg\": 15", "\"before\": 7", "\"left\": 1", "\"points_inserted\": 5",
                          "\"boundary_splits_instead\": 2", "\"min_per_tet_histogram_before\"", "\"listed\""})
    EXPECT_NE(j.find(key), std::string::npos) << key;
}

// Sliver removal's points sit nearer their neighbours than FDR's protection spheres allow: on a
// small cube the final mesh's nn/f falls below Theorem 4.4's bound. The theorem is judged on the
// mesh rule 3 left (the same mesh as a run without sliver removal, figure for figure) and the final
// figure is shown beside it, not judged.
TEST(Report3, TheoremsJudgedOnFdrVerticesBeforeSliverRemoval) {
  const plc::Plc cube = cube_plc();
  const Const3 f(0.1);
  const tet::TetResult with = tet::tetrahedralize(cube, f);
  tet::TetOptions no_slivers;
  no_slivers.remove_slivers = false;
  const tet::TetResult without = tet::tetrahedralize(cube, f, no_slivers);
  ASSERT_GT(with.stats.sliver_splits, 0u);
  ASSERT_TRUE(with.stats.fdr_vertex_figures);
  EXPECT_FALSE(without.stats.fdr_vertex_figures);
  const Report3 rule3 = measure_tets(without.mesh, f, without.stats);
  EXPECT_EQ(with.stats.fdr_nn_over_f_min, rule3.nn_over_f_min);
  EXPECT_EQ(with.stats.fdr_el_over_f_max, rule3.el_over_f_max);

  const Report3 r = measure_tets(with.mesh, f, with.stats);
  ASSERT_TRUE(r.guarantees.valid);
  EXPECT_EQ(r.guarantees.nn_over_f_min, 0.5);  // alpha = 0, B = 1: beta = 1/4
  EXPECT_LT(r.nn_over_f_min, with.stats.fdr_nn_over_f_min);  // the sliver points come nearer
  std::map<std::string, TheoremRow> rows;
  for (const auto& t : r.theorems) rows[t.key] = t;
  const TheoremRow& nn = rows.at("theorem_4_4_nn_over_f_min");
  EXPECT_EQ(nn.measured, with.stats.fdr_nn_over_f_min);
  EXPECT_TRUE(nn.applies && nn.holds && !nn.beyond_paper);
  EXPECT_EQ(rows.at("theorem_4_5_el_over_f_max").measured, with.stats.fdr_el_over_f_max);
  const TheoremRow& after = rows.at("after_slivers_nn_over_f_min");
  EXPECT_EQ(after.measured, r.nn_over_f_min);
  EXPECT_TRUE(after.beyond_paper);
  EXPECT_FALSE(after.applies);
  EXPECT_EQ(rows.at("after_slivers_el_over_f_max").measured, r.el_over_f_max);
  std::ostringstream text, json;
  write_text3(r, text);
  write_json3(r, json);
  EXPECT_NE(text.str().find("nn/f min (Thm 4.4, before sliver removal): bound >= 0.5"), std::string::npos) << text.str();
  EXPECT_NE(text.str().find("nn/f min after sliver removal: measured"), std::string::npos) << text.str();
  EXPECT_EQ(text.str().find("FAILS"), std::string::npos) << text.str();
  EXPECT_NE(json.str().find("\"beyond_paper\": true"), std::string::npos);

  // Without sliver removal the final mesh is rule 3's: the theorem's row measures it, nothing beside.
  const Report3 plain = measure_tets(without.mesh, f, without.stats);
  for (const auto& t : plain.theorems) EXPECT_FALSE(t.beyond_paper) << t.key;
  EXPECT_EQ(plain.theorems.size() + 2, r.theorems.size());
}

// f = 0.1 + 0.05 x: a spacing that varies, so every f evaluation counts.
class Linear3 final : public sizing::SizingField3 {
 public:
  double operator()(Point3 p) const override { return 0.1 + 0.05 * p.x; }
  double lipschitz() const override { return 0.05; }
  std::string describe() const override { return "linear"; }
};

// An n x n x n block of Kuhn cubes (six tetrahedra each), its corners jittered so that no two
// tetrahedra measure alike, and materials in runs of varying length.
tet::TetMesh kuhn_block(int n) {
  tet::TetMesh m;
  const int k = n + 1;
  auto id = [&](int i, int j, int l) { return static_cast<VertexId>((l * k + j) * k + i); };
  for (int l = 0; l < k; ++l)
    for (int j = 0; j < k; ++j)
      for (int i = 0; i < k; ++i) {
        const double h = 0.013 * std::sin(1.7 * i + 2.3 * j + 3.1 * l);
        m.points.push_back({i + h, j - h, l + 0.5 * h});
      }
  const tet::TetMesh unit = kuhn_cube();
  for (int l = 0; l < n; ++l)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (const auto& t : unit.tets) {
          std::array<VertexId, 4> q{};
          for (int c = 0; c < 4; ++c) {
            const Point3 u = unit.points[t[c]];
            q[c] = id(i + static_cast<int>(u.x), j + static_cast<int>(u.y), l + static_cast<int>(u.z));
          }
          m.tets.push_back(q);
          m.tet_material.push_back((i / 3 + l) % 4);
        }
  return m;
}

// The report on one thread and on two: the same figures bit for bit (their JSON and the
// per-tetrahedron values byte for byte), over many chunks of tetrahedra.
TEST(Report3, SameFiguresForOneAndTwoThreads) {
  const tet::TetMesh m = kuhn_block(16);  // 24576 tetrahedra
  tet::TetStats st;
  st.bound = 1.0;
  const Linear3 f;
  TetValues v1, v2;
  const Report3 r1 = measure_tets(m, f, st, &v1, 1);
  const Report3 r2 = measure_tets(m, f, st, &v2, 2);
  std::ostringstream j1, j2;
  write_json3(r1, j1);
  write_json3(r2, j2);
  EXPECT_EQ(j1.str(), j2.str());
  EXPECT_EQ(v1.r_over_f, v2.r_over_f);
  EXPECT_EQ(v1.radius_edge, v2.radius_edge);
  EXPECT_EQ(v1.min_dihedral_deg, v2.min_dihedral_deg);
  EXPECT_EQ(r1.volume, r2.volume);
  EXPECT_NEAR(r1.volume, 16.0 * 16 * 16, 1.0);  // the jittered surface moves a little
  ASSERT_EQ(r1.materials.size(), 4u);
  std::size_t tets = 0;
  for (const auto& mf : r1.materials) tets += mf.tets;
  EXPECT_EQ(tets, m.tets.size());
  // The per-vertex and per-edge figures against a plain count over the tetrahedra.
  double nn = 1e300, lf_min = 1e300, lf_max = 0;
  std::vector<double> lo(m.points.size(), 1e300);
  for (const auto& t : m.tets)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        if (a != b) {
          const Point3 p = m.points[t[a]], q = m.points[t[b]];
          lo[t[a]] = std::min(lo[t[a]], dist(p, q));
          lf_min = std::min(lf_min, dist(p, q) / f(0.5 * (p + q)));
          lf_max = std::max(lf_max, dist(p, q) / f(0.5 * (p + q)));
        }
  for (std::size_t i = 0; i < lo.size(); ++i) nn = std::min(nn, lo[i] / f(m.points[i]));
  EXPECT_EQ(r1.nn_over_f_min, nn);
  EXPECT_EQ(r1.min_l_over_f, lf_min);
  EXPECT_EQ(r1.max_l_over_f, lf_max);
}

TEST(Report3, GuaranteesNeedAlphaBBelowOne) {
  EXPECT_FALSE(compute_guarantees3(-1, 1).valid);
  EXPECT_FALSE(compute_guarantees3(0.5, 2).valid);
  EXPECT_FALSE(compute_guarantees3(0.1, 0).valid);
  const Guarantees3 g = compute_guarantees3(0.1, 1);
  ASSERT_TRUE(g.valid);
  EXPECT_NEAR(g.R_over_l_max, (2 + (1.5 + std::sqrt(2.0)) * 0.1) / 0.9, 1e-12);  // the paper's closed form
  EXPECT_NEAR(g.el_over_f_max, 2 / 1.1, 1e-15);
}

TEST(Check3, KuhnCubePassesEveryStep) {
  const tet::TetMesh m = kuhn_cube();
  EXPECT_FALSE(check_orientation(m));
  EXPECT_FALSE(check_faces_closed(m));
  EXPECT_FALSE(check_delaunay(m));
  EXPECT_FALSE(check_conforming(m, cube_plc()));
  EXPECT_FALSE(check_r_over_f(m, Const3(1.0), 1.0));
  EXPECT_NO_THROW(check_tets(m, cube_plc(), Const3(1.0), 1.0));
}

TEST(Check3, NegativeTetrahedron) {
  tet::TetMesh m = kuhn_cube();
  std::swap(m.tets[2][0], m.tets[2][1]);
  const auto e = check_orientation(m);
  ASSERT_TRUE(e);
  EXPECT_NE(e->find("tetrahedron 2"), std::string::npos);
}

TEST(Check3, FaceSharedByThree) {
  tet::TetMesh m = kuhn_cube();
  m.tets.push_back(m.tets[0]);
  EXPECT_TRUE(check_faces_closed(m));
}

TEST(Check3, NotDelaunay) {
  tet::TetMesh m;
  m.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.3, 0.3, 1}, {0.3, 0.3, -0.01}};
  m.tets = {{0, 1, 2, 3}, {0, 2, 1, 4}};
  ASSERT_FALSE(check_orientation(m));
  const auto e = check_delaunay(m);
  ASSERT_TRUE(e);
  EXPECT_NE(e->find("not Delaunay"), std::string::npos);
}

TEST(Check3, MissingSubfacetBreaksConformity) {
  tet::TetMesh m = kuhn_cube();
  m.faces.pop_back();
  m.face_marker.pop_back();
  const auto e = check_conforming(m, cube_plc());
  ASSERT_TRUE(e);
  EXPECT_NE(e->find("area"), std::string::npos);
}

TEST(Check3, SubfacetOffItsFacetsPlane) {
  tet::TetMesh m = kuhn_cube();
  std::swap(m.face_marker[0], m.face_marker.back());  // two subfacets of different sides trade markers
  EXPECT_TRUE(check_conforming(m, cube_plc()));
}

TEST(Check3, RatioAboveBound) {
  const tet::TetMesh m = kuhn_cube();
  const auto e = check_r_over_f(m, Const3(1.0), 0.8);
  ASSERT_TRUE(e);
  EXPECT_NE(e->find("R/f(c)"), std::string::npos);
  try {
    check_tets(m, cube_plc(), Const3(1.0), 0.8);
    FAIL();
  } catch (const Error& x) {
    EXPECT_EQ(x.exit_code(), static_cast<int>(ExitCode::kCheckFailed));
  }
}

}  // namespace
}  // namespace fdr::quality
