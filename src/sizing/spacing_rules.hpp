// The GIS spacing rules, evaluated on a grid in ground metres: the rules
// named on the command line combined by minimum, clamped to [hmin, hmax], nodata -> hmax.
#pragma once
#include <optional>
#include <string>
#include <utility>
#include <vector>
#include "sizing/grid.hpp"

namespace fdr::sizing {

struct SpacingRules {
  double hmin = 0, hmax = 0;                // metres, 0 < hmin <= hmax
  std::optional<double> dist_grade;         // h = hmin + grade * distance to shore
  std::optional<double> slope;              // h = (2 pi / slp) depth / |grad depth|   (needs a DEM)
  std::optional<double> wavelength;         // h = T sqrt(g depth) / wl                (needs a DEM)
  double wave_period_s = 44712.0;           // T
  std::optional<double> vertical_tol;       // h = sqrt(8 tol / |curvature|)          (needs a DEM)
  std::string size_raster;                  // name of an explicit size raster ("" none)
  // Channel rule (channel_rule.hpp): at least N elements across narrow water; combined with the
  // others by minimum; not counted by any() (it refines, it does not replace the default rule).
  std::optional<double> channel_elements;
  // True if any rule is named; without one the distance rule h = hmin + 0.1 d is used.
  bool any() const { return dist_grade || slope || wavelength || vertical_tol || !size_raster.empty(); }
};

// The inputs the rules read, all on (or resampled to) the cells of `like`.
struct RuleInputs {
  const Grid* like = nullptr;                                // the spacing grid's cells
  const std::vector<std::pair<Point2, Point2>>* shore = nullptr;  // land and island segments
  const Grid* dem = nullptr;                                 // elevation (positive up), any cells
  const Grid* size = nullptr;                                // size_raster_rule() of the size raster
  const std::vector<std::pair<Point2, Point2>>* boundary = nullptr;  // every domain boundary segment (water mask)
};

struct RuleGrid {
  Grid h;                                   // combined, clamped to [hmin, hmax], NaN filled with hmax
  std::vector<std::string> names;           // one label per rule used, in order
};

// Evaluates the rules (distance, slope, wavelength, curvature, size raster), combines them by
// minimum (hmax everywhere when none applies), clamps and fills nodata. A rule that needs the DEM
// is skipped without one (the caller refuses such options first).
RuleGrid spacing_from_rules(const SpacingRules& rules, const RuleInputs& in);

// "grid NXxNY: min(rule, ...) clamped to [hmin, hmax] m, gradient-limited to G" (reports, logs).
std::string describe_rules(const RuleGrid& g, const SpacingRules& rules, double gradation);

}  // namespace fdr::sizing
