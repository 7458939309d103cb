// A global mesh measured on the sphere (global_measure.hpp).
#include "gis/global_measure.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <unordered_map>

#include "base/error.hpp"

namespace fdr::gis {

namespace {

constexpr double kGravity = 9.81;

std::uint64_t edge_key(Index a, Index b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint64_t>(b);
}

// Smallest angle (degrees) of the chord triangle abc (points in R^3).
double min_angle_deg(Point3 a, Point3 b, Point3 c) {
  auto angle = [](Point3 p, Point3 q, Point3 r) {
    const Point3 u = q - p, v = r - p;
    return std::atan2(std::sqrt(norm2(cross(u, v))), dot(u, v));
  };
  return std::min({angle(a, b, c), angle(b, c, a), angle(c, a, b)}) * 180.0 / std::numbers::pi;
}

}  // namespace

SphereMeasure measure_on_sphere(const SphereMeshInput& in) {
  if (!in.vertices || !in.triangles || !in.proj) throw Error(ExitCode::kInternal, "measure_on_sphere: missing input");
  const auto& V = *in.vertices;
  const auto& T = *in.triangles;
  const double R = in.proj->radius();
  std::vector<Point3> u(V.size());
  for (std::size_t i = 0; i < V.size(); ++i) u[i] = unit_vector(in.proj->inverse(V[i]));
  SphereMeasure s;
  s.triangles = T.size();
  s.shortest_edge_m = std::numeric_limits<double>::infinity();
  s.dt_s = std::numeric_limits<double>::infinity();
  std::unordered_map<std::uint64_t, std::uint32_t> uses;
  uses.reserve(T.size() * 2);
  double sum_edges = 0, sum_q = 0;
  for (const auto& t : T) {
    const Point3 a = u[t[0]], b = u[t[1]], c = u[t[2]];
    const double area = spherical_triangle_area(a, b, c, R);
    if (area <= 0) ++s.negative_triangles;
    s.area_m2 += area;
    std::array<double, 3> len{};
    for (int k = 0; k < 3; ++k) {
      const Index p = t[k], q = t[(k + 1) % 3];
      len[k] = great_circle(u[p], u[q], R);
      if (++uses[edge_key(p, q)] == 1) {
        ++s.edges;
        sum_edges += len[k];
        s.shortest_edge_m = std::min(s.shortest_edge_m, len[k]);
        s.longest_edge_m = std::max(s.longest_edge_m, len[k]);
        if (in.hmin > 0 && len[k] < 0.1 * in.hmin) ++s.edges_below_tenth_hmin;
      }
    }
    const Point3 A = R * a, B = R * b, C = R * c;
    const double ang = min_angle_deg(A, B, C);
    s.min_angle_deg = std::min(s.min_angle_deg, ang);
    if (ang < 30) ++s.below_30_deg;
    const double chord_area = 0.5 * std::sqrt(norm2(cross(B - A, C - A)));
    sum_q += 4 * std::sqrt(3.0) * chord_area / (norm2(B - A) + norm2(C - B) + norm2(A - C));
    if (in.f_ground) {
      const Point3 cc = spherical_circumcentre(a, b, c);
      const double r = great_circle(cc, a, R);
      const LonLat ll = to_lonlat(cc);
      const double ratio = r / in.f_ground->sample(ll);
      if (ratio > s.max_r_over_f) { s.max_r_over_f = ratio; s.max_r_over_f_at = ll; }
      if (ratio > in.bound) ++s.r_over_f_above_bound;
    }
    if (in.z && !in.z->empty()) {
      const double zm = ((*in.z)[t[0]] + (*in.z)[t[1]] + (*in.z)[t[2]]) / 3.0;
      const double depth = std::max(-zm, in.min_depth_m);
      const double h = 2 * std::fabs(area) / std::max({len[0], len[1], len[2]});
      const double dt = h / std::sqrt(kGravity * depth);
      if (dt < s.dt_s) { s.dt_s = dt; s.dt_at = to_lonlat((1.0 / 3.0) * (a + b + c)); }
    }
  }
  if (!T.empty()) {
    s.mean_edge_m = sum_edges / static_cast<double>(s.edges);
    s.mean_quality = sum_q / static_cast<double>(T.size());
  }
  if (!std::isfinite(s.dt_s)) s.dt_s = 0;
  std::unordered_map<std::uint64_t, char> coast;
  if (in.coast_edges)
    for (const auto& [a, b] : *in.coast_edges) coast[edge_key(a, b)] = 1;
  for (const auto& [k, n] : uses) {
    if (n > 2) ++s.edges_over_two;
    if (n == 1) {
      ++s.boundary_edges;
      if (!coast.count(k)) ++s.boundary_edges_not_coast;
    }
  }
  return s;
}

std::vector<std::pair<std::string, double>> sphere_figures(const SphereMeasure& s) {
  return {{"sphere_triangles", static_cast<double>(s.triangles)},
          {"sphere_edges", static_cast<double>(s.edges)},
          {"sphere_shortest_edge_m", s.shortest_edge_m},
          {"sphere_mean_edge_m", s.mean_edge_m},
          {"sphere_longest_edge_m", s.longest_edge_m},
          {"sphere_edges_below_tenth_hmin", static_cast<double>(s.edges_below_tenth_hmin)},
          {"sphere_area_m2", s.area_m2},
          {"sphere_negative_triangles", static_cast<double>(s.negative_triangles)},
          {"sphere_max_r_over_f", s.max_r_over_f},
          {"sphere_max_r_over_f_lon", s.max_r_over_f_at.lon_deg},
          {"sphere_max_r_over_f_lat", s.max_r_over_f_at.lat_deg},
          {"sphere_r_over_f_above_bound", static_cast<double>(s.r_over_f_above_bound)},
          {"sphere_min_angle_deg", s.min_angle_deg},
          {"sphere_triangles_below_30_deg", static_cast<double>(s.below_30_deg)},
          {"sphere_mean_quality", s.mean_quality},
          {"sphere_dt_s", s.dt_s},
          {"sphere_dt_lon", s.dt_at.lon_deg},
          {"sphere_dt_lat", s.dt_at.lat_deg},
          {"sphere_boundary_edges", static_cast<double>(s.boundary_edges)},
          {"sphere_boundary_edges_not_coast", static_cast<double>(s.boundary_edges_not_coast)},
          {"sphere_edges_over_two_triangles", static_cast<double>(s.edges_over_two)}};
}

}  // namespace fdr::gis
