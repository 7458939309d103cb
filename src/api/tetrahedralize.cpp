// The 3D facade: reads by extension (tetio), spacing specs (sizing), the mesher (tet).
#include "api/tetrahedralize.hpp"
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include "base/error.hpp"
#include "sizing/spacing3d_make.hpp"
#include "tetio/read_plc.hpp"
#include "tetio/read_tetgen.hpp"

namespace fdr {
namespace {

std::string lower_extension(const std::string& path) {
  const auto slash = path.find_last_of('/');
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string e = path.substr(dot + 1);
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return e;
}

}  // namespace

TetResult tetrahedralize(const plc::Plc& plc, const sizing::SizingField3& f, const TetOptions& options) {
  TetResult r = tet::tetrahedralize(plc, f, options);
  if (r.stats.capped)
    throw Error(ExitCode::kWorkLimit, (plc.source.empty() ? std::string("input") : plc.source) +
                                          ": the vertex cap was reached before every tetrahedron met R/f(c) <= B; "
                                          "coarsen the spacing or raise the cap");
  return r;
}

TetResult tetrahedralize(const plc::Plc& plc, const std::string& spacing, const TetOptions& options) {
  const sizing::SizingPtr3 f = sizing::make_spacing3(spacing);
  return fdr::tetrahedralize(plc, *f, options);
}

std::string default_spacing3(const plc::Plc& plc) {
  if (plc.points.empty()) return "1";
  Point3 lo = plc.points[0], hi = plc.points[0];
  for (const auto& p : plc.points) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  const double d = dist(lo, hi) / 20.0;
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", d > 0 && std::isfinite(d) ? d : 1.0);
  return buf;
}

sizing::SizingPtr3 grid_spacing3(sizing::Grid3 grid, const std::string& label) {
  return std::make_shared<const sizing::GridField3>(std::move(grid), label);
}

plc::Plc read_plc(const std::string& path) { return tetio::read_plc(path); }

bool is_3d_input(const std::string& path) {
  const std::string e = lower_extension(path);
  if (e == "smesh" || e == "off" || e == "stl" || e == "ply") return true;
  if (e == "poly" || e == "node") {
    try {
      return tetio::poly_dimension(path) == 3;
    } catch (const Error&) {
      return false;
    }
  }
  return false;
}

}  // namespace fdr
