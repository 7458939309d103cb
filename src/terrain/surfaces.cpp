// Clamping a stack of surfaces into non-crossing order (surfaces.hpp).
#include "terrain/surfaces.hpp"
#include <algorithm>
#include <cmath>
#include <sstream>
#include "base/error.hpp"

namespace fdr::terrain {
namespace {

std::string where(const Tin& tin, Point2 origin, std::size_t v) {
  std::ostringstream s;
  s.precision(12);
  s << "vertex " << v << " (" << origin.x + tin.xy[v].x << ", " << origin.y + tin.xy[v].y << ")";
  return s.str();
}

void check_shapes(const std::vector<Surface>& stack, const Tin& tin) {
  if (stack.size() < 2) throw Error(ExitCode::kInvalidGeometry, "a terrain volume needs a top and a base");
  for (const Surface& s : stack) {
    if (s.z.size() != tin.xy.size())
      throw Error(ExitCode::kInternal, "surface " + s.name + ": " + std::to_string(s.z.size()) +
                                           " elevations for " + std::to_string(tin.xy.size()) + " vertices");
    for (std::size_t v = 0; v < s.z.size(); ++v)
      if (!std::isfinite(s.z[v]))
        throw Error(ExitCode::kInvalidGeometry, "surface " + s.name + ": no elevation at " + where(tin, {}, v));
  }
}

}  // namespace

double default_min_thickness(double hmin, double vertical_tol) {
  const double h = std::isfinite(hmin) && hmin > 0 ? kMinThicknessPerHmin * hmin : 0.0;
  return std::max(h, std::isfinite(vertical_tol) && vertical_tol > 0 ? vertical_tol : 0.0);
}

ClampCounts clamp_surfaces(std::vector<Surface>& stack, const Tin& tin, Point2 origin, double min_thickness) {
  check_shapes(stack, tin);
  const Surface& top = stack.front();
  const Surface& base = stack.back();
  for (std::size_t v = 0; v < tin.xy.size(); ++v)
    if (!(base.z[v] < top.z[v])) {
      std::ostringstream s;
      s << "the base (" << base.z[v] << " m) is not below the top (" << top.z[v] << " m) at " << where(tin, origin, v);
      throw Error(ExitCode::kInvalidGeometry, s.str());
    }
  ClampCounts c;
  c.lowered.assign(stack.size(), 0);
  c.raised.assign(stack.size(), 0);
  c.collapsed.assign(stack.size(), 0);
  for (std::size_t k = 1; k + 1 < stack.size(); ++k) {
    const std::vector<double>& above = stack[k - 1].z;
    std::vector<double>& z = stack[k].z;
    bool inside_somewhere = false;
    for (std::size_t v = 0; v < z.size(); ++v) {
      if (z[v] >= above[v]) {
        z[v] = above[v];
        ++c.lowered[k];
      } else if (z[v] <= base.z[v]) {
        z[v] = base.z[v];
        ++c.raised[k];
      } else if (above[v] - z[v] < min_thickness) {
        z[v] = above[v];
        ++c.collapsed[k];
      } else if (z[v] - base.z[v] < min_thickness) {
        z[v] = base.z[v];
        ++c.collapsed[k];
      } else {
        inside_somewhere = true;
      }
    }
    if (!inside_somewhere)
      throw Error(ExitCode::kInvalidGeometry,
                  "horizon " + stack[k].name + " lies nowhere between the surface above it and the base" +
                      (c.collapsed[k] ? " by the minimum layer thickness (--min-thickness)" : "") + ": its layer would be empty");
  }
  return c;
}

}  // namespace fdr::terrain
