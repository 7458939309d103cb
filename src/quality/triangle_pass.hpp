// The report's single pass over the triangles and their interior edges: every triangle metric,
// the interior edges' orthogonality and smoothness, the vertices' shortest edges and what the
// nearest-neighbour walk needs, and the area and R/f(c) sums. Any worker may measure any range;
// the figures are combined so that they do not depend on how the triangles were split.
#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>
#include "mesh/mesh_view.hpp"
#include "quality/angle_bins.hpp"
#include "quality/compensated_sum.hpp"
#include "quality/report.hpp"
#include "quality/top_k.hpp"
#include "sizing/sizing_field.hpp"

namespace fdr::quality {

// Triangles per chunk: the unit of the area and R/f(c) sums (each in triangle order; the chunks
// are added in order at the end) and of the work handed to the threads.
constexpr std::size_t kSumChunk = 4096;
struct ChunkSums {
  CompensatedSum area, r_over_f;
  std::size_t count = 0;
};

// What every worker reads, and the per-vertex and per-chunk arrays they write.
struct PassInputs {
  const mesh::MeshView& m;
  const std::vector<Index>& nb;  // half-edge adjacency
  const sizing::SizingField* f;
  double bound_B;
  TriangleValues* per_triangle;
  bool walk;  // gather what the nearest-neighbour walk needs (tri_of_vertex, local Delaunay check)
  // f at the vertices (null without f): el(p)/f(p) is the largest of lmax(T)/f(p) over the
  // triangles T at p (a division by f(p) > 0 keeps the order, also as rounded), so no el array.
  const double* fv;
  double* nn2;       // per vertex: shortest mesh edge, squared
  Index* tov;        // per vertex: a triangle with that corner
  ChunkSums* sums;   // per chunk of kSumChunk triangles
};

// What one worker measured over its triangles.
struct PassFigures {
  PassFigures(const QualityReport& r, std::size_t top_k);
  QualityReport q;  // degenerate, inverted, angle extremes and histograms, max R/l
  AngleBins angles;
  std::size_t interior = 0;   // interior edges
  double omax = -1, smax = -1;  // orthogonality and smoothness maxima
  TopK otop, stop;
  std::vector<Index> not_delaunay;
  bool ccw = true;
  std::size_t spacing_invalid = 0, bad = 0;
  std::optional<double> max_rf, el_f_max;
  // Adds another worker's figures (every one a count, an extreme or a multiset).
  void absorb(PassFigures& o);
};

class TrianglePass {
 public:
  TrianglePass(const PassInputs& in, const QualityReport& r, std::size_t top_k) : in_(in), fig(r, top_k) {}
  // Everything for the triangles [lo, hi); with_f: also the area, R/f(c) and el/f (else
  // evaluate() does them later). kShared: other workers write nn2 and tov at the same time.
  template <bool kShared>
  void measure(std::size_t lo, std::size_t hi, bool with_f);
  // The area, R/f(c) and el/f of the triangles [lo, hi) measured without f.
  void evaluate(std::size_t lo, std::size_t hi);

 private:
  static constexpr std::size_t kBatch = 64;
  // Per triangle of a batch.
  struct Tri {
    Point2 a, b, c;
    double cr, q[3], lmin, lmax, radius;
    Point2 cc, cell;  // circumcentre; cell centre (when the triangle measures an edge)
    int o;
  };
  // Per interior edge of a batch (measured from its half-edge u -> w with u <= w).
  struct Edge {
    std::uint32_t i;  // triangle in the batch
    int k;
    Point2 ga, gb, gc, far;
  };
  template <bool kShared>
  void measure_batch(std::size_t lo, std::size_t hi, bool with_f);
  std::size_t load_batch(std::size_t lo, std::size_t n);
  void shape_batch(std::size_t n);
  template <bool kShared>
  void triangles_batch(std::size_t lo, std::size_t n, bool with_f);
  void edges_batch(std::size_t lo, std::size_t ne);
  void el_over_f(const std::array<Index, 3>& tr, double lmax);
  void add_f(std::size_t t, double cr, double radius, Point2 center);

  PassInputs in_;
  Tri tri_[kBatch];
  Edge edge_[3 * kBatch];

 public:
  PassFigures fig;
};

}  // namespace fdr::quality
