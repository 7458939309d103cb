// Mesh quality measurement (FDR paper: Definition 2.1, Theorems 4.3-4.5): compute_quality runs
// the steps in order: the triangle pass, the nearest-neighbour search, the vertex metrics.
#include "quality/report.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "base/error.hpp"
#include "base/large_array.hpp"
#include "base/parallel.hpp"
#include "base/step_laps.hpp"
#include "quality/extremes.hpp"
#include "quality/mesh_adjacency.hpp"
#include "quality/top_k.hpp"
#include "quality/triangle_pass.hpp"
#include "quality/vertex_metrics.hpp"

namespace fdr::quality {
namespace {

// The meshes from which the report's passes use more than one thread.
constexpr std::size_t kMinParallelTriangles = 16384;

// The report's figures that need no measurement.
QualityReport report_head(const mesh::MeshView& m, const sizing::SizingField* f, double bound_B, double alpha,
                          const RunInfo& run) {
  QualityReport r;
  r.vertices = m.num_vertices();
  r.triangles = m.num_triangles();
  r.bound_B = bound_B;
  // An unknown alpha (negative) falls back to the field's own Lipschitz constant, if it knows one.
  if (!(alpha >= 0) && f != nullptr && f->lipschitz() >= 0) alpha = f->lipschitz();
  r.alpha = alpha;
  r.spacing = f ? f->describe() : (!run.spacing.empty() ? run.spacing : std::string("none"));
  r.guarantees = compute_guarantees(alpha, bound_B, run.conforming_D);
  r.run = run;
  if (f) r.bad_triangles = 0;
  return r;
}

void check_vertex_ids(const mesh::MeshView& m) {
  const std::size_t nv = m.num_vertices(), nt = m.num_triangles();
  for (std::size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k)
      if (m.triangles[t][k] >= nv)
        throw Error(ExitCode::kInternal, "quality: triangle " + std::to_string(t) + " references vertex " +
                                             std::to_string(m.triangles[t][k]) + " but the mesh has " +
                                             std::to_string(nv) + " vertices");
}

// A new array of n copies of x with LargeArray's page policy, as the vector that leaves quality.
template <class T>
std::vector<T> large_vector(std::size_t n, const T& x) {
  return LargeArray<T>(n, x).take();
}

// The per-vertex arrays; their fresh pages are written on two threads when `two`.
void prepare_vertex_arrays(MeshWalkPrep& prep, std::vector<double>* fill, std::size_t nv, bool walk, bool two) {
  auto shortest = [&] { prep.nn2.assign(nv, kInf); };
  auto f_and_corners = [&] {
    if (fill) *fill = large_vector(nv, 0.0);
    if (walk) prep.tri_of_vertex.assign(nv, kNoId);
  };
  if (two) {
    run_beside(shortest, f_and_corners);
  } else {
    f_and_corners();
    shortest();
  }
}

// f at every vertex, in two halves at once when `two` (f must then be thread-safe).
void fill_spacing(const sizing::SizingField& f, const std::vector<Point2>& V, std::vector<double>& fill, bool two) {
  auto range = [&](std::size_t lo, std::size_t hi) {
    for (std::size_t i = lo; i < hi; ++i) fill[i] = f(V[i]);
  };
  const std::size_t nv = V.size();
  if (two) run_beside([&] { range(nv / 2, nv); }, [&] { range(0, nv / 2); });
  else range(0, nv);
}

// The triangle pass over every triangle, in chunks over `threads` workers (worker 0 the calling
// thread). A spacing that is not thread-safe is evaluated on the calling thread only: the other
// workers measure their chunks without it (listed in `without_f`), and `before_first` (filling f
// at the vertices) runs on the calling thread before its first chunk while they start.
struct TrianglePhase {
  std::vector<std::unique_ptr<TrianglePass>> passes;  // one per worker
  std::vector<ChunkSums> sums;
  std::vector<unsigned char> without_f;  // per chunk
};
template <class Before>
void measure_triangles(TrianglePhase& ph, const PassInputs& in, bool f_shared, unsigned threads, Before&& before_first) {
  const std::size_t nt = in.m.num_triangles(), nchunks = ph.sums.size();
  if (threads <= 1) {
    before_first();
    ph.passes[0]->measure<false>(0, nt, true);
    return;
  }
  bool started = false;
  // Work units of several sum chunks: fewer places where two workers write the same vertices.
  constexpr std::size_t kChunksPerUnit = 8;
  parallel_chunks(
      (nchunks + kChunksPerUnit - 1) / kChunksPerUnit,
      [&](std::size_t u, unsigned w) {
        if (w == 0 && !started) {
          before_first();
          started = true;
        }
        const bool with_f = w == 0 || f_shared || in.f == nullptr;
        const std::size_t c_hi = std::min(nchunks, (u + 1) * kChunksPerUnit);
        ph.passes[w]->measure<true>(u * kChunksPerUnit * kSumChunk, std::min(nt, c_hi * kSumChunk), with_f);
        for (std::size_t c = u * kChunksPerUnit; c < c_hi; ++c) ph.without_f[c] = !with_f;
      },
      threads);
  if (!started) before_first();
}

// The chunks measured without f, evaluated on the calling thread.
void evaluate_rest(TrianglePhase& ph, std::size_t nt) {
  for (std::size_t c = 0; c < ph.without_f.size(); ++c)
    if (ph.without_f[c]) ph.passes[0]->evaluate(c * kSumChunk, std::min(nt, (c + 1) * kSumChunk));
}

// The area and R/f(c) figures: the chunks' compensated sums added in chunk order.
void add_sums(QualityReport& r, const std::vector<ChunkSums>& sums, const PassFigures& fig, bool with_f) {
  CompensatedSum area, rf;
  std::size_t count = 0;
  for (const ChunkSums& cs : sums) {
    area.add(cs.area.sum);
    area.add(cs.area.c);
    rf.add(cs.r_over_f.sum);
    rf.add(cs.r_over_f.c);
    count += cs.count;
  }
  r.area = area.value();
  if (count > 0) r.mean_R_over_f = rf.value() / static_cast<double>(count);
  r.spacing_invalid += fig.spacing_invalid;
  if (with_f) *r.bad_triangles += fig.bad;
  if (fig.max_rf) update_max(r.max_R_over_f, *fig.max_rf);
}

// The triangle figures of the pass into r.
void add_triangle_figures(QualityReport& r, const PassFigures& fig) {
  r.degenerate_triangles += fig.q.degenerate_triangles;
  r.inverted_triangles += fig.q.inverted_triangles;
  r.min_angle_deg = fig.q.min_angle_deg;
  r.max_angle_deg = fig.q.max_angle_deg;
  r.min_angle_histogram = fig.q.min_angle_histogram;
  r.max_angle_histogram = fig.q.max_angle_histogram;
  r.max_radius_edge = fig.q.max_radius_edge;
}

// Orthogonality and smoothness: maxima from the pass, p99 from the largest values it kept (or,
// when too few were kept, from compute_orthogonality).
void add_orthogonality(QualityReport& r, PassFigures& fig, std::size_t top_k, const mesh::MeshView& m,
                       const std::vector<Index>& nb) {
  OrthogonalityStats& s = r.orthogonality;
  s.interior_edges = fig.interior;
  if (fig.interior > 0) {
    s.orthogonality_max = fig.omax;
    s.smoothness_max = fig.smax;
    s.orthogonality_p99 = quantile_from_top(fig.otop.values(), top_k, fig.interior, 0.99);
    s.smoothness_p99 = quantile_from_top(fig.stop.values(), top_k, fig.interior, 0.99);
    if (!s.orthogonality_p99 || !s.smoothness_p99) {
      const OrthogonalityStats all = compute_orthogonality(m, nb, nullptr);
      s.orthogonality_p99 = all.orthogonality_p99;
      s.smoothness_p99 = all.smoothness_p99;
    }
  }
  fig.otop.release();
  fig.stop.release();
}

// The walk's squared nearest-neighbour distances in vertex chunks over `threads` workers; empty
// when the walk cannot be used.
std::vector<double> walk_nearest(MeshNearestNeighbours& search, std::size_t nv, unsigned threads) {
  if (!search.usable()) return {};
  constexpr std::size_t kVertices = 8192;
  if (threads <= 1) {
    search.search(0, nv);
  } else {
    parallel_chunks(
        (nv + kVertices - 1) / kVertices,
        [&](std::size_t c, unsigned) { search.search(c * kVertices, std::min(nv, (c + 1) * kVertices)); }, threads);
  }
  return search.take();
}

}  // namespace

QualityReport compute_quality(const mesh::MeshView& m, const sizing::SizingField* f, double bound_B,
                              double alpha, const RunInfo& run, TriangleValues* per_triangle,
                              const std::vector<double>* f_at_vertices, std::vector<double>* fill_f_at_vertices) {
  StepLaps QL(debug::Aid::kReport, "  quality");  // developer aid (base/step_laps.hpp)
  QualityReport r = report_head(m, f, bound_B, alpha, run);
  check_vertex_ids(m);
  const std::size_t nv = m.num_vertices(), nt = m.num_triangles();
  // The mesher's adjacency, else one built from the triangles (meshes read from files).
  const bool own_nb = m.neighbours.size() != 3 * nt;
  const std::vector<Index> built = own_nb ? half_edge_neighbours(m) : std::vector<Index>{};
  const std::vector<Index>& nb = own_nb ? built : m.neighbours;
  const bool walk = !own_nb && nv >= 2;  // nearest neighbours by walking the mesher's mesh
  const bool two = max_threads() > 1 && nt >= kMinParallelTriangles;
  const unsigned threads = two ? max_threads() : 1;

  if (per_triangle) {
    per_triangle->area = large_vector(nt, 0.0);
    per_triangle->min_angle_deg = large_vector(nt, 0.0);
    if (f) per_triangle->r_over_f = large_vector(nt, kInf);
    else per_triangle->r_over_f.clear();
  }
  // f at the vertices: given, else evaluated here (el(p)/f(p) is measured per triangle).
  std::vector<double> own_fv;
  std::vector<double>* fill = fill_f_at_vertices;
  if (f && !fill && !(f_at_vertices && f_at_vertices->size() == nv)) fill = &own_fv;
  if (!f) fill = nullptr;
  MeshWalkPrep prep;
  prepare_vertex_arrays(prep, fill, nv, walk, two);
  const bool f_shared = f && f->thread_safe();
  bool filled = false;
  if (fill && f_shared) {
    fill_spacing(*f, m.vertices, *fill, two);
    filled = true;
  }
  const double* fv = f ? (fill ? fill->data() : f_at_vertices->data()) : m.f.size() == nv ? m.f.data() : nullptr;
  QL("setup");

  // Over 1 % of the interior edges (at most 3/2 per triangle but for repeated vertices; else the
  // p99s are measured again, as a sort would).
  const std::size_t top_k = 3 * nt / 200 + 4;
  TrianglePhase ph;
  ph.sums.resize((nt + kSumChunk - 1) / kSumChunk);
  ph.without_f.assign(ph.sums.size(), 0);
  const PassInputs in{m, nb, f, bound_B, per_triangle, walk, fv, prep.nn2.data(), prep.tri_of_vertex.data(),
                      ph.sums.data()};
  for (unsigned w = 0; w < threads; ++w) ph.passes.push_back(std::make_unique<TrianglePass>(in, r, top_k));
  measure_triangles(ph, in, f_shared, threads, [&] {
    if (fill && !filled) fill_spacing(*f, m.vertices, *fill, false);
  });
  PassFigures& fig = ph.passes[0]->fig;
  for (unsigned w = 1; w < threads; ++w) fig.absorb(ph.passes[w]->fig);
  QL("triangles");

  // The search over the mesher's mesh is built (on a second thread when there is one) while f is
  // evaluated on the chunks measured without it.
  prep.not_delaunay = std::move(fig.not_delaunay);
  prep.ccw = fig.ccw;
  std::optional<MeshNearestNeighbours> search;
  auto build = [&] {
    if (walk) search.emplace(m, nb, prep);
  };
  const bool pending = std::find(ph.without_f.begin(), ph.without_f.end(), 1) != ph.without_f.end();
  if (pending && walk) {
    run_beside(build, [&] { evaluate_rest(ph, nt); });
  } else {
    evaluate_rest(ph, nt);
    build();
  }
  QL("evaluate+build");
  std::vector<double> walk_sq = search ? walk_nearest(*search, nv, threads) : std::vector<double>{};
  search.reset();
  QL("search");

  add_triangle_figures(r, fig);
  add_sums(r, ph.sums, fig, f != nullptr);
  ph.sums = {};
  add_orthogonality(r, fig, top_k, m, nb);

  // Vertex metrics: nn(p) is exact over all vertices (not only mesh neighbours).
  const std::vector<double> nn = nearest_from(std::move(walk_sq), std::move(prep.nn2).take(), m.vertices);
  prep.tri_of_vertex.release();
  QL("merge+p99+take");
  if (nv >= 2) r.nn_min = *std::min_element(nn.begin(), nn.end());
  const bool have_vertex_f = f != nullptr || m.f.size() == nv;
  if (!have_vertex_f || nv < 2) return r;
  r.el_over_f_max = fig.el_f_max;  // el(p) is defined at corners only
  conformity_figures(r, nn, fv, f, m.vertices);
  QL("conformity");
  return r;
}

}  // namespace fdr::quality
