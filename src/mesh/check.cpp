// Validity checkers: topology, orientation, constrained Delaunay property, segment recovery.
#include "mesh/check.hpp"
#include <cmath>
#include <sstream>
#include <unordered_map>
#include "base/triangle_geometry.hpp"
#include "predicates/predicates.hpp"

namespace fdr::mesh {
namespace {
std::string fmt_pt(Point2 p) {
  std::ostringstream s;
  s.precision(17);
  s << "(" << p.x << ", " << p.y << ")";
  return s.str();
}
}  // namespace

CheckResult check_topology(const Triangulation& tri) {
  CheckResult r;
  const std::size_t nv = tri.num_vertices();
  for (TriangleId t = 0; t < tri.num_slots(); ++t) {
    if (tri.dead(t)) continue;
    for (int k = 0; k < 3; ++k) {
      const HalfEdge h = 3 * t + k;
      if (tri.org(h) >= nv) { r.add("triangle " + std::to_string(t) + " has an invalid vertex id"); continue; }
      const HalfEdge w = tri.twin(h);
      if (w == kNoId) continue;
      if (w >= 3 * tri.num_slots() || tri.dead(tri_of(w))) {
        r.add("half-edge " + std::to_string(h) + " points to a dead or invalid twin");
        continue;
      }
      if (tri.twin(w) != h) r.add("twin asymmetry at half-edge " + std::to_string(h));
      if (tri.org(w) != tri.dst(h) || tri.dst(w) != tri.org(h))
        r.add("twin endpoints mismatch at half-edge " + std::to_string(h));
      if (tri.constrained(w) != tri.constrained(h))
        r.add("constraint bit asymmetric at half-edge " + std::to_string(h));
    }
    const Point2 a = tri.point(tri.corner(t, 0)), b = tri.point(tri.corner(t, 1)), c = tri.point(tri.corner(t, 2));
    if (predicates::orient2d(a, b, c) <= 0)
      r.add("triangle " + std::to_string(t) + " is not counter-clockwise: " + fmt_pt(a) + " " + fmt_pt(b) + " " + fmt_pt(c));
  }
  return r;
}

CheckResult check_delaunay(const Triangulation& tri) {
  CheckResult r;
  for (TriangleId t = 0; t < tri.num_slots(); ++t) {
    if (tri.dead(t)) continue;
    for (int k = 0; k < 3; ++k) {
      const HalfEdge h = 3 * t + k;
      const HalfEdge w = tri.twin(h);
      if (w == kNoId || w < h || tri.constrained(h)) continue;
      const Point2 a = tri.point(tri.corner(t, 0)), b = tri.point(tri.corner(t, 1)), c = tri.point(tri.corner(t, 2));
      const Point2 d = tri.point(tri.apex(w));
      if (predicates::incircle(a, b, c, d) > 0)
        r.add("edge " + fmt_pt(tri.point(tri.org(h))) + "-" + fmt_pt(tri.point(tri.dst(h))) + " is not locally Delaunay");
    }
  }
  return r;
}

CheckResult check_segments(const Triangulation& tri) {
  CheckResult r;
  // Constrained edges by input segment, from every live half-edge (robust to pinched vertices).
  std::unordered_map<Index, std::vector<std::pair<Index, Index>>> by_seg;
  for (TriangleId t = 0; t < tri.num_slots(); ++t) {
    if (tri.dead(t)) continue;
    for (int k = 0; k < 3; ++k) {
      const HalfEdge h = 3 * t + static_cast<Index>(k);
      if (!tri.constrained(h)) continue;
      const Index s = tri.segment_of(tri.org(h), tri.dst(h));
      if (s == kNoId) continue;
      by_seg[s].push_back({tri.org(h), tri.dst(h)});
    }
  }
  std::vector<bool> in_mesh(tri.num_vertices(), false);
  for (TriangleId t = 0; t < tri.num_slots(); ++t)
    if (!tri.dead(t))
      for (int k = 0; k < 3; ++k) in_mesh[tri.corner(t, k)] = true;
  for (Index s = 0; s < tri.input_segments().size(); ++s) {
    const auto& seg = tri.input_segments()[s];
    if (seg.a == seg.b || !in_mesh[seg.a] || !in_mesh[seg.b]) continue;  // removed with a hole
    std::unordered_map<Index, std::vector<Index>> adj;
    for (const auto& [u, w] : by_seg[s]) {
      adj[u].push_back(w);
      adj[w].push_back(u);
    }
    // Follow the chain from a; each step must reach a new vertex, ending at b.
    Index cur = seg.a, prev = kNoId;
    bool ok = true;
    for (std::size_t steps = 0; cur != seg.b; ++steps) {
      Index nxt = kNoId;
      for (Index w : adj[cur])
        if (w != prev) { nxt = w; break; }
      if (nxt == kNoId || steps > adj.size()) { ok = false; break; }
      prev = cur;
      cur = nxt;
    }
    if (!ok)
      r.add("input segment " + std::to_string(s) + " " + fmt_pt(tri.point(seg.a)) + "-" + fmt_pt(tri.point(seg.b)) +
            " is not a chain of mesh edges");
  }
  return r;
}

CheckResult check_spacing(const Triangulation& tri, const std::function<double(Point2)>& f, double bound) {
  CheckResult r;
  for (TriangleId t = 0; t < tri.num_slots(); ++t) {
    if (tri.dead(t)) continue;
    const Point2 a = tri.point(tri.corner(t, 0)), b = tri.point(tri.corner(t, 1)), c = tri.point(tri.corner(t, 2));
    double r2 = 0;
    const Point2 cc = geom::circumcentre(a, b, c, &r2);
    const double fc = f(cc);
    if (!(fc > 0) || r2 > bound * bound * fc * fc) {
      std::ostringstream s;
      s.precision(6);
      s << "triangle " << t << " has R/f(c) = " << std::sqrt(r2) / fc << " > B = " << bound << " at " << fmt_pt(cc);
      r.add(s.str());
    }
  }
  return r;
}

CheckResult check_all(const Triangulation& tri) {
  CheckResult r = check_topology(tri);
  for (auto* part : {&check_delaunay, &check_segments}) {
    if (!r.ok() && part == &check_delaunay) break;  // geometry checks need sane topology
    CheckResult q = part(tri);
    r.count += q.count;
    for (auto& p : q.problems) if (r.problems.size() < 20) r.problems.push_back(p);
  }
  return r;
}

}  // namespace fdr::mesh
