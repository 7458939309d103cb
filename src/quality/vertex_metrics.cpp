// The report's vertex metrics (see vertex_metrics.hpp).
#include "quality/vertex_metrics.hpp"

#include <algorithm>
#include <cmath>
#include "base/error.hpp"
#include "base/kd_tree.hpp"
#include "base/parallel.hpp"
#include "quality/compensated_sum.hpp"
#include "quality/extremes.hpp"
#include "quality/top_k.hpp"

namespace fdr::quality {

std::vector<double> nearest_neighbour_distances(const std::vector<Point2>& pts) {
  std::vector<double> nn(pts.size(), kInf);
  if (pts.size() < 2) return nn;
  const KdTree tree(pts);
  for (std::size_t k = 0; k < tree.size(); ++k) nn[tree.id_at(k)] = std::sqrt(tree.nearest_sq_at(k));
  return nn;
}

std::vector<double> nearest_from(std::vector<double>&& walk_sq, std::vector<double>&& edge_sq,
                                 const std::vector<Point2>& vertices) {
  if (!walk_sq.empty()) {
    for (double& d : walk_sq) d = std::sqrt(d);
    return std::move(walk_sq);
  }
  std::vector<double> nn = std::move(edge_sq);
  if (vertices.size() >= 2) {
    const KdTree tree(vertices, max_threads());
    for (std::size_t k = 0; k < tree.size(); ++k) {
      const Index i = tree.id_at(k);
      nn[i] = std::sqrt(tree.nearest_sq_at(k, nn[i]));
    }
  }
  return nn;
}

namespace {

// The conformity figures of a range of vertices.
struct VertexPart {
  std::size_t invalid = 0, nconf = 0;
  std::optional<double> nn_over_f_min, conf_min;
  Histogram hist;
  TopK low;  // the largest values of -conformity: the smallest 5 % without a copy of every value
};

// Conformity min(nn/f, f/nn) of the vertices [lo, hi); `sum` (when given) adds them in order.
void measure_vertices(std::size_t lo, std::size_t hi, const std::vector<double>& nn, const double* fv,
                      const sizing::SizingField* f, const std::vector<Point2>& vertices, VertexPart& vp,
                      CompensatedSum* sum) {
  for (std::size_t i = lo; i < hi; ++i) {
    const double fp = fv ? fv[i] : (*f)(vertices[i]);
    if (!usable_spacing(fp)) {
      ++vp.invalid;
      continue;
    }
    const double q = nn[i] / fp;
    const double ci = std::min(q, fp / nn[i]);  // nn = 0 (duplicate point) gives 0
    ++vp.nconf;
    vp.low.add(-ci);
    update_min(vp.conf_min, ci);
    if (sum) sum->add(ci);
    vp.hist.add(ci);
    update_min(vp.nn_over_f_min, q);
  }
}

// p05 by nearest rank: the smallest value with at least 5 % of the n values at or below it,
// from the largest values of their negations.
double p05_from(TopK& low, std::size_t n) {
  const std::size_t rank = static_cast<std::size_t>(std::ceil(0.05 * static_cast<double>(n)));
  const std::size_t k = rank == 0 ? 0 : rank - 1;  // the k-th smallest is the (k+1)-th largest of -ci
  std::vector<double>& v = low.values();
  if (k + 1 > v.size()) throw Error(ExitCode::kInternal, "quality: percentile buffer too small");
  const auto at = v.end() - static_cast<std::ptrdiff_t>(k + 1);
  std::nth_element(v.begin(), at, v.end(), TopK::less);
  return -*at;
}

}  // namespace

void conformity_figures(QualityReport& r, const std::vector<double>& nn, const double* fv,
                        const sizing::SizingField* f, const std::vector<Point2>& vertices) {
  const std::size_t nv = vertices.size();
  // With f at the vertices in an array, two halves at once; the compensated sum runs over every
  // vertex in order on this thread (it depends on the order).
  std::vector<VertexPart> vparts(fv && max_threads() > 1 && nv >= 16384 ? 2 : 1,
                                 VertexPart{0, 0, {}, {}, r.conformity_histogram, TopK(nv / 20 + 4)});
  CompensatedSum conf_sum;
  if (vparts.size() == 2) {
    const std::size_t half = nv / 2;
    run_beside([&] { measure_vertices(half, nv, nn, fv, f, vertices, vparts[1], nullptr); },
               [&] {
                 measure_vertices(0, half, nn, fv, f, vertices, vparts[0], &conf_sum);
                 for (std::size_t i = half; i < nv; ++i)
                   if (usable_spacing(fv[i])) conf_sum.add(std::min(nn[i] / fv[i], fv[i] / nn[i]));
               });
  } else {
    measure_vertices(0, nv, nn, fv, f, vertices, vparts[0], &conf_sum);
  }
  std::size_t nconf = 0;
  std::optional<double> conf_min;
  for (VertexPart& vp : vparts) {
    r.spacing_invalid += vp.invalid;
    nconf += vp.nconf;
    if (vp.nn_over_f_min) update_min(r.nn_over_f_min, *vp.nn_over_f_min);
    if (vp.conf_min) update_min(conf_min, *vp.conf_min);
    for (std::size_t b = 0; b < r.conformity_histogram.counts.size(); ++b)
      r.conformity_histogram.counts[b] += vp.hist.counts[b];
    if (&vp != &vparts[0]) vparts[0].low.absorb(vp.low);
  }
  if (nconf == 0) return;
  r.conformity_mean = conf_sum.value() / static_cast<double>(nconf);
  r.conformity_p05 = p05_from(vparts[0].low, nconf);
  r.conformity_min = conf_min;
}

}  // namespace fdr::quality
