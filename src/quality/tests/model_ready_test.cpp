// Model-readiness metrics (issue 11) on hand-made meshes with known answers, and the theory
// table's per-theorem {bound, measured, holds} in the JSON report.
#include <gtest/gtest.h>

#include "quality/tests/grid_cells.hpp"

#include <cmath>
#include <numbers>
#include <random>
#include <sstream>
#include <nlohmann/json.hpp>

#include "base/tests/scoped_env.hpp"
#include "quality/mesh_adjacency.hpp"
#include "quality/model_ready.hpp"
#include "quality/report.hpp"

namespace fdr::quality {
namespace {

const double kPi = std::numbers::pi;
const double kSqrt3 = std::sqrt(3.0);

// (n+1)^2 vertices on [0,n]^2 scaled by `h`, each square cut along its (i,j)-(i+1,j+1) diagonal.
mesh::MeshView grid(int n, double h = 1.0, Point2 shift = {0, 0}) {
  mesh::MeshView m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.vertices.push_back({shift.x + h * i, shift.y + h * j});
  auto id = [n](int i, int j) { return Index(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

// Appends `b` to `a` (disjoint union of the vertex and triangle arrays).
void append(mesh::MeshView& a, const mesh::MeshView& b) {
  const Index off = static_cast<Index>(a.vertices.size());
  a.vertices.insert(a.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (auto t : b.triangles) a.triangles.push_back({t[0] + off, t[1] + off, t[2] + off});
}

// Isosceles triangle with apex angle `deg` at `apex` and legs of length `leg` (CCW).
mesh::MeshView isosceles(double deg, Point2 apex = {0, 0}, double leg = 1.0) {
  mesh::MeshView m;
  const double a = deg * kPi / 180.0;
  m.vertices = {apex, apex + Point2{leg, 0}, apex + Point2{leg * std::cos(a), leg * std::sin(a)}};
  m.triangles = {{0, 1, 2}};
  return m;
}

std::vector<std::pair<Point2, Point2>> ring(std::vector<Point2> p) {
  std::vector<std::pair<Point2, Point2>> s;
  for (std::size_t i = 0; i < p.size(); ++i) s.push_back({p[i], p[(i + 1) % p.size()]});
  return s;
}

std::vector<std::pair<Point2, Point2>> square(double lo, double hi) {
  return ring({{lo, lo}, {hi, lo}, {hi, hi}, {lo, hi}});
}

TEST(ModelReady, GridEdgesAnglesQuality) {
  ModelReadyInputs in;
  in.hmin = 2.5;
  const auto r = compute_model_readiness(grid(2), in);
  EXPECT_EQ(r.triangles, 8u);
  EXPECT_EQ(r.edges, 16u);  // 6 horizontal, 6 vertical, 4 diagonals
  ASSERT_TRUE(r.shortest_edge_m);
  EXPECT_DOUBLE_EQ(*r.shortest_edge_m, 1.0);
  EXPECT_DOUBLE_EQ(*r.shortest_edge_over_hmin(), 0.4);
  EXPECT_EQ(r.edges_below_half_hmin, 12u);  // the unit edges (< 1.25), not the diagonals (1.414)
  EXPECT_EQ(r.edges_below_tenth_hmin, 0u);
  EXPECT_DOUBLE_EQ(*r.pct_edges_below_half_hmin(), 75.0);
  EXPECT_EQ(r.triangles_below_20_deg, 0u);
  EXPECT_EQ(r.triangles_below_30_deg, 0u);
  // Right isosceles: 4*sqrt(3) * 0.5 / (1 + 1 + 2) = sqrt(3)/2.
  EXPECT_NEAR(*r.mean_quality, kSqrt3 / 2, 1e-12);
  EXPECT_EQ(r.mesh_pieces, 1u);
  EXPECT_EQ(r.mesh_boundary_edges, 8u);
  EXPECT_DOUBLE_EQ(r.mesh_area_m2, 4.0);
  EXPECT_FALSE(r.time_step);       // no z
  EXPECT_FALSE(r.input_to_mesh);   // no input boundary
}

TEST(ModelReady, EquilateralQualityIsOne) {
  mesh::MeshView m;
  m.vertices = {{0, 0}, {2, 0}, {1, kSqrt3}};
  m.triangles = {{0, 1, 2}};
  const auto r = compute_model_readiness(m, {});
  EXPECT_NEAR(*r.mean_quality, 1.0, 1e-12);
  EXPECT_NEAR(*r.shortest_edge_m, 2.0, 1e-12);
  EXPECT_FALSE(r.hmin_m);
  EXPECT_FALSE(r.pct_edges_below_half_hmin());  // unknown without hmin
}

TEST(ModelReady, SkinnyTrianglesCountedByMinimumAngle) {
  // Apex angles 10 (< 20 and < 30), 25 (< 30 only), 40 (neither); disjoint: three pieces.
  mesh::MeshView m = isosceles(10);
  append(m, isosceles(25, {5, 0}));
  append(m, isosceles(40, {10, 0}));
  const auto r = compute_model_readiness(m, {});
  EXPECT_EQ(r.triangles_below_20_deg, 1u);
  EXPECT_EQ(r.triangles_below_30_deg, 2u);
  EXPECT_NEAR(r.pct_triangles_below_30(), 200.0 / 3, 1e-12);
  EXPECT_EQ(r.mesh_pieces, 3u);
  // Shortest edge: the 10-degree triangle's base 2 sin(5 deg).
  EXPECT_NEAR(*r.shortest_edge_m, 2 * std::sin(5 * kPi / 180), 1e-12);
  // Mean quality from the closed form for an isosceles triangle with legs 1 and apex angle a:
  // area sin(a)/2, edges^2 = 2 + (2 - 2 cos a).
  double q = 0;
  for (double a : {10.0, 25.0, 40.0}) {
    const double t = a * kPi / 180;
    q += 4 * kSqrt3 * 0.5 * std::sin(t) / (4 - 2 * std::cos(t));
  }
  EXPECT_NEAR(*r.mean_quality, q / 3, 1e-12);
}

TEST(ModelReady, PiecesJoinThroughEdgesOnly) {
  mesh::MeshView two = grid(1);          // [0,1]^2
  append(two, grid(1, 1.0, {3, 0}));     // [3,4]x[0,1]
  EXPECT_EQ(compute_model_readiness(two, {}).mesh_pieces, 2u);
  // Two squares sharing the corner (1,1) only: still two pieces (no shared edge).
  mesh::MeshView pinch = grid(1);
  pinch.vertices.push_back({2, 1});
  pinch.vertices.push_back({2, 2});
  pinch.vertices.push_back({1, 2});
  pinch.triangles.push_back({3, 4, 5});
  pinch.triangles.push_back({3, 5, 6});
  const auto r = compute_model_readiness(pinch, {});
  EXPECT_EQ(r.mesh_pieces, 2u);
  EXPECT_EQ(r.mesh_boundary_edges, 8u);
}

TEST(ModelReady, CoastDeviationAgainstOffsetBoundary) {
  // Mesh [0,10]^2; the input coast is the square [-0.5, 10.5]^2 (0.5 outside everywhere).
  const auto input = square(-0.5, 10.5);
  ModelReadyInputs in;
  in.hmin = 2;  // samples every 1 m
  in.input_boundary = &input;
  mesh::MeshView m = grid(5, 2.0);
  m.origin = {1000, 2000};
  const auto r = compute_model_readiness(m, in);
  ASSERT_TRUE(r.input_to_mesh && r.mesh_to_input);
  // Input -> mesh: 0.5 from the sides, 0.5*sqrt(2) from the corners.
  EXPECT_NEAR(r.input_to_mesh->max_m, 0.5 * std::sqrt(2.0), 1e-12);
  EXPECT_EQ(r.input_to_mesh->samples, 44u);  // 4 sides of 11 m: a corner and 10 points each
  // The largest distance is at an input corner (world coordinates).
  const Point2 c = r.input_to_mesh->max_at;
  EXPECT_NEAR(std::fabs(c.x - 1005) , 5.5, 1e-12);
  EXPECT_NEAR(std::fabs(c.y - 2005), 5.5, 1e-12);
  // Mesh -> input: every mesh boundary point is 0.5 from the input square.
  EXPECT_NEAR(r.mesh_to_input->max_m, 0.5, 1e-12);
  EXPECT_NEAR(r.mesh_to_input->p99_m, 0.5, 1e-12);
  EXPECT_EQ(r.mesh_to_input->samples, 40u);  // 20 boundary edges of 2 m, a vertex and a midpoint each

  // An island of the input that the mesh does not have (removed): 4 m from the nearest mesh
  // boundary ([4,6]^2 inside [0,10]^2: its corners are 4 from the sides, its side midpoints 4).
  auto with_island = input;
  for (const auto& s : square(4, 6)) with_island.push_back(s);
  in.input_boundary = &with_island;
  const auto r2 = compute_model_readiness(m, in);
  EXPECT_NEAR(r2.input_to_mesh->max_m, 4.0, 1e-12);
  EXPECT_NEAR(r2.mesh_to_input->max_m, 0.5, 1e-12);  // the mesh boundary is still near the coast
}

TEST(ModelReady, P99IsTheNearestRank) {
  // 200 samples on a line at distances 0..199 / 100 from the segment y = 0: p99 = 1.98.
  std::vector<std::pair<Point2, Point2>> segs = {{{0, 0}, {1000, 0}}};
  std::vector<Point2> pts;
  for (int i = 0; i < 200; ++i) pts.push_back({double(i), i / 100.0});
  const auto d = distances_to_segments(pts, segs);
  for (int i = 0; i < 200; ++i) EXPECT_DOUBLE_EQ(d[i], i / 100.0);
}

TEST(ModelReady, GridDistanceMatchesBruteForce) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1000), step(-20, 20);
  std::vector<std::pair<Point2, Point2>> segs;
  for (int i = 0; i < 2000; ++i) {
    const Point2 a{u(rng), u(rng) * 0.3};  // a thin band: many empty cells
    segs.push_back({a, a + Point2{step(rng), step(rng)}});
  }
  segs.push_back({{0, 0}, {1000, 900}});  // one long diagonal over many cells
  std::vector<Point2> pts;
  for (int i = 0; i < 3000; ++i) pts.push_back({u(rng) * 1.4 - 200, u(rng) * 1.4 - 200});  // also outside
  const auto d = distances_to_segments(pts, segs);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& [a, b] : segs) best = std::min(best, dist_to_segment(pts[i], a, b));
    ASSERT_NEAR(d[i], best, 1e-9 * (1 + best)) << i;
  }
  EXPECT_TRUE(std::isinf(distances_to_segments({{0, 0}}, {})[0]));
}

// Issue 7: the grid's cells are about one segment long and a query stops once the nearest cell
// not scanned is farther than the best distance: the same value, bit for bit, as the minimum of
// the same per-segment formula over every segment (random closed polylines of very different
// segment lengths, points on them, near them, far away and outside the grid).
TEST(ModelReady, GridDistanceEqualsBruteForceBitForBit) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<std::pair<Point2, Point2>> segs;
  for (int r = 0; r < 60; ++r) {
    const Point2 c{u(rng) * 5000, u(rng) * 3000};
    const double rad = 20 + 400 * u(rng);
    const int k = 3 + static_cast<int>(60 * u(rng));
    std::vector<Point2> p;
    for (int i = 0; i < k; ++i) {
      const double a = 6.283185307179586 * i / k, rr = rad * (0.6 + 0.4 * u(rng));
      p.push_back(c + Point2{rr * std::cos(a), rr * std::sin(a)});
    }
    for (const auto& s : ring(p)) segs.push_back(s);
  }
  std::vector<Point2> pts;
  for (const auto& [a, b] : segs) {
    pts.push_back(a);
    pts.push_back(a + u(rng) * (b - a));
    pts.push_back(a + u(rng) * (b - a) + Point2{u(rng) - 0.5, u(rng) - 0.5});
    pts.push_back(a + Point2{(u(rng) - 0.5) * 100, (u(rng) - 0.5) * 100});
  }
  for (int i = 0; i < 500; ++i) pts.push_back({u(rng) * 8000 - 1500, u(rng) * 6000 - 1500});
  const auto d = distances_to_segments(pts, segs);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    double best2 = std::numeric_limits<double>::infinity();
    for (const auto& [a, b] : segs) {  // the grid's per-segment formula
      const Point2 e = b - a;
      const double l2 = norm2(e);
      const double t = l2 > 0 ? std::clamp(dot(pts[i] - a, e) / l2, 0.0, 1.0) : 0.0;
      best2 = std::min(best2, norm2(pts[i] - (a + t * e)));
    }
    ASSERT_EQ(d[i], std::sqrt(best2)) << i;
  }
}

TEST(ModelReady, TimeStepFromShortestAltitudeAndClampedDepth) {
  // Two equilateral triangles of side 10: one 4 m deep, one on land (z = +3, clamped to 1 m).
  mesh::MeshView m;
  m.vertices = {{0, 0}, {10, 0}, {5, 5 * kSqrt3}, {20, 0}, {30, 0}, {25, 5 * kSqrt3}};
  m.triangles = {{0, 1, 2}, {3, 4, 5}};
  m.origin = {500000, 4000000};
  const double h = 5 * kSqrt3;  // altitude
  ModelReadyInputs in;
  in.min_depth_m = 1;
  m.z = {-4, -4, -4, -100, -100, -100};
  auto r = compute_model_readiness(m, in);
  ASSERT_TRUE(r.time_step);
  EXPECT_NEAR(r.time_step->dt_s, h / std::sqrt(9.81 * 100), 1e-12);  // the deeper one is faster
  EXPECT_EQ(r.time_step->triangle, 1u);
  EXPECT_NEAR(r.time_step->depth_m, 100, 1e-12);
  EXPECT_NEAR(r.time_step->h_m, h, 1e-12);
  EXPECT_NEAR(r.time_step->at.x, 500025, 1e-9);
  EXPECT_NEAR(r.time_step->at.y, 4000000 + h / 3, 1e-9);

  m.z = {-4, -4, -4, 3, 3, 3};
  r = compute_model_readiness(m, in);
  EXPECT_NEAR(r.time_step->dt_s, h / std::sqrt(9.81 * 4), 1e-12);  // land: clamped to 1 m, slower
  EXPECT_EQ(r.time_step->triangle, 0u);
  m.z = {-0.2, -0.2, -0.2, 3, 3, 3};  // both shallower than the clamp: depth 1 m
  r = compute_model_readiness(m, in);
  EXPECT_NEAR(r.time_step->dt_s, h / std::sqrt(9.81 * 1), 1e-12);
  EXPECT_EQ(r.time_step->depth_m, 1.0);
  in.min_depth_m = 5;  // a larger clamp: both at 5 m
  r = compute_model_readiness(m, in);
  EXPECT_NEAR(r.time_step->dt_s, h / std::sqrt(9.81 * 5), 1e-12);
  EXPECT_EQ(r.time_step->triangle, 0u);  // ties: the first triangle
}

// The time step is an ocean model's limit: on a mesh with z but no vertex below sea level (a DEM
// of land) every depth would be the --min-depth clamp, so it is left out and said so; where the
// limiting triangle's depth is the clamp, the report says that too. Both paths agree.
TEST(ModelReady, TimeStepLeftOutOnLandAndClampLabelled) {
  mesh::MeshView m = grid(3, 10.0);
  m.z.assign(m.vertices.size(), 250.0);
  m.z[0] = 0.0;  // at sea level is not below it
  ModelReadyInputs in;
  in.hmin = 10;
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 1) m.neighbours = half_edge_neighbours(m);
    const ModelReadiness r = compute_model_readiness(m, in);
    EXPECT_FALSE(r.time_step) << pass;
    EXPECT_TRUE(r.land_only) << pass;
    const auto j = model_ready_json(r);
    EXPECT_TRUE(j["time_step"].is_null());
    EXPECT_NE(j["time_step_omitted"].get<std::string>().find("land-only"), std::string::npos);
    std::ostringstream txt;
    write_model_ready_text(r, txt);
    EXPECT_NE(txt.str().find("time step h/sqrt(g depth)     : n/a: no vertex below sea level"), std::string::npos)
        << txt.str();
  }
  m.neighbours.clear();
  // One vertex 0.3 m below sea level: a wet mesh, its limiting triangle clamped to 1 m.
  m.z[5] = -0.3;
  ModelReadiness r = compute_model_readiness(m, in);
  ASSERT_TRUE(r.time_step);
  EXPECT_FALSE(r.land_only);
  EXPECT_TRUE(r.time_step_depth_clamped());
  EXPECT_TRUE(model_ready_json(r)["time_step"]["depth_clamped"].get<bool>());
  EXPECT_FALSE(model_ready_json(r).contains("time_step_omitted"));
  std::ostringstream txt;
  write_model_ready_text(r, txt);
  EXPECT_NE(txt.str().find("depth 1 m (the --min-depth clamp)"), std::string::npos) << txt.str();
  // Deep water everywhere: not clamped.
  m.z.assign(m.vertices.size(), -40.0);
  r = compute_model_readiness(m, in);
  ASSERT_TRUE(r.time_step);
  EXPECT_FALSE(r.time_step_depth_clamped());
  EXPECT_FALSE(model_ready_json(r)["time_step"]["depth_clamped"].get<bool>());
}

// The coast deviation says what it measured against: the input domain's boundary, and when the
// GIS stage united adjacent or overlapping input polygons, how many into how many.
TEST(ModelReady, DeviationSaysWhatItMeasuresAgainst) {
  const auto input = square(0, 3);
  mesh::MeshView m = grid(3);
  ModelReadyInputs in;
  in.hmin = 1;
  in.input_boundary = &input;
  auto j = model_ready_json(compute_model_readiness(m, in));
  EXPECT_EQ(j["coast_deviation"]["measured_against"], "boundary of the input domain");
  const std::vector<std::pair<std::string, double>> figs = {{"input_polygons", 12}, {"input_polygons_united", 1}};
  in.coast_figures = &figs;
  const ModelReadiness r = compute_model_readiness(m, in);
  j = model_ready_json(r);
  EXPECT_EQ(j["coast_deviation"]["measured_against"],
            "boundary of the united input domain (12 polygons united into 1)");
  std::ostringstream txt;
  write_model_ready_text(r, txt);
  EXPECT_NE(txt.str().find("coast measured against        : boundary of the united input domain (12 polygons "
                           "united into 1)"),
            std::string::npos)
      << txt.str();
  // Without an input boundary nothing is measured and nothing is said.
  EXPECT_TRUE(model_ready_json(compute_model_readiness(m, {}))["coast_deviation"]["measured_against"].is_null());
}

TEST(ModelReady, FiguresAreaChangeAndJson) {
  const std::vector<std::pair<std::string, double>> figs = {
      {"input_pieces", 3}, {"input_area_m2", 4.04}, {"narrow_water_closed", 2}, {"water_removed_m2", 0.03},
      {"islands_removed", 5}, {"islands_removed_m2", 0.01}};
  const auto input = square(0, 2);
  ModelReadyInputs in;
  in.hmin = 1;
  in.coast_figures = &figs;
  in.input_boundary = &input;
  mesh::MeshView m = grid(2);
  m.z.assign(m.vertices.size(), -9.81);
  QualityReport q = compute_quality(m, nullptr, 1.0, -1, RunInfo{});
  q.model_ready = compute_model_readiness(m, in);
  EXPECT_NEAR(*q.model_ready->area_change_pct(), 100 * (4 - 4.04) / 4.04, 1e-12);
  EXPECT_EQ(*q.model_ready->input_pieces, 3);
  std::ostringstream js;
  write_json(q, js);
  const auto j = nlohmann::json::parse(js.str());
  ASSERT_TRUE(j.contains("model_ready"));
  const auto& mr = j["model_ready"];
  for (const char* k : {"hmin_m", "edges", "shortest_edge_m", "shortest_edge_over_hmin", "edges_below_half_hmin_pct",
                        "edges_below_tenth_hmin_pct", "triangles_below_20_deg_pct", "triangles_below_30_deg_pct",
                        "mean_quality", "pieces", "coast_deviation", "time_step", "area", "features_removed",
                        "coast_figures"})
    EXPECT_TRUE(mr.contains(k)) << k;
  EXPECT_EQ(mr["pieces"]["mesh"], 1);
  EXPECT_EQ(mr["pieces"]["input"], 3.0);
  EXPECT_EQ(mr["features_removed"]["islands"], 5.0);
  EXPECT_EQ(mr["features_removed"]["water_closed_m2"], 0.03);
  EXPECT_EQ(mr["coast_deviation"]["input_to_mesh"]["max_m"], 0.0);
  EXPECT_EQ(mr["coast_deviation"]["mesh_to_input"]["p99_over_hmin"], 0.0);
  // h = 1/sqrt(2) (right isosceles, legs 1), depth 9.81: dt = h / 9.81.
  EXPECT_NEAR(mr["time_step"]["dt_s"].get<double>(), std::sqrt(0.5) / 9.81, 1e-12);
  EXPECT_EQ(mr["time_step"]["h"], "shortest altitude");
  EXPECT_EQ(mr["coast_figures"]["islands_removed"], 5.0);

  std::ostringstream txt;
  write_text(q, txt);
  const std::string s = txt.str();
  EXPECT_NE(s.find("Model readiness (hmin = 1 m)"), std::string::npos) << s;
  EXPECT_NE(s.find("pieces mesh / input           : 1 / 3"), std::string::npos) << s;
  EXPECT_NE(s.find("islands removed               : 5"), std::string::npos) << s;
}

// Issue 7: with the mesher's adjacency the figures come from one pass over the triangles on up to
// two threads; they must equal the plain path's (half-edges grouped and sorted) bit for bit, for
// every FDR_THREADS. A jittered grid (random diagonals) with holes cut out (several pieces, inner
// boundaries), repeated edge lengths (ties for the shortest edge), depths, and a random input coast.
TEST(ModelReady, AdjacencyPathEqualsPlainForEveryThreadCount) {
  for (unsigned seed : {1u, 2u, 3u}) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> jitter(-0.2, 0.2), depth(-40, 5), u(-5, 175);
    std::bernoulli_distribution coin(0.5), keep(0.97);
    const int n = 170;
    mesh::MeshView m;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const bool inner = i > 0 && j > 0 && i < n - 1 && j < n - 1 && (i + j) % 7 != 0;  // some exact grid points
        m.vertices.push_back({i + (inner ? jitter(rng) : 0.0), j + (inner ? jitter(rng) : 0.0)});
        m.z.push_back(depth(rng));
      }
    for (int j = 0; j + 1 < n; ++j)
      for (int i = 0; i + 1 < n; ++i) {
        if (!keep(rng) || (i / 20 == 3 && j / 30 == 2) || j == 100) continue;  // holes, a cut across
        test::push_cell(m, n, i, j, coin(rng));
      }
    std::shuffle(m.triangles.begin(), m.triangles.end(), rng);  // ties met in any order
    m.origin = {350000, 4100000};
    std::vector<std::pair<Point2, Point2>> coast;
    for (int r = 0; r < 40; ++r) {  // random closed polylines
      std::vector<Point2> p;
      const Point2 c{u(rng), u(rng)};
      for (int k = 0; k < 12; ++k) p.push_back(c + Point2{8 * jitter(rng) * 5, 8 * jitter(rng) * 5});
      for (const auto& s : ring(p)) coast.push_back(s);
    }
    for (const auto& s : square(-0.3, n - 0.7)) coast.push_back(s);
    const std::vector<std::pair<std::string, double>> figs = {{"input_pieces", 2}, {"input_area_m2", 28000}};
    ModelReadyInputs in;
    in.hmin = 1.5;
    in.min_depth_m = 2;
    in.input_boundary = &coast;
    in.coast_figures = &figs;
    const std::string plain = model_ready_json(compute_model_readiness_plain(m, in)).dump();
    EXPECT_EQ(plain, model_ready_json(compute_model_readiness(m, in)).dump());  // no adjacency: the plain path
    m.neighbours = half_edge_neighbours(m);
    ASSERT_GE(m.triangles.size(), 4u * 8192u);  // several chunks for each thread
    for (int t : {1, 2, 3}) {
      const ThreadsEnv env(t);
      const ModelReadiness r = compute_model_readiness(m, in);
      EXPECT_EQ(plain, model_ready_json(r).dump()) << "seed " << seed << ", FDR_THREADS=" << t;
      EXPECT_GT(r.mesh_pieces, 1u);
      EXPECT_GT(r.mesh_boundary_edges, 4u * (n - 1));
    }
  }
}

class Constant : public sizing::SizingField {
 public:
  explicit Constant(double v) : v_(v) {}
  double operator()(Point2) const override { return v_; }
  double lipschitz() const override { return 0.0; }
  std::string describe() const override { return "constant"; }

 private:
  double v_;
};

// The theory table in JSON: per bound {bound, measured, holds}; valid only when all counted hold.
TEST(Guarantees, PerTheoremHoldsAndValid) {
  const Constant f(0.75);
  // Grid of unit squares with f = 0.75, B = 1: R/f(c) = 0.943 <= 1, R/l = 0.707, min angle 45,
  // nn/f = 1.33, el/f = 1.886 (above 4.5 as printed, 2B/(1+0) = 2 ... holds).
  auto check = [](const nlohmann::json& g) {
    bool all = g["applicable"].get<bool>();
    for (auto it = g.begin(); it != g.end(); ++it) {
      if (!it.value().is_object()) continue;
      const auto& c = it.value();
      ASSERT_TRUE(c.contains("bound") && c.contains("measured") && c.contains("holds")) << it.key();
      const double b = c["bound"].get<double>(), m = c["measured"].get<double>();
      const bool holds = c["relation"] == "<=" ? m <= b : m >= b;
      EXPECT_EQ(c["holds"].get<bool>(), holds) << it.key();
      if (c["counts_for_valid"].get<bool>()) all = all && holds;
    }
    EXPECT_EQ(g["valid"].get<bool>(), all);
  };
  {
    const auto r = compute_quality(grid(2), &f, 1.0, 0.0, RunInfo{});
    std::ostringstream js;
    write_json(r, js);
    const auto g = nlohmann::json::parse(js.str())["guarantees"];
    for (const char* k : {"fdr_R_over_f_max", "theorem_4_3_R_over_l_max", "theorem_4_3_min_angle_deg",
                          "theorem_4_4_nn_over_f_min", "theorem_4_5_el_over_f_max",
                          "theorem_4_5_corrected_el_over_f_max"})
      EXPECT_TRUE(g.contains(k)) << k;
    EXPECT_TRUE(g["valid"].get<bool>());
    EXPECT_TRUE(g["applicable"].get<bool>());
    check(g);
  }
  {
    // A 10-degree sliver breaks the min angle and R/l bounds: applicable but not valid.
    const auto r = compute_quality(isosceles(10, {0, 0}, 0.3), &f, 1.0, 0.0, RunInfo{});
    EXPECT_FALSE(guarantees_hold(r));
    std::ostringstream js;
    write_json(r, js);
    const auto g = nlohmann::json::parse(js.str())["guarantees"];
    EXPECT_TRUE(g["applicable"].get<bool>());
    EXPECT_FALSE(g["valid"].get<bool>());
    EXPECT_FALSE(g["theorem_4_3_min_angle_deg"]["holds"].get<bool>());
    EXPECT_NEAR(g["theorem_4_3_min_angle_deg"]["measured"].get<double>(), 10.0, 1e-9);
    check(g);
    std::ostringstream txt;
    write_text(r, txt);
    EXPECT_NE(txt.str().find("all bounds hold: NO"), std::string::npos) << txt.str();
  }
}

}  // namespace
}  // namespace fdr::quality
