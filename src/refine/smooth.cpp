// Quality smoothing of free Steiner vertices with exact acceptance tests (see smooth.hpp).
#include "refine/smooth.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "predicates/predicates.hpp"

namespace fdr::refine {
namespace {

using mesh::next_he;
using mesh::prev_he;

constexpr double kSqrt3x4 = 6.928203230275509;  // 4 sqrt(3)

// 4 sqrt(3) area / sum of squared edges: 1 for an equilateral triangle, 0 when degenerate.
double tri_quality(Point2 a, Point2 b, Point2 c) {
  const double ar = 0.5 * ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
  const double s = norm2(b - a) + norm2(c - b) + norm2(a - c);
  return s > 0 ? kSqrt3x4 * ar / s : 0.0;
}

double min_angle_cos2_deg(Point2 a, Point2 b, Point2 c) {
  auto ang = [](Point2 p, Point2 q, Point2 r) {  // angle at p
    const Point2 u = q - p, v = r - p;
    return std::atan2(std::fabs(u.x * v.y - u.y * v.x), dot(u, v));
  };
  return std::min({ang(a, b, c), ang(b, c, a), ang(c, a, b)}) * 57.29577951308232;
}

class Smoother {
 public:
  Smoother(mesh::Triangulation& tri, const sizing::SizingField& f, const SmoothOptions& o)
      : t_(tri), f_(f), o_(o) {}

  SmoothStats run() {
    SmoothStats st;
    t_.rebuild_vertex_map();
    std::vector<Index> free;
    for (Index v = 0; v < t_.pts.size(); ++v)
      if (t_.vkind[v] == mesh::VertexKind::kFree && t_.vhe[v] != kNoId) free.push_back(v);
    st.candidates = free.size();
    for (int pass = 0; pass < o_.passes; ++pass) {
      std::size_t moved = 0;
      for (Index v : free) moved += try_vertex(v);
      st.moves += moved;
      ++st.passes;
      if (moved * 200 < free.size()) break;  // converged: under 0.5 % still moving
    }
    return st;
  }

 private:
  // The star of v: half-edges h leaving v (org(h) == v), counter-clockwise. False if the star
  // is open (v on the boundary of the mesh) or a neighbour is a super vertex.
  bool star(Index v, std::vector<HalfEdge>& hs) const {
    hs.clear();
    const HalfEdge h0 = t_.vhe[v];
    HalfEdge h = h0;
    for (std::size_t guard = 0; guard < 1024; ++guard) {
      if (t_.vkind[t_.dst(h)] == mesh::VertexKind::kSuper) return false;
      hs.push_back(h);
      const HalfEdge back = t_.twin[prev_he(h)];
      if (back == kNoId) return false;
      h = back;
      if (h == h0) return true;
    }
    return false;
  }

  bool try_vertex(Index v) {
    if (!star(v, hs_)) return false;
    const Point2 p0 = t_.pts[v];
    // Current star quality.
    double qmin = 1e300, qsum = 0, amin = 1e300;
    Point2 acc{0, 0};
    double wsum = 0;
    for (HalfEdge h : hs_) {
      const Point2 a = t_.pts[t_.dst(h)], b = t_.pts[t_.apex(h)];
      const double q = tri_quality(p0, a, b);
      qmin = std::min(qmin, q);
      qsum += q;
      amin = std::min(amin, min_angle_cos2_deg(p0, a, b));
      const double ar = 0.5 * ((a.x - p0.x) * (b.y - p0.y) - (a.y - p0.y) * (b.x - p0.x));
      const Point2 c = predicates::circumcenter(p0, a, b);
      acc = acc + ar * c;
      wsum += ar;
    }
    if (!(wsum > 0)) return false;
    const Point2 target = (1.0 / wsum) * acc;
    const double floor_angle = std::min(amin, o_.min_angle_deg);
    for (double step : {1.0, 0.5, 0.25}) {
      const Point2 p = p0 + step * (target - p0);
      if (p == p0 || !std::isfinite(p.x) || !std::isfinite(p.y)) return false;
      if (acceptable(p, qmin, qsum, floor_angle)) {
        t_.pts[v] = p;
        return true;
      }
    }
    return false;
  }

  bool acceptable(Point2 p, double qmin, double qsum, double floor_angle) const {
    double nmin = 1e300, nsum = 0;
    for (HalfEdge h : hs_) {
      const Index ia = t_.dst(h), ib = t_.apex(h);
      const Point2 a = t_.pts[ia], b = t_.pts[ib];
      if (predicates::orient2d(p, a, b) <= 0) return false;
      const double q = tri_quality(p, a, b);
      nmin = std::min(nmin, q);
      nsum += q;
      if (min_angle_cos2_deg(p, a, b) < floor_angle) return false;
    }
    if (nmin < qmin || !(nsum > qsum)) return false;
    for (HalfEdge h : hs_) {
      const Index ia = t_.dst(h), ib = t_.apex(h);
      const Point2 a = t_.pts[ia], b = t_.pts[ib];
      // Link edge a-b: the triangle across it must not have its apex inside circle(p, a, b),
      // and a constrained link edge must not be encroached by p.
      const HalfEdge link = next_he(h);  // a -> b
      if (t_.constrained(link)) {
        if (predicates::encroaches(a, b, p)) return false;
      } else {
        const HalfEdge tw = t_.twin[link];
        if (tw != kNoId) {
          const Point2 d = t_.pts[t_.apex(tw)];
          if (predicates::incircle(p, a, b, d) > 0) return false;
        }
      }
      // Spoke p-a (between this triangle and the previous one around p): the previous
      // triangle's far vertex must not be inside circle(p, a, b). Spokes are never constrained
      // (v is a free vertex), but check: a constrained spoke could not move anyway.
      const HalfEdge prev_t = t_.twin[h];  // a -> p in the neighbouring triangle
      if (prev_t != kNoId) {
        const Point2 z = t_.pts[t_.apex(prev_t)];
        if (predicates::incircle(p, a, b, z) > 0) return false;
      }
      // FDR bound on the moved triangle.
      double r2 = 0;
      const Point2 c = predicates::circumcenter(p, a, b, &r2);
      const double fc = f_(c);
      if (!(fc > 0) || !std::isfinite(fc)) return false;
      if (r2 > o_.bound * o_.bound * fc * fc) return false;
    }
    return true;
  }

  mesh::Triangulation& t_;
  const sizing::SizingField& f_;
  SmoothOptions o_;
  std::vector<HalfEdge> hs_;
};

}  // namespace

SmoothStats smooth(mesh::Triangulation& tri, const sizing::SizingField& f, const SmoothOptions& options) {
  Smoother s(tri, f, options);
  return s.run();
}

}  // namespace fdr::refine
