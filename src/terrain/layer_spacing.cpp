// The spacing bounded by the layers' thickness (layer_spacing.hpp).
#include "terrain/layer_spacing.hpp"
#include <algorithm>
#include <cmath>
#include <limits>
#include "base/error.hpp"
#include "sizing/spacing3d_limiter.hpp"

namespace fdr::terrain {
namespace {

// The cell indices along one axis whose centres lie within one cell of [lo, hi].
std::pair<std::size_t, std::size_t> cell_range(double lo, double hi, double origin, double d, std::size_t n) {
  const double a = std::ceil((lo - d - origin) / d - 0.5), b = std::floor((hi + d - origin) / d - 0.5);
  const double top = static_cast<double>(n) - 1;
  return {static_cast<std::size_t>(std::clamp(a, 0.0, top)), static_cast<std::size_t>(std::clamp(b, 0.0, top))};
}

}  // namespace

LayerSpacingResult bound_by_layer_thickness(sizing::Grid3& g, const Tin& tin, const std::vector<Surface>& stack,
                                           const LayerSpacing& opt, const Layering& layering) {
  if (!(opt.factor > 0) || !std::isfinite(opt.factor) || !(opt.grade > 0) || !std::isfinite(opt.grade))
    throw Error(ExitCode::kUsage, "terrain spacing: the layer thickness factor and grade must be > 0");
  if (g.v.size() != g.nx * g.ny * g.nz) throw Error(ExitCode::kInternal, "terrain spacing: the grid is not filled");
  constexpr double kInf = std::numeric_limits<double>::infinity();
  sizing::Grid3 bound = g;
  std::fill(bound.v.begin(), bound.v.end(), kInf);
  const std::size_t layers = stack.empty() ? 0 : stack.size() - 1;
  std::vector<ThinPlace> thinnest(layers);
  for (std::size_t s = 0; s < layers; ++s) thinnest[s] = {s, {}, kInf};
  for (std::size_t ti = 0; ti < tin.triangles.size(); ++ti) {
    const auto& t = tin.triangles[ti];
    double xlo = kInf, xhi = -kInf, ylo = kInf, yhi = -kInf;
    for (VertexId v : t) {
      xlo = std::min(xlo, tin.xy[v].x), xhi = std::max(xhi, tin.xy[v].x);
      ylo = std::min(ylo, tin.xy[v].y), yhi = std::max(yhi, tin.xy[v].y);
    }
    const auto [i0, i1] = cell_range(xlo, xhi, g.x0, g.dx, g.nx);
    const auto [j0, j1] = cell_range(ylo, yhi, g.y0, g.dy, g.ny);
    for (std::size_t s = 0; s < layers; ++s) {
      double thin = kInf, zlo = kInf, zhi = -kInf, zmid = 0;
      for (int k = 0; k < 3; ++k) {
        const double up = corner_z(stack, layering, tin, ti, s, k), lo = corner_z(stack, layering, tin, ti, s + 1, k);
        if (up - lo > 0) thin = std::min(thin, up - lo);
        zlo = std::min(zlo, lo), zhi = std::max(zhi, up), zmid += (up + lo) / 6;
      }
      if (thin == kInf) continue;  // pinched out on the whole triangle
      const double b = opt.factor * thin;
      if (b < opt.hmin && thin < thinnest[s].thickness) {
        const Point2 a = tin.xy[t[0]], c = tin.xy[t[1]], d = tin.xy[t[2]];
        thinnest[s] = {s, {(a.x + c.x + d.x) / 3, (a.y + c.y + d.y) / 3, zmid}, thin};
      }
      const auto [k0, k1] = cell_range(zlo, zhi, g.z0, g.dz, g.nz);
      for (std::size_t k = k0; k <= k1; ++k)
        for (std::size_t j = j0; j <= j1; ++j)
          for (std::size_t i = i0; i <= i1; ++i) bound.at(i, j, k) = std::min(bound.at(i, j, k), b);
    }
  }
  // The same convention as the depth spacing: a per-axis limit of grade / sqrt(3) keeps the
  // trilinear field grade-Lipschitz.
  // Limiting only lowers a cell to another's bound plus a non-negative amount, so no limited bound
  // is below the least one: when that is no smaller than every spacing cell, no cell of g changes
  // with or without the limiter, and its sweeps over the whole grid are spared (every layer
  // thicker than the spacing needs, the usual case without thin horizons).
  const double least_bound = *std::min_element(bound.v.begin(), bound.v.end());
  const double most_spacing = *std::max_element(g.v.begin(), g.v.end());
  if (least_bound < most_spacing) sizing::limit_gradient3(bound, opt.grade / std::sqrt(3.0));
  LayerSpacingResult r;
  r.smallest = kInf;
  for (std::size_t c = 0; c < g.v.size(); ++c) {
    if (bound.v[c] < g.v[c]) {
      g.v[c] = bound.v[c];
      if (g.v[c] < opt.hmin) ++r.cells_below_hmin;
    }
    r.smallest = std::min(r.smallest, g.v[c]);
  }
  for (const ThinPlace& p : thinnest)
    if (p.thickness < kInf) r.places.push_back(p);
  std::sort(r.places.begin(), r.places.end(), [](const ThinPlace& a, const ThinPlace& b) { return a.thickness < b.thickness; });
  return r;
}

}  // namespace fdr::terrain
