// Small geometry helpers of the coast generalisation (convex.hpp).
#include "coast/convex.hpp"

#include <algorithm>
#include <limits>

#include "predicates/predicates.hpp"

namespace fdr::coast {

double signed_area(const std::vector<Point2>& r) {
  double a = 0;
  for (std::size_t i = 0, n = r.size(); i < n; ++i) {
    const Point2 p = r[i], q = r[(i + 1) % n];
    a += (p.x - r[0].x) * (q.y - r[0].y) - (q.x - r[0].x) * (p.y - r[0].y);
  }
  return 0.5 * a;
}

std::vector<Point2> convex_hull(std::vector<Point2> p) {
  std::sort(p.begin(), p.end(), [](Point2 a, Point2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  p.erase(std::unique(p.begin(), p.end(), [](Point2 a, Point2 b) { return a.x == b.x && a.y == b.y; }), p.end());
  if (p.size() < 3) return p;
  std::vector<Point2> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && predicates::orient2d(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && predicates::orient2d(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  return h;
}
bool segments_meet(Point2 a, Point2 b, Point2 c, Point2 d) {
  const int o1 = predicates::orient2d(a, b, c), o2 = predicates::orient2d(a, b, d);
  const int o3 = predicates::orient2d(c, d, a), o4 = predicates::orient2d(c, d, b);
  auto on = [](Point2 p, Point2 q, Point2 r) {  // r on segment pq, collinear
    return std::min(p.x, q.x) <= r.x && r.x <= std::max(p.x, q.x) && std::min(p.y, q.y) <= r.y && r.y <= std::max(p.y, q.y);
  };
  if (o1 != o2 && o3 != o4 && o1 * o2 <= 0 && o3 * o4 <= 0) return true;
  return (o1 == 0 && on(a, b, c)) || (o2 == 0 && on(a, b, d)) || (o3 == 0 && on(c, d, a)) || (o4 == 0 && on(c, d, b));
}
double segment_distance(Point2 a, Point2 b, Point2 c, Point2 d) {
  if (segments_meet(a, b, c, d)) return 0;
  return std::min({dist_to_segment(a, c, d), dist_to_segment(b, c, d), dist_to_segment(c, a, b), dist_to_segment(d, a, b)});
}

Box2 box_of(const std::vector<Point2>& pts) {
  Box2 b;
  for (Point2 q : pts) b.add(q);
  return b;
}
// p farther than r from box b (a cheap test before the exact ones).
bool beyond(Point2 p, double r, const Box2& b) {
  return p.x < b.lo.x - r || p.x > b.hi.x + r || p.y < b.lo.y - r || p.y > b.hi.y + r;
}
// Boxes a and b farther apart than r along x or y.
bool apart(const Box2& a, const Box2& b, double r) {
  return a.lo.x > b.hi.x + r || b.lo.x > a.hi.x + r || a.lo.y > b.hi.y + r || b.lo.y > a.hi.y + r;
}
bool inside_ring(Point2 p, const std::vector<Point2>& ring) {
  bool in = false;
  for (std::size_t i = 0, n = ring.size(), j = n - 1; i < n; j = i++) {
    const Point2 a = ring[i], b = ring[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x)) in = !in;
  }
  return in;
}

bool inside_convex(Point2 p, const std::vector<Point2>& h) {  // closed
  for (std::size_t i = 0; i < h.size(); ++i)
    if (predicates::orient2d(h[i], h[(i + 1) % h.size()], p) < 0) return false;
  return true;
}
// Distance from segment ab to the convex polygon h (0 when they meet).
double convex_distance(Point2 a, Point2 b, const std::vector<Point2>& h) {
  if (inside_convex(a, h) || inside_convex(b, h)) return 0;
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < h.size(); ++i) d = std::min(d, segment_distance(a, b, h[i], h[(i + 1) % h.size()]));
  return d;
}

double convex_gap(const std::vector<Point2>& a, const std::vector<Point2>& b) {
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < a.size() && d > 0; ++i) d = std::min(d, convex_distance(a[i], a[(i + 1) % a.size()], b));
  for (std::size_t i = 0; i < b.size() && d > 0; ++i) d = std::min(d, convex_distance(b[i], b[(i + 1) % b.size()], a));
  return d;
}

}  // namespace fdr::coast
