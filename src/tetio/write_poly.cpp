// TetGen .poly writer for plc::Plc.
#include "tetio/write_poly.hpp"

#include "base/error.hpp"
#include "base/out_file.hpp"

namespace fdr::tetio {
namespace {

std::int64_t n64(std::size_t v) { return static_cast<std::int64_t>(v); }

void check_ids(const plc::Plc& p) {
  auto bad = [&](VertexId v) { return static_cast<std::size_t>(v) >= p.points.size(); };
  for (std::size_t f = 0; f < p.facets.size(); ++f) {
    for (const auto& poly : p.facets[f].polygons) {
      for (VertexId v : poly) {
        if (bad(v)) throw Error(ExitCode::kInternal, "PLC to write: facet " + std::to_string(f) + " has vertex " + std::to_string(v));
      }
    }
  }
  for (std::size_t s = 0; s < p.segments.size(); ++s) {
    if (bad(p.segments[s][0]) || bad(p.segments[s][1])) {
      throw Error(ExitCode::kInternal, "PLC to write: segment " + std::to_string(s) + " has a vertex out of range");
    }
  }
  if (!p.point_markers.empty() && p.point_markers.size() != p.points.size()) {
    throw Error(ExitCode::kInternal, "PLC to write: point_markers length differs from points");
  }
}

void point(OutFile& out, Point3 p) { out.num(p.x).sp().num(p.y).sp().num(p.z); }

}  // namespace

void write_poly(const std::string& path, const plc::Plc& p) {
  check_ids(p);
  OutFile out(path);
  const bool markers = !p.point_markers.empty();
  out.str("# <points> <dimension> <attributes> <boundary markers>\n");
  out.num(n64(p.points.size())).str(markers ? " 3 0 1\n" : " 3 0 0\n");
  for (std::size_t i = 0; i < p.points.size(); ++i) {
    out.num(n64(i + 1)).sp();
    point(out, p.points[i]);
    if (markers) out.sp().num(static_cast<std::int64_t>(p.point_markers[i]));
    out.nl();
  }
  out.str("# <facets> <boundary markers>\n").num(n64(p.facets.size() + p.segments.size())).str(" 1\n");
  for (const plc::Facet& f : p.facets) {
    out.num(n64(f.polygons.size())).sp().num(n64(f.holes.size())).sp().num(static_cast<std::int64_t>(f.marker)).nl();
    for (const auto& poly : f.polygons) {
      out.num(n64(poly.size()));
      for (VertexId v : poly) out.sp().num(static_cast<std::int64_t>(v) + 1);
      out.nl();
    }
    for (std::size_t h = 0; h < f.holes.size(); ++h) {
      out.num(n64(h + 1)).sp();
      point(out, f.holes[h]);
      out.nl();
    }
  }
  for (const auto& s : p.segments) {
    out.str("1 0 0\n2 ").num(static_cast<std::int64_t>(s[0]) + 1).sp().num(static_cast<std::int64_t>(s[1]) + 1).nl();
  }
  out.str("# <volume holes>\n").num(n64(p.holes.size())).nl();
  for (std::size_t h = 0; h < p.holes.size(); ++h) {
    out.num(n64(h + 1)).sp();
    point(out, p.holes[h]);
    out.nl();
  }
  out.str("# <regions>: <number> <x> <y> <z> <attribute> <max volume>\n").num(n64(p.regions.size())).nl();
  for (std::size_t r = 0; r < p.regions.size(); ++r) {
    out.num(n64(r + 1)).sp();
    point(out, p.regions[r].point);
    out.sp().num(p.regions[r].attribute).sp().num(p.regions[r].max_volume).nl();
  }
  out.commit();
}

}  // namespace fdr::tetio
