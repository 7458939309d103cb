// The GIS spacing rules on a grid: each rule named, then combined, clamped and filled in one pass.
#include "base/num_format.hpp"
#include "sizing/spacing_rules.hpp"
#include "sizing/channel_rule.hpp"
#include <algorithm>
#include <sstream>
#include "sizing/raster_rules.hpp"
#include "sizing/resample_grid.hpp"
#include "base/parallel.hpp"
#include <cmath>

namespace fdr::sizing {
namespace {
std::string num(double v) { return num6(v); }
}  // namespace

RuleGrid spacing_from_rules(const SpacingRules& r, const RuleInputs& in) {
  const Grid& like = *in.like;
  RuleGrid out;
  std::vector<Grid> rules;
  auto& names = out.names;
  // Distance to shore (land and island edges; open boundaries are not shore).
  Grid dist;
  const bool have_shore = in.shore && !in.shore->empty();
  if (have_shore && (r.dist_grade || !r.any() || r.channel_elements)) dist = distance_to_shore(like, *in.shore);
  // Channels: N elements across narrow water (its medial ridge of the distance to shore). Made
  // first, so the distance rule then takes the distance grid over in place; listed second (the
  // minimum does not depend on the order).
  Grid channel;
  const bool channels = r.channel_elements && have_shore && in.boundary && !in.boundary->empty();
  if (channels) channel = rule_channel(dist, inside_mask(like, *in.boundary), *r.channel_elements);
  if (r.dist_grade || !r.any()) {
    const double grade = r.dist_grade.value_or(0.1);
    if (have_shore) {
      rules.push_back(rule_distance(std::move(dist), r.hmin, grade));
      names.push_back("distance (hmin + " + num(grade) + " d)");
    }
  }
  if (channels) {
    rules.push_back(std::move(channel));
    names.push_back("channel (" + num(*r.channel_elements) + " elements across)");
  }
  // Depth rules run on the DEM resampled to the spacing grid: the curvature rule on a DEM's
  // native (often coarser) cells would miss the bends between samples that a fine TIN must follow.
  Grid zfine, depth;
  if (in.dem && (r.slope || r.wavelength || r.vertical_tol)) {
    zfine = resample_like(*in.dem, like);
    depth = zfine;
    for (auto& v : depth.v) v = -v;  // elevation positive up -> depth positive down
  }
  if (r.slope && in.dem) {
    rules.push_back(rule_slope(depth, *r.slope));
    names.push_back("slope (slp " + num(*r.slope) + ")");
  }
  if (r.wavelength && in.dem) {
    rules.push_back(rule_wavelength(depth, r.wave_period_s, *r.wavelength));
    names.push_back("wavelength (T " + num(r.wave_period_s) + " s, wl " + num(*r.wavelength) + ")");
  }
  if (r.vertical_tol && in.dem) {
    rules.push_back(rule_curvature(zfine, *r.vertical_tol));
    names.push_back("vertical error (tol " + num(*r.vertical_tol) + " m)");
  }
  if (in.size) {
    rules.push_back(*in.size);
    names.push_back("size raster " + r.size_raster);
  }
  (void)clamp(Grid{}, r.hmin, r.hmax);  // checks 0 < hmin <= hmax (an empty grid: no work)
  Grid h;
  if (rules.empty()) {
    h = like;
    std::fill(h.v.begin(), h.v.end(), r.hmax);
  } else {
    for (const Grid& g : rules)
      if (g.nx != rules[0].nx || g.ny != rules[0].ny || g.x0 != rules[0].x0 || g.y0 != rules[0].y0 ||
          g.dx != rules[0].dx || g.dy != rules[0].dy || g.v.size() != rules[0].v.size())
        (void)combine_min(rules);  // throws Error(kInternal) naming the grids
    // combine_min, clamp and fill_nan in one pass, in place over the first rule's grid.
    h = std::move(rules[0]);
    const double hmin = r.hmin, hmax = r.hmax;
    parallel_bands(h.ny, [&](std::size_t j0, std::size_t j1) {
      for (std::size_t c = j0 * h.nx; c < j1 * h.nx; ++c) {
        double v = h.v[c];
        for (std::size_t k = 1; k < rules.size(); ++k) v = std::fmin(v, rules[k].v[c]);
        h.v[c] = std::isnan(v) ? hmax : std::min(std::max(v, hmin), hmax);
      }
    });
  }
  out.h = std::move(h);
  return out;
}

std::string describe_rules(const RuleGrid& g, const SpacingRules& r, double gradation) {
  std::string desc = "grid " + std::to_string(g.h.nx) + "x" + std::to_string(g.h.ny) + ": min(";
  for (std::size_t i = 0; i < g.names.size(); ++i) desc += (i ? ", " : "") + g.names[i];
  desc += ") clamped to [" + num(r.hmin) + ", " + num(r.hmax) + "] m, gradient-limited to " + num(gradation);
  return desc;
}

}  // namespace fdr::sizing
