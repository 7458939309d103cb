// Fan insertions of the smoothing (see smooth_fan.hpp).
#include "refine/smooth_fan.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "base/triangle_geometry.hpp"
#include "cdt/insert.hpp"
#include "cdt/locate.hpp"
#include "predicates/predicates.hpp"

namespace fdr::refine {
namespace {

using mesh::next_he;
using mesh::prev_he;

// Inserts a free vertex at p (located from triangle start) if the rules of smooth_fan.hpp allow.
bool try_insert(mesh::Triangulation& tri, const sizing::SizingField& f, const FanOptions& o, double floor_key,
                cdt::Inserter& ins, TriangleId start, Point2 p) {
  if (!std::isfinite(p.x) || !std::isfinite(p.y)) return false;
  const cdt::Location loc = cdt::locate_straight(tri, start, p, 64);
  if (loc.kind == cdt::LocateKind::kBlocked || loc.kind == cdt::LocateKind::kOnVertex ||
      (loc.kind == cdt::LocateKind::kOnEdge && tri.constrained(loc.he)))
    return false;
  if (!ins.build_cavity(p, loc)) return false;
  // The old triangles: their deficit and min angle.
  double old_deficit = 0, old_angle = 1e300;
  for (TriangleId t : ins.cavity()) {
    const Point2 a = tri.point(tri.corner(t, 0)), b = tri.point(tri.corner(t, 1)), c = tri.point(tri.corner(t, 2));
    old_deficit += 1 - geom::mean_ratio_quality(a, b, c);
    old_angle = std::min(old_angle, geom::min_angle_sin2(a, b, c));
  }
  const double fp = f(p);
  const double floor_angle = std::min(old_angle, floor_key);
  double new_deficit = 0;
  bool ok = fp > 0 && std::isfinite(fp);
  for (std::size_t k = 0; ok && k < ins.boundary().size(); ++k) {
    const HalfEdge g = ins.boundary()[k];
    const Point2 a = tri.point(tri.org(g)), b = tri.point(tri.dst(g));
    new_deficit += 1 - geom::mean_ratio_quality(a, b, p);
    if (norm2(a - p) < 0.25 * fp * fp || geom::min_angle_sin2(a, b, p) < floor_angle) ok = false;
    if (tri.constrained(g)) {
      // Not encroached, and p at least f/2 from it (so from any vertex behind it).
      if (predicates::encroaches(a, b, p)) ok = false;
      const Point2 d = b - a;
      const double t = std::clamp(dot(p - a, d) / norm2(d), 0.0, 1.0);
      if (norm2(a + t * d - p) < 0.25 * fp * fp) ok = false;
    }
    double r2 = 0;
    const Point2 cc = geom::circumcentre(a, b, p, &r2);
    const double fc = f(cc);
    if (!(fc > 0) || !std::isfinite(fc) || r2 > o.bound * o.bound * fc * fc) ok = false;
  }
  if (!ok || !(new_deficit < old_deficit)) {
    ins.abort();
    return false;
  }
  ins.commit(p, mesh::VertexKind::kFree);
  return true;
}

}  // namespace

Fan fan_of(const mesh::Triangulation& tri, Index y) {
  Fan fan;
  HalfEdge h0 = tri.vertex_edge(y);
  if (h0 == kNoId) return fan;
  // To the clockwise end of an open fan (or once round a closed one).
  for (std::size_t guard = 0; guard < 1024; ++guard) {
    const HalfEdge tw = tri.twin(h0);
    if (tw == kNoId) break;
    h0 = next_he(tw);
    if (h0 == tri.vertex_edge(y)) break;
  }
  double widest = -1;
  HalfEdge h = h0;
  for (std::size_t guard = 0; guard < 1024; ++guard) {
    const Index a = tri.dst(h), b = tri.apex(h);
    if (tri.kind(a) == mesh::VertexKind::kSuper || tri.kind(b) == mesh::VertexKind::kSuper) return {};
    const double ang = geom::angle_deg(tri.point(y), tri.point(a), tri.point(b));
    ++fan.triangles;
    fan.angle_deg += ang;
    if (ang > widest) {
      widest = ang;
      fan.widest = h;
      fan.widest_deg = ang;
    }
    const HalfEdge back = tri.twin(prev_he(h));
    if (back == kNoId || back == h0) return fan;
    h = back;
  }
  return {};
}

std::size_t insert_fan_vertices(mesh::Triangulation& tri, const sizing::SizingField& f, const FanOptions& o) {
  const double sn = std::sin(std::clamp(o.min_angle_deg, 0.0, 60.0) * geom::kRadPerDeg);
  const double floor_key = sn * sn;
  cdt::Inserter ins(tri);
  std::size_t added = 0;
  const std::size_t n = tri.num_vertices();  // the vertices added here are free: not visited
  for (Index y = 0; y < n; ++y) {
    const mesh::VertexKind kind = tri.kind(y);
    if (kind != mesh::VertexKind::kInput && kind != mesh::VertexKind::kSegment) continue;
    const Fan fan = fan_of(tri, y);
    if (fan.triangles == 0 || !(fan.widest_deg > kFanWideDeg)) continue;
    const HalfEdge h = fan.widest;
    const Point2 py = tri.point(y), pa = tri.point(tri.dst(h)), pb = tri.point(tri.apex(h));
    const double la = std::sqrt(norm2(pa - py)), lb = std::sqrt(norm2(pb - py));
    const Point2 bis = (1.0 / la) * (pa - py) + (1.0 / lb) * (pb - py);
    const double bl = std::sqrt(norm2(bis));
    if (!(bl > 0) || !std::isfinite(bl)) continue;
    for (double scale : {1.0, 0.8, 1.2}) {
      const Point2 p = py + (scale * 0.5 * (la + lb) / bl) * bis;
      if (try_insert(tri, f, o, floor_key, ins, mesh::tri_of(h), p)) {
        ++added;
        break;
      }
    }
  }
  return added;
}

}  // namespace fdr::refine
