// Clamping a stack of surfaces into non-crossing order (surfaces.hpp).
#include "terrain/surfaces.hpp"
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
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

namespace {

double area_of(const Tin& tin, const std::array<VertexId, 3>& t) {
  const Point2 a = tin.xy[t[0]], b = tin.xy[t[1]], c = tin.xy[t[2]];
  return 0.5 * std::abs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
}

// The layering of one triangle (q: its n entries) from the top down, each removal counted in r.
void end_pinch_outs_on(const Tin& tin, const std::vector<Surface>& stack, std::size_t t, std::uint16_t* q,
                       PinchOutRepair& r) {
  const std::size_t n = stack.size();
  const auto base = static_cast<std::uint16_t>(n - 1);
  const auto& tri = tin.triangles[t];
  for (std::size_t s = 0; s + 1 < n; ++s) {
    if (q[s] == q[s + 1]) continue;
    int zero = 0, positive = 0;
    double sum = 0;
    for (VertexId v : tri) {
      const double th = stack[q[s]].z[v] - stack[q[s + 1]].z[v];
      (th > 0 ? positive : zero) += 1;
      sum += th;
    }
    if (zero == 0 || positive == 0) continue;
    ++r.triangles[s];
    r.volume[s] += area_of(tin, tri) * sum / 3.0;
    if (q[s + 1] == base) {
      // The base stays: the surfaces on this layer's top over the triangle (those following the
      // same surface, or meeting it at all three corners) go down onto it. The top is never among
      // them: the column between the top and the base is positive everywhere.
      const std::uint16_t up = q[s];
      auto on_top = [&](std::uint16_t a) {
        return a == up || std::all_of(tri.begin(), tri.end(), [&](VertexId v) { return stack[a].z[v] == stack[up].z[v]; });
      };
      for (std::size_t k = s + 1; k-- > 1 && on_top(q[k]);) q[k] = base;
    } else {
      q[s + 1] = q[s];
    }
  }
}

}  // namespace

PinchOutRepair end_pinch_outs(const Tin& tin, const std::vector<Surface>& stack) {
  const std::size_t n = stack.size();
  if (n < 2) throw Error(ExitCode::kInvalidGeometry, "a terrain volume needs a top and a base");
  if (n > std::numeric_limits<std::uint16_t>::max())
    throw Error(ExitCode::kUsage, "a terrain volume takes at most " +
                                      std::to_string(std::numeric_limits<std::uint16_t>::max()) + " surfaces");
  PinchOutRepair r;
  r.triangles.assign(n - 1, 0);
  r.volume.assign(n - 1, 0.0);
  std::vector<std::uint16_t> on(tin.triangles.size() * n);
  for (std::size_t t = 0; t < tin.triangles.size(); ++t) {
    std::uint16_t* q = on.data() + t * n;
    std::iota(q, q + n, std::uint16_t{0});
    end_pinch_outs_on(tin, stack, t, q, r);
    for (std::size_t s = 1; s + 1 < n; ++s)
      if (q[s] != s)
        for (VertexId v : tin.triangles[t]) {
          const double d = std::abs(stack[q[s]].z[v] - stack[s].z[v]);
          if (d > r.largest_move) r.largest_move = d, r.largest_at = v;
        }
  }
  const bool changed = std::any_of(r.triangles.begin(), r.triangles.end(), [](std::size_t c) { return c > 0; });
  if (changed) {
    r.layering.surfaces = n;
    r.layering.on = std::move(on);
  }
  return r;
}

}  // namespace fdr::terrain
