// The run's plan (plan.hpp): usage checks before any I/O and each stage's parameters.
#include "pipeline/plan.hpp"
#include <algorithm>
#include <cmath>
#include "base/error.hpp"
#include "base/path_util.hpp"
#include "io/write_many.hpp"
#include "pipeline/pipeline.hpp"
#include "pipeline/run3d.hpp"

namespace fdr::pipeline {
namespace {
// --frontal's default for GIS inputs (.poly inputs: 0, the paper's circumcentre rule). Why 0.75:
// the triangles made on the front are then about as large as the circumcentre rule's on average
// (a few per cent more triangles), with a mean quality well above it; 0.8 gives a few per cent
// fewer triangles and a little less quality.
constexpr double kGisFrontalRadius = 0.75;

// --global: land without an extent, explicit hmin and hmax (the plane's box says nothing about
// the sphere's sizes), the spacing rules that are evaluated on the sphere.
void check_global_options(const Options& opt) {
  if (opt.pole && !opt.global) throw Error(ExitCode::kUsage, "--pole needs --global");
  if (!opt.global) return;
  if (opt.land.empty() || !opt.input.empty() || opt.extent)
    throw Error(ExitCode::kUsage, "--global takes --land LAND and neither INPUT nor --extent");
  if (!opt.hmin || !opt.hmax) throw Error(ExitCode::kUsage, "--global needs --hmin and --hmax (metres on the sphere)");
  if (!opt.size_raster.empty() || opt.vertical_tol || !opt.spacing.empty() || !opt.write_spacing.empty())
    throw Error(ExitCode::kUsage, "--global spacing: --hmin, --hmax, --dist-grade, --slope-rule, --wavelength-rule and "
                                  "--gradation only (no --size-raster, --vertical-tol, --spacing, --write-spacing)");
  if (!opt.open_boundary.empty() || !opt.breaklines.empty() || !opt.points.empty())
    throw Error(ExitCode::kUsage, "--global takes no --open-boundary, --breaklines or --points");
}

// GIS options that need another option (checked again where they are used).
void check_gis_options(const Options& opt) {
  if (!opt.land.empty() && !opt.extent && !opt.global)
    throw Error(ExitCode::kUsage, "--land needs --extent XMIN,YMIN,XMAX,YMAX (or --global)");
  check_global_options(opt);
  check_layer_options(opt);
  auto negative = [](const std::optional<double>& v) { return v && !(*v >= 0); };
  if (negative(opt.close_width) || negative(opt.min_feature) || negative(opt.min_island_factor))
    throw Error(ExitCode::kUsage, "--close-width, --min-feature and --min-island must be >= 0");
  if (opt.slope_rule && opt.raster.empty()) throw Error(ExitCode::kUsage, "--slope-rule needs --raster");
  if (opt.wavelength_rule && opt.raster.empty()) throw Error(ExitCode::kUsage, "--wavelength-rule needs --raster");
  if (opt.vertical_tol && opt.raster.empty()) throw Error(ExitCode::kUsage, "--vertical-tol needs --raster (the DEM)");
  const bool any_rule = opt.dist_grade || opt.slope_rule || opt.wavelength_rule || opt.vertical_tol ||
                        !opt.size_raster.empty();
  const bool spacing_grid = !opt.raster.empty() || any_rule || opt.spacing.empty();
  if (spacing_grid && !(opt.gradation > 0)) throw Error(ExitCode::kUsage, "--gradation must be positive");
  if (!(opt.densify_deg >= 0 && opt.densify_deg <= 90))
    throw Error(ExitCode::kUsage, "--densify must be between 0 (off) and 90 degrees");
  if (!opt.keep_coast && !(opt.coast_tol >= 0)) throw Error(ExitCode::kUsage, "--coast-tol must be >= 0");
  if (!opt.write_spacing.empty() && !spacing_grid)
    throw Error(ExitCode::kUsage, "--write-spacing needs a raster-based spacing (give --raster or a rule)");
}

MeasureParams measure_params(const Options& opt, const Plan& p, const std::vector<io::Format>& formats) {
  MeasureParams m;
  m.gis = p.gis;
  m.tin_error = opt.vertical_tol.has_value();
  m.min_depth_m = opt.min_depth_m;
  m.triangulate = p.triangulate;
  m.keep_adjacency = std::any_of(formats.begin(), formats.end(), io::carries_boundaries);
  m.vertex_f = std::find(formats.begin(), formats.end(), io::Format::kNode) != formats.end();
  return m;
}

WriteParams write_params(const Options& opt, const Plan& p, std::vector<io::Format> formats) {
  WriteParams w;
  w.gis = p.gis;
  w.outputs = opt.outputs;
  w.formats = std::move(formats);
  w.output_crs = output_crs_of(opt);
  w.write_spacing = opt.write_spacing;
  w.report_json = opt.report_json;
  w.source = p.source;
  w.command_line = opt.command_line;
  w.bound = opt.bound;
  w.min_angle_deg = p.triangulate.min_angle_deg;
  w.slf_double = opt.slf_double;
  w.postgis = {opt.pg_prefix, opt.pg_schema, opt.pg_overwrite};
  if (!opt.telemac_open.empty()) w.telemac_codes = io::parse_telemac_codes(opt.telemac_open);
  return w;
}

}  // namespace

void check_layer_options(const Options& opt) {
  if (opt.open_boundary.empty() && !opt.open_boundary_layer.empty())
    throw Error(ExitCode::kUsage, "--open-boundary-layer needs --open-boundary FILE");
  if (opt.breaklines.empty() && !opt.breaklines_layer.empty())
    throw Error(ExitCode::kUsage, "--breaklines-layer needs --breaklines FILE");
  if (opt.points.empty() && !opt.points_layer.empty())
    throw Error(ExitCode::kUsage, "--points-layer needs --points FILE");
}

std::string output_crs_of(const Options& opt) {
  return opt.output_crs.empty() && opt.global ? std::string("EPSG:4326") : opt.output_crs;
}

bool is_poly_input(const std::string& path) {
  const std::string e = lower_ext(path);
  return e == "poly" || e == "node";
}

bool report_is_read(const Options& opt, const std::vector<io::Format>& formats) {
  if (!opt.report_only_if_read || !opt.quiet || !opt.report_json.empty()) return true;
  return stores_triangle_values(formats) || stores_metadata(formats);
}

Plan plan_run(const Options& opt) {
  if (!opt.dem.empty())
    throw Error(ExitCode::kUsage, "--dem makes a terrain volume: a 3D run (pipeline::run3d), not a 2D mesh");
  check_no_terrain_options(opt);
  Plan p;
  if (opt.input.empty() && opt.land.empty())
    throw Error(ExitCode::kUsage, "no input given: INPUT (a .poly/.node file or water polygons) or --land with --extent");
  p.source = !opt.input.empty() ? opt.input : opt.land;
  p.gis = !is_poly_input(opt.input);
  if (!(opt.bound > 0) || !std::isfinite(opt.bound)) throw Error(ExitCode::kUsage, "--bound must be a positive number");
  if (opt.min_angle_deg >= 60 || std::isnan(opt.min_angle_deg)) throw Error(ExitCode::kUsage, "--min-angle must be in [0, 60)");
  if (opt.smooth_passes > 100) throw Error(ExitCode::kUsage, "--smooth must be in [0, 100]");
  if (!(opt.frontal_radius < 1) || std::isnan(opt.frontal_radius)) throw Error(ExitCode::kUsage, "--frontal must be in [0, 1)");
  if (opt.no_sliver_removal || opt.sliver_angle_deg)
    throw Error(ExitCode::kUsage, std::string(opt.no_sliver_removal ? "--no-sliver-removal" : "--sliver-angle") +
                                      " applies to 3D runs only; " + p.source + " is a 2D input");
  // Model-ready defaults for GIS inputs: a 30 degree angle bound and smoothing.
  TriangulateOptions& t = p.triangulate;
  t.bound = opt.bound;
  t.min_angle_deg = opt.min_angle_deg >= 0 ? opt.min_angle_deg : (p.gis ? 30.0 : 0.0);
  t.angle_split_min_f = p.gis ? 0.5 : 0.0;
  t.smooth_passes = opt.smooth_passes >= 0 ? opt.smooth_passes : (p.gis ? 4 : 0);
  t.frontal_radius = opt.frontal_radius >= 0 ? opt.frontal_radius : (p.gis ? kGisFrontalRadius : 0.0);
  t.max_steiner = opt.max_steiner;
  t.check = opt.check;
  t.source = p.source;
  // Output formats: a bad -o fails before any work.
  std::vector<io::Format> formats;
  for (const auto& o : opt.outputs) formats.push_back(io::format_from_path(o, opt.of));
  if (!opt.telemac_open.empty()) io::parse_telemac_codes(opt.telemac_open);  // a bad value fails here
  for (std::size_t i = 0; i < formats.size(); ++i)
    if (formats[i] == io::Format::kLl && !p.gis)
      throw Error(ExitCode::kUsage, opt.outputs[i] + ": hgrid.ll needs lon/lat, but a .poly/.node input has no CRS; "
                                                     "write .gr3 instead or mesh from GIS layers");
  if (p.gis) check_gis_options(opt);
  p.measure_report = report_is_read(opt, formats);
  p.triangle_values = output_crs_of(opt).empty() && stores_triangle_values(formats);
  p.measure = measure_params(opt, p, formats);
  p.write = write_params(opt, p, std::move(formats));
  return p;
}

}  // namespace fdr::pipeline
