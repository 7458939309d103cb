// The GIS spacing rules on a grid (moved from pipeline/gis_stage.cpp: issue 8).
#include "sizing/spacing_rules.hpp"
#include <algorithm>
#include <sstream>
#include "sizing/raster_rules.hpp"
#include "sizing/resample_grid.hpp"

namespace fdr::sizing {
namespace {
std::string num(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}
}  // namespace

RuleGrid spacing_from_rules(const SpacingRules& r, const RuleInputs& in) {
  const Grid& like = *in.like;
  RuleGrid out;
  std::vector<Grid> rules;
  auto& names = out.names;
  // Distance to shore (land and island edges; open boundaries are not shore).
  if (r.dist_grade || !r.any()) {
    const double grade = r.dist_grade.value_or(0.1);
    if (in.shore && !in.shore->empty()) {
      rules.push_back(rule_distance(distance_to_shore(like, *in.shore), r.hmin, grade));
      names.push_back("distance (hmin + " + num(grade) + " d)");
    }
  }
  // Depth rules run on the DEM resampled to the spacing grid: the curvature rule on the native
  // 5'/30" cells would miss the bends between samples that a fine TIN must follow.
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
  Grid h;
  if (rules.empty()) {
    h = like;
    std::fill(h.v.begin(), h.v.end(), r.hmax);
  } else {
    h = combine_min(rules);
  }
  h = clamp(h, r.hmin, r.hmax);
  out.h = fill_nan(h, r.hmax);
  return out;
}

std::string describe_rules(const RuleGrid& g, const SpacingRules& r, double gradation) {
  std::string desc = "grid " + std::to_string(g.h.nx) + "x" + std::to_string(g.h.ny) + ": min(";
  for (std::size_t i = 0; i < g.names.size(); ++i) desc += (i ? ", " : "") + g.names[i];
  desc += ") clamped to [" + num(r.hmin) + ", " + num(r.hmax) + "] m, gradient-limited to " + num(gradation);
  return desc;
}

}  // namespace fdr::sizing
