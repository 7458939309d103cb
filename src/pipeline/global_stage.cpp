// The --global stages: spacing on the sphere, depths in lon/lat, the mesh measured on the sphere.
#include "pipeline/global_stage.hpp"

#include <cmath>
#include <numbers>
#include "base/error.hpp"
#include "base/num_format.hpp"
#include "gis/global_coast.hpp"
#include "gis/global_measure.hpp"

namespace fdr::pipeline {
namespace {

// Coast points (unit vectors) along every land and island segment, at most half a grid cell
// apart on the ground, for the distance to shore.
std::vector<Point3> shore_points(const pslg::Pslg& raw, const gis::SphereStereo& proj, double step_m) {
  std::vector<Point3> out;
  for (const auto& s : raw.segments) {
    if (s.marker != static_cast<int>(EdgeKind::kLand) && s.marker != static_cast<int>(EdgeKind::kIsland)) continue;
    const Point2 a = raw.points[s.a], b = raw.points[s.b];
    const Point3 ua = gis::unit_vector(proj.inverse(a)), ub = gis::unit_vector(proj.inverse(b));
    const double len = gis::great_circle(ua, ub, proj.radius());
    const int n = static_cast<int>(std::min(1e4, std::ceil(len / step_m)));
    out.push_back(ua);
    for (int k = 1; k < n; ++k) out.push_back(gis::unit_vector(proj.inverse(a + (static_cast<double>(k) / n) * (b - a))));
  }
  return out;
}

}  // namespace

void add_sphere_coast_deviation(const mesh::MeshView& m, const std::vector<std::pair<Point2, Point2>>& input_boundary,
                                const gis::SphereStereo& proj, double hmin, const LogFn& log,
                                std::vector<std::pair<std::string, double>>& out) {
  auto unit = [&](Point2 local) { return gis::unit_vector(proj.inverse(m.origin + local)); };
  std::vector<gis::SphereArc> input, mesh;
  input.reserve(input_boundary.size());
  for (const auto& [a, b] : input_boundary) input.push_back({unit(a), unit(b)});
  for (const auto& e : m.edges)
    if (e.marker == static_cast<int>(EdgeKind::kLand) || e.marker == static_cast<int>(EdgeKind::kIsland))
      mesh.push_back({unit(m.vertices[e.a]), unit(m.vertices[e.b])});
  if (input.empty() || mesh.empty()) return;
  const gis::SphereDeviation in_mesh = gis::sphere_deviation(input, mesh, 0.5 * hmin, proj.radius());
  const gis::SphereDeviation mesh_in = gis::sphere_deviation(mesh, input, 0.5 * hmin, proj.radius());
  // The same as the regional yardstick: input rings without a vertex within 2 hmin of the mesh
  // coast (islands the generalisation removed, listed in the repairs) left out and counted.
  std::size_t lost = 0;
  const gis::SphereDeviation in_kept = gis::sphere_deviation_kept(input, mesh, 0.5 * hmin, 2 * hmin, &lost, proj.radius());
  out.push_back({"sphere_coast_input_to_mesh_max_m", in_mesh.max_m});
  out.push_back({"sphere_coast_input_to_mesh_p99_m", in_mesh.p99_m});
  out.push_back({"sphere_coast_input_to_mesh_max_lon", in_mesh.max_at.lon_deg});
  out.push_back({"sphere_coast_input_to_mesh_max_lat", in_mesh.max_at.lat_deg});
  out.push_back({"sphere_coast_input_to_mesh_kept_max_m", in_kept.max_m});
  out.push_back({"sphere_coast_input_to_mesh_kept_p99_m", in_kept.p99_m});
  out.push_back({"sphere_coast_input_rings_without_counterpart", static_cast<double>(lost)});
  out.push_back({"sphere_coast_mesh_to_input_max_m", mesh_in.max_m});
  out.push_back({"sphere_coast_mesh_to_input_p99_m", mesh_in.p99_m});
  out.push_back({"sphere_coast_mesh_to_input_max_lon", mesh_in.max_at.lon_deg});
  out.push_back({"sphere_coast_mesh_to_input_max_lat", mesh_in.max_at.lat_deg});
  if (log)
    log(LogLevel::kInfo, "coast deviation on the sphere: input -> mesh p99 " + num6(in_mesh.p99_m) + " m, max " +
                             num6(in_mesh.max_m) + " m at (" + num6(in_mesh.max_at.lon_deg) + ", " +
                             num6(in_mesh.max_at.lat_deg) + "), rings with a counterpart p99 " + num6(in_kept.p99_m) +
                             " m, max " + num6(in_kept.max_m) + " m (" + std::to_string(lost) +
                             " rings without); mesh -> input p99 " + num6(mesh_in.p99_m) + " m, max " +
                             num6(mesh_in.max_m) + " m (" + std::to_string(in_mesh.samples) + " and " +
                             std::to_string(mesh_in.samples) + " samples)");
}

std::vector<Point3> sphere_points(const mesh::MeshView& m, const gis::SphereStereo& proj) {
  std::vector<Point3> out(m.vertices.size());
  for (std::size_t i = 0; i < out.size(); ++i)
    out[i] = gis::sphere_xyz(proj.inverse(m.world(static_cast<Index>(i))), proj.radius());
  return out;
}

GisSpacing global_spacing(const Options& opt, const gis::GisInput& g, StageClock& clock, const LogFn& log) {
  auto info = [&](const std::string& s) { if (log) log(LogLevel::kInfo, s); };
  const gis::SphereStereo proj(opt.pole ? LonLat{(*opt.pole)[0], (*opt.pole)[1]} : LonLat{0, -90});
  gis::SphereRules r;
  r.hmin = *opt.hmin;
  r.hmax = *opt.hmax;
  r.dist_grade = opt.dist_grade;
  r.slope = opt.slope_rule;
  r.wavelength = opt.wavelength_rule;
  r.wave_period_s = opt.wave_period_s;
  r.gradation = opt.gradation;
  if (opt.cell_size) r.cell_deg = *opt.cell_size / (gis::kEarthRadius * std::numbers::pi / 180.0);
  GisSpacing sp;
  if (!opt.raster.empty()) {
    sp.lonlat_dem = std::make_shared<const gis::LonLatRaster>(gis::read_lonlat_raster(opt.raster));
    clock.lap("raster");
    info("raster " + opt.raster + ": " + std::to_string(sp.lonlat_dem->nx) + " x " + std::to_string(sp.lonlat_dem->ny) +
         " cells of " + num6(sp.lonlat_dem->dx) + " deg (lon/lat)");
  }
  // The southmost latitude of the domain and its farthest point from the projection centre.
  double lat_min = 90, rho_max = 0;
  for (const Point2& p : g.raw.points) {
    lat_min = std::min(lat_min, proj.inverse(p).lat_deg);
    rho_max = std::max(rho_max, std::hypot(p.x, p.y));
  }
  const double cell_m = (r.cell_deg > 0 ? r.cell_deg : gis::default_cell_deg(r.hmin)) * gis::kEarthRadius * std::numbers::pi / 180.0;
  const std::vector<Point3> shore = shore_points(g.raw, proj, 0.5 * cell_m);
  std::string desc;
  auto grid = std::make_shared<const gis::LonLatGrid>(gis::sphere_spacing(r, lat_min, shore, sp.lonlat_dem.get(), &desc));
  clock.lap("sizing");
  info("spacing: " + desc + " (" + std::to_string(shore.size()) + " shore points)");
  sp.sphere_f = std::make_shared<const gis::StereoSpacing>(grid, proj, r.gradation, rho_max, opt.bound, desc);
  sp.f = sp.sphere_f;
  sp.hmin = r.hmin;
  const double kmax = proj.scale({rho_max, 0});
  sp.kdev = kmax - 1;
  info("projection scale factor (exact, 1 + rho^2 / 4R^2): 1 to " + num6(kmax) + " over the domain; plane Lipschitz "
       "bound of f " + num6(sp.sphere_f->lipschitz()));
  return sp;
}

std::vector<double> global_depths(const mesh::MeshView& m, const PreparedInput& in) {
  std::vector<double> z(m.vertices.size());
  const gis::SphereStereo& proj = in.sphere_f->projection();
  for (std::size_t i = 0; i < z.size(); ++i) z[i] = in.lonlat_dem->sample(proj.inverse(m.world(static_cast<Index>(i))));
  return z;
}

void add_sphere_figures(const mesh::MeshView& m, const GisSpacing& sp, double bound, double hmin, double min_depth_m,
                        const LogFn& log, std::vector<std::pair<std::string, double>>& out) {
  std::vector<std::pair<Index, Index>> coast;
  for (const auto& e : m.edges)
    if (e.marker == static_cast<int>(EdgeKind::kLand) || e.marker == static_cast<int>(EdgeKind::kIsland))
      coast.push_back({e.a, e.b});
  std::vector<Point2> world(m.vertices.size());
  for (std::size_t i = 0; i < world.size(); ++i) world[i] = m.world(static_cast<Index>(i));
  gis::SphereMeshInput in;
  in.vertices = &world;
  in.triangles = &m.triangles;
  in.coast_edges = &coast;
  in.z = &m.z;
  in.proj = &sp.sphere_f->projection();
  in.f_ground = &sp.sphere_f->ground();
  in.bound = bound;
  in.hmin = hmin;
  in.min_depth_m = min_depth_m;
  const gis::SphereMeasure s = gis::measure_on_sphere(in);
  for (auto& row : gis::sphere_figures(s)) out.push_back(std::move(row));
  if (log)
    log(LogLevel::kInfo,
        "on the sphere: " + std::to_string(s.triangles) + " triangles, edges " + num6(s.shortest_edge_m) + " to " +
            num6(s.longest_edge_m) + " m (mean " + num6(s.mean_edge_m) + "), area " + num6(s.area_m2 / 1e6) +
            " km^2, max R/f " + num6(s.max_r_over_f) + " (" + std::to_string(s.r_over_f_above_bound) +
            " above B), min angle " + num6(s.min_angle_deg) + " deg, mean quality " + num6(s.mean_quality) +
            ", dt " + num6(s.dt_s) + " s; " + (s.closed() ? "closed" : "NOT closed") + " (" +
            std::to_string(s.boundary_edges) + " coast edges, " + std::to_string(s.boundary_edges_not_coast) +
            " other boundary edges, " + std::to_string(s.edges_over_two) + " edges of 3+ triangles)");
}

void attach_sphere(PreparedInput& out, const GisSpacing& sp, const Options& opt, const LogFn& log) {
  out.sphere_f = sp.sphere_f;
  out.lonlat_dem = sp.lonlat_dem;
  out.metadata.push_back({"sphere_radius_m", std::to_string(gis::kEarthRadius)});
  out.sphere_figures = [sp, bound = opt.bound, md = opt.min_depth_m, log](const mesh::MeshView& m, const auto& coast,
                                                                           auto& figs) {
    add_sphere_figures(m, sp, bound, sp.hmin, md, log, figs);
    add_sphere_coast_deviation(m, coast, sp.sphere_f->projection(), sp.hmin, log, figs);
  };
  out.sphere_radius = sp.sphere_f->projection().radius();
  out.sphere_xyz = [sp](const mesh::MeshView& m) { return sphere_points(m, sp.sphere_f->projection()); };
}

}  // namespace fdr::pipeline
