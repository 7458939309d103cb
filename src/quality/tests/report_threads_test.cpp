// Issue 7: the report splits its single pass over the triangles between two threads by triangle
// ranges (chunks claimed from both ends, per-vertex extremes shared, percentiles from the largest
// values of each part). Every figure must be the same, bit for bit, for every FDR_THREADS, and
// the percentiles, extremes and nearest neighbours the same as a plain computation over all values.
#include <gtest/gtest.h>

#include "quality/tests/grid_cells.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>
#include <sstream>
#include <string>

#include "quality/mesh_adjacency.hpp"
#include "quality/orthogonality.hpp"
#include "quality/report.hpp"

namespace fdr::quality {
namespace {

class WaveField : public sizing::SizingField {
 public:
  double operator()(Point2 p) const override { return 0.02 + 0.01 * std::sin(3 * p.x) * std::cos(2 * p.y); }
  std::string describe() const override { return "wave"; }
};

// A jittered n x n grid of the unit square (each cell cut along a random diagonal, so the mesh is
// not Delaunay; jitter below h/10 keeps every triangle counter-clockwise; about half the triangles
// obtuse), the boundary and one row of edges as constrained edges, and the adjacency when
// `adjacency` (as the mesher gives it).
mesh::MeshView jittered_grid(int n, unsigned seed, bool adjacency) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.09, 0.09);
  std::bernoulli_distribution coin(0.5);
  mesh::MeshView m;
  const double h = 1.0 / (n - 1);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const bool inner = i > 0 && j > 0 && i < n - 1 && j < n - 1;
      double x = i * h, y = j * h;
      if (inner) {
        x += jitter(rng) * h;
        y += jitter(rng) * h;
      }
      m.vertices.push_back({x, y});
    }
  auto id = [n](int i, int j) { return Index(j * n + i); };
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      test::push_cell(m, n, i, j, coin(rng));
    }
  for (int i = 0; i + 1 < n; ++i) {
    m.edges.push_back({id(i, 0), id(i + 1, 0), 1, 0});
    m.edges.push_back({id(i, n - 1), id(i + 1, n - 1), 1, 0});
    m.edges.push_back({id(0, i), id(0, i + 1), 1, 0});
    m.edges.push_back({id(n - 1, i), id(n - 1, i + 1), 1, 0});
    m.edges.push_back({id(i, n / 2), id(i + 1, n / 2), 2, 1});
  }
  if (adjacency) m.neighbours = half_edge_neighbours(m);
  return m;
}

struct Measured {
  std::string json;
  QualityReport r;
  TriangleValues tv;
};

Measured measure(const mesh::MeshView& m, const sizing::SizingField* f, const char* threads, bool per_triangle) {
  ::setenv("FDR_THREADS", threads, 1);
  Measured out;
  out.r = compute_quality(m, f, 1.0, -1, RunInfo{}, per_triangle ? &out.tv : nullptr);
  ::unsetenv("FDR_THREADS");
  std::ostringstream js;
  write_json(out.r, js);
  out.json = js.str();
  return out;
}

double nearest_rank(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  const std::size_t rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size())));
  return v[rank == 0 ? 0 : std::min(rank - 1, v.size() - 1)];
}

void check(const mesh::MeshView& m, const sizing::SizingField* f, bool per_triangle) {
  ASSERT_GE(m.triangles.size(), 12u * 4096u);  // several chunks (4096 triangles) for each thread
  const Measured one = measure(m, f, "1", per_triangle);
  for (const char* t : {"2", "3"}) {
    const Measured other = measure(m, f, t, per_triangle);
    EXPECT_EQ(one.json, other.json) << "FDR_THREADS=" << t;
    EXPECT_EQ(one.tv.area, other.tv.area);
    EXPECT_EQ(one.tv.min_angle_deg, other.tv.min_angle_deg);
    EXPECT_EQ(one.tv.r_over_f, other.tv.r_over_f);
  }
  // Against plain computations over every value.
  const OrthogonalityStats ref = compute_orthogonality(m);  // keeps its own sort-equivalent p99
  EXPECT_EQ(one.r.orthogonality.interior_edges, ref.interior_edges);
  EXPECT_EQ(one.r.orthogonality.orthogonality_max, ref.orthogonality_max);
  EXPECT_EQ(one.r.orthogonality.orthogonality_p99, ref.orthogonality_p99);
  EXPECT_EQ(one.r.orthogonality.smoothness_max, ref.smoothness_max);
  EXPECT_EQ(one.r.orthogonality.smoothness_p99, ref.smoothness_p99);
  const std::vector<double> nn = nearest_neighbour_distances(m.vertices);  // k-d tree
  EXPECT_EQ(*one.r.nn_min, *std::min_element(nn.begin(), nn.end()));
  if (f) {
    std::vector<double> conf;
    for (std::size_t i = 0; i < nn.size(); ++i) {
      const double fp = (*f)(m.vertices[i]);
      conf.push_back(std::min(nn[i] / fp, fp / nn[i]));
    }
    EXPECT_EQ(*one.r.conformity_p05, nearest_rank(conf, 0.05));
    EXPECT_EQ(*one.r.conformity_min, *std::min_element(conf.begin(), conf.end()));
    std::vector<double> el(m.vertices.size(), 0.0);  // longest edge of the triangles at each vertex
    for (const auto& t : m.triangles)
      for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 3; ++j) el[t[k]] = std::max(el[t[k]], dist(m.vertices[t[j]], m.vertices[t[(j + 1) % 3]]));
    double el_f = 0;
    for (std::size_t i = 0; i < el.size(); ++i) el_f = std::max(el_f, el[i] / (*f)(m.vertices[i]));
    EXPECT_EQ(*one.r.el_over_f_max, el_f);
  }
}

TEST(ReportThreads, SameFiguresForEveryThreadCountWithTheMesherAdjacency) {
  const WaveField f;
  for (unsigned seed : {1u, 2u}) check(jittered_grid(170, seed, true), &f, seed == 2);
}

// A thread-safe f is evaluated by the thread that measures the triangle (area and R/f(c) summed
// per chunk of triangles, the chunks added in order); the figures are those of the calling
// thread's evaluation bit for bit, for every thread count.
class SharedWaveField : public WaveField {
 public:
  bool thread_safe() const override { return true; }
};

TEST(ReportThreads, SameFiguresWhenBothThreadsEvaluateTheSpacing) {
  const SharedWaveField shared;
  const WaveField calling;
  const mesh::MeshView m = jittered_grid(170, 5, true);
  check(m, &shared, true);
  for (const char* t : {"1", "2", "3"}) {
    const Measured a = measure(m, &shared, t, true), b = measure(m, &calling, t, true);
    EXPECT_EQ(a.json, b.json) << "FDR_THREADS=" << t;
    EXPECT_EQ(a.tv.r_over_f, b.tv.r_over_f);
    EXPECT_EQ(*a.r.bad_triangles, *b.r.bad_triangles);
  }
}

TEST(ReportThreads, SameFiguresWithoutAdjacencyAndWithPerVertexSpacing) {
  mesh::MeshView m = jittered_grid(165, 3, false);
  for (const Point2 p : m.vertices) m.f.push_back(0.01 + 0.02 * p.x);
  check(m, nullptr, false);
}

TEST(ReportThreads, SameFiguresWithoutSpacing) { check(jittered_grid(160, 4, true), nullptr, true); }

// Triangles with a repeated corner make more than 3/2 interior edges per triangle: the p99s are
// then beyond what the pass keeps and are measured again (as a sort would give them).
TEST(ReportThreads, P99WithMoreEdgesThanTrianglesAllow) {
  mesh::MeshView m = jittered_grid(40, 5, false);
  const std::size_t grid = m.triangles.size();
  for (Index i = 0; i < 6000; ++i) m.triangles.push_back({i % 1500, i % 1500, i % 1500 + 1});
  m.edges.clear();
  const OrthogonalityStats ref = compute_orthogonality(m);
  // n - ceil(0.99 n) + 1 values from the p99 up: more than the 3/200 per triangle kept.
  ASSERT_GT(ref.interior_edges / 100, 3 * m.triangles.size() / 200 + 8) << grid;
  for (const char* t : {"1", "2"}) {
    const Measured run = measure(m, nullptr, t, false);
    EXPECT_EQ(run.r.orthogonality.interior_edges, ref.interior_edges);
    EXPECT_EQ(run.r.orthogonality.orthogonality_p99, ref.orthogonality_p99);
    EXPECT_EQ(run.r.orthogonality.smoothness_p99, ref.smoothness_p99);
    EXPECT_EQ(run.r.orthogonality.smoothness_max, ref.smoothness_max);
  }
}

}  // namespace
}  // namespace fdr::quality
