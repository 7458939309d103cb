// Basic value types shared by every module: points, boxes, typed ids.
#pragma once
#include <cstdint>
#include <limits>
#include <cmath>
#include <algorithm>

namespace fdr {

#if defined(FDR_64BIT_IDS)
using Index = std::uint64_t;
#else
using Index = std::uint32_t;
#endif
using VertexId = Index;    // index into a vertex array
using TriangleId = Index;  // index into a triangle array
using HalfEdge = Index;    // 3*t + k: edge k of triangle t (from vertex k to vertex k+1 mod 3)
inline constexpr Index kNoId = std::numeric_limits<Index>::max();

// A point in the local projected frame (metres, shifted to the domain's origin).
struct Point2 {
  double x = 0, y = 0;
  friend bool operator==(const Point2&, const Point2&) = default;
};
inline Point2 operator+(Point2 a, Point2 b) { return {a.x + b.x, a.y + b.y}; }
inline Point2 operator-(Point2 a, Point2 b) { return {a.x - b.x, a.y - b.y}; }
inline Point2 operator*(double s, Point2 a) { return {s * a.x, s * a.y}; }
inline double dot(Point2 a, Point2 b) { return a.x * b.x + a.y * b.y; }
inline double norm2(Point2 a) { return a.x * a.x + a.y * a.y; }
inline double dist(Point2 a, Point2 b) { return std::sqrt(norm2(a - b)); }
// Distance from p to the closed segment ab (a measurement for tolerances and reports, never a
// topological decision).
inline double dist_to_segment(Point2 p, Point2 a, Point2 b) {
  const Point2 d = b - a;
  const double l2 = norm2(d);
  const double t = l2 > 0 ? std::clamp(dot(p - a, d) / l2, 0.0, 1.0) : 0.0;
  return dist(p, a + t * d);
}

// Geographic coordinates in degrees; deliberately a different type from Point2.
struct LonLat {
  double lon_deg = 0, lat_deg = 0;
};

struct Box2 {
  Point2 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  Point2 hi{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  void add(Point2 p) {
    lo.x = std::min(lo.x, p.x); lo.y = std::min(lo.y, p.y);
    hi.x = std::max(hi.x, p.x); hi.y = std::max(hi.y, p.y);
  }
  bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y); }
  double width() const { return hi.x - lo.x; }
  double height() const { return hi.y - lo.y; }
  Point2 center() const { return {0.5 * (lo.x + hi.x), 0.5 * (lo.y + hi.y)}; }
  bool contains(Point2 p) const { return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y; }
};

}  // namespace fdr
