// Terrain volumes: 2D TIN (pipeline::run with the DEM as raster) -> surfaces sampled at its
// vertices (gis) -> PLC and spacing (terrain) -> tetrahedralize (api) -> report -> write (tetio).
#include "pipeline/terrain_run.hpp"
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <sstream>
#include <nlohmann/json.hpp>
#include "api/tetrahedralize.hpp"
#include "base/error.hpp"
#include "gis/crs.hpp"
#include "gis/raster_input.hpp"
#include "pipeline/pipeline.hpp"
#include "pipeline/terrain_gpkg.hpp"
#include "pipeline/terrain_wells.hpp"
#include "quality/check3d.hpp"
#include "quality/rss.hpp"
#include "terrain/depth_spacing.hpp"
#include "terrain/layer_spacing.hpp"
#include "terrain/surfaces.hpp"
#include "terrain/terrain_plc.hpp"
#include "base/out_file.hpp"
#include "tetio/write_poly.hpp"
#include "tetio/write_tets.hpp"

namespace fdr::pipeline {
namespace {

// The cell budget of the 3D spacing grid: fine enough to follow the 2D spacing across the domain,
// small enough that the 3D limiter's sweeps take a fraction of the meshing.
constexpr double kSpacingCells = 1e6;
// Default growth of the spacing per metre of depth below the top.
constexpr double kDefaultDepthGrade = 0.25;
// The 2D run's options: the terrain TIN of the domain with the DEM as its raster, nothing written.
// Without INPUT the domain is the DEM's valid-data box; the wells are fixed points of the TIN.
Options tin_options(const Options& opt, const TerrainInputs& in) {
  Options o = opt;
  if (!in.domain.path().empty()) o.input = in.domain.path();
  if (!in.points.path().empty()) o.points = in.points.path();
  o.wells.clear();
  o.wells_layer.clear();
  o.well_spacing.reset();
  o.raster = opt.dem;
  o.dem.clear();
  o.base.clear();
  o.horizons.clear();
  o.depth_grade.reset();
  o.min_thickness.reset();
  o.outputs.clear();
  o.report_json.clear();
  o.check = false;
  o.quiet = true;
  o.report_only_if_read = true;
  o.bound = Options{}.bound;
  o.bound_given = false;
  return o;
}

terrain::Tin tin_of(const mesh::MeshView& m) {
  terrain::Tin t;
  t.xy = m.vertices;
  t.triangles.reserve(m.triangles.size());
  for (const auto& tr : m.triangles) t.triangles.push_back({tr[0], tr[1], tr[2]});
  return t;
}

Box2 box_of(const std::vector<Point2>& xy) {
  Box2 b;
  for (const Point2 p : xy) b.add(p);
  return b;
}

// A raster warped into the working frame and sampled at the TIN's vertices; errors name the option.
std::vector<double> sample_raster(const std::string& option, const std::string& path, const gis::Frame& frame,
                                  const std::vector<Point2>& xy, const LogFn& log) {
  try {
    const Box2 box = box_of(xy);
    const sizing::Grid g = gis::read_raster_to_frame(path, frame, box, gis::grid_cell_size_hint(path, frame, box), &xy);
    int filled = 0;
    std::vector<double> z = gis::sample_depths(g, xy, &filled);
    if (filled > 0 && log)
      log(LogLevel::kWarning, option + " " + path + ": " + std::to_string(filled) +
                                  " vertices on nodata cells take the nearest valid cell's value");
    return z;
  } catch (const Error& e) {
    throw Error(e.code(), option + " " + path + ": " + e.what());
  }
}

std::string stem(const std::string& path) { return std::filesystem::path(path).stem().string(); }

// top (the TIN's DEM elevations), the horizons, the base; clamped into order (a documented repair,
// logged), with the base refused where it is not below the top.
std::vector<terrain::Surface> surface_stack(const Options& opt, const mesh::MeshView& m, const terrain::Tin& tin,
                                            const gis::Frame& frame, double min_thickness, const LogFn& log) {
  std::vector<terrain::Surface> stack;
  stack.push_back({"top", m.z});
  for (const std::string& h : opt.horizons) {
    std::string name = stem(h);
    for (const auto& s : stack)
      if (s.name == name) name += "_" + std::to_string(stack.size());
    stack.push_back({name, sample_raster("--horizon", h, frame, tin.xy, log)});
  }
  if (const auto zb = base_elevation(opt.base)) stack.push_back({"base", std::vector<double>(tin.xy.size(), *zb)});
  else stack.push_back({"base", sample_raster("--base", opt.base, frame, tin.xy, log)});
  const terrain::ClampCounts c = terrain::clamp_surfaces(stack, tin, m.origin, min_thickness);
  for (std::size_t k = 1; k + 1 < stack.size(); ++k)
    if (log && (c.lowered[k] || c.raised[k] || c.collapsed[k])) {
      std::ostringstream s;
      s << "horizon " << stack[k].name << ": " << c.lowered[k] << " vertices lowered onto the surface above, "
        << c.raised[k] << " raised onto the base (the layers pinch out there), " << c.collapsed[k]
        << " moved onto the surface above or the base where a layer is thinner than " << min_thickness << " m";
      log(LogLevel::kWarning, s.str());
    }
  return stack;
}

// Every pinch-out ended at a vertical wall (terrain::end_pinch_outs, a documented repair, logged
// with the triangles and volume moved per layer and the largest vertical move of a surface).
terrain::PinchOutRepair end_pinch_outs(const terrain::Tin& tin, const std::vector<terrain::Surface>& stack,
                                       Point2 origin, const LogFn& log) {
  terrain::PinchOutRepair r = terrain::end_pinch_outs(tin, stack);
  if (log && !r.layering.identity()) {
    std::ostringstream s;
    s.precision(10);
    s << "pinch-outs end at vertical walls: layers removed from the TIN triangles where they thin to zero (";
    const char* sep = "";
    for (std::size_t k = 0; k < r.triangles.size(); ++k)
      if (r.triangles[k]) {
        s << sep << stack[k].name << "-" << stack[k + 1].name << " " << r.triangles[k] << " triangles, " << r.volume[k]
          << " m3 moved to the layer beside";
        sep = "; ";
      }
    const Point2 at = tin.xy[r.largest_at];
    s << "), a surface moved by up to " << r.largest_move << " m (at " << at.x + origin.x << ", " << at.y + origin.y
      << ")";
    log(LogLevel::kWarning, s.str());
  }
  return r;
}

// The top's elevation per column of g: the TIN's vertices binned into the columns (mean), columns
// without a vertex from their neighbours (gis::sample_depths fills from the nearest valid cell).
std::vector<double> top_per_column(const sizing::Grid3& g, const std::vector<Point2>& xy, const std::vector<double>& top) {
  sizing::Grid bins;
  bins.nx = g.nx;
  bins.ny = g.ny;
  bins.x0 = g.x0;
  bins.y0 = g.y0;
  bins.dx = g.dx;
  bins.dy = g.dy;
  std::vector<double> sum(g.nx * g.ny, 0.0), cnt(g.nx * g.ny, 0.0);
  for (std::size_t v = 0; v < xy.size(); ++v) {
    const auto i = static_cast<std::size_t>(std::clamp((xy[v].x - g.x0) / g.dx, 0.0, static_cast<double>(g.nx - 1)));
    const auto j = static_cast<std::size_t>(std::clamp((xy[v].y - g.y0) / g.dy, 0.0, static_cast<double>(g.ny - 1)));
    sum[j * g.nx + i] += top[v];
    cnt[j * g.nx + i] += 1;
  }
  bins.v.resize(sum.size());
  for (std::size_t c = 0; c < sum.size(); ++c) bins.v[c] = cnt[c] > 0 ? sum[c] / cnt[c] : std::nan("");
  return gis::sample_depths(bins, terrain::column_centres(g));
}

// The 2D spacing's range on the TIN's vertices, with --hmin for its low end when given: the
// defaults of the terrain spacing's bounds and of the well spacing.
std::pair<double, double> spacing_range(const Options& opt, const sizing::SizingField& f2, const std::vector<Point2>& xy) {
  double lo = std::numeric_limits<double>::infinity(), hi = 0;
  for (const Point2 q : xy) {
    const double h = f2(q);
    if (std::isfinite(h)) lo = std::min(lo, h), hi = std::max(hi, h);
  }
  if (opt.hmin) lo = *opt.hmin;
  return {lo, hi};
}

// f(x, y, z) = clamp(f2D(x, y) + G depth, hmin, hmax) on a 3D grid, at most well_h along the wells
// and at most the thickness of a layer near it, gradient-limited to --gradation; hmin and hmax default to the 2D spacing's range (hmax grown by
// the grade over the box's height). Made from the local-frame PLC and TIN; the grid returned is
// in world coordinates (+ origin).
sizing::SizingPtr3 terrain_spacing(const Options& opt, const plc::Plc& p, const sizing::SizingField& f2,
                                   const terrain::Tin& tin, const std::vector<terrain::Surface>& stack,
                                   const terrain::Layering& layering, Point2 origin,
                                   const std::vector<std::array<Point3, 2>>& wells, double well_h, const LogFn& log) {
  const std::vector<Point2>& xy = tin.xy;
  const std::vector<double>& top = stack.front().z;
  Box3 box;
  for (const Point3& q : p.points) box.add(q);
  // The grid's cell is hmin / 2 at the finest.
  const auto [lo, hi] = spacing_range(opt, f2, xy);
  sizing::Grid3 g = terrain::spacing_grid_geometry(box, kSpacingCells, 0.5 * lo);
  const std::vector<Point2> cols = terrain::column_centres(g);
  std::vector<double> h2(cols.size());
  for (std::size_t c = 0; c < cols.size(); ++c) h2[c] = f2(cols[c]);
  terrain::DepthSpacing ds;
  ds.grade = opt.depth_grade.value_or(kDefaultDepthGrade);
  ds.hmin = lo;
  ds.hmax = opt.hmax.value_or(hi + ds.grade * (box.hi.z - box.lo.z));
  ds.alpha = opt.gradation;
  ds.near_segments = wells;
  ds.near_h = well_h;
  terrain::fill_depth_spacing(g, h2, top_per_column(g, xy, top), ds);
  terrain::LayerSpacing ls;
  ls.hmin = ds.hmin;
  const terrain::LayerSpacingResult lr = terrain::bound_by_layer_thickness(g, tin, stack, ls, layering);
  if (log && !lr.places.empty()) {
    std::ostringstream w;
    w.precision(10);
    w << "the layers' thickness took the spacing below hmin (" << ds.hmin << " m) in " << lr.cells_below_hmin
      << " grid cells, down to " << lr.smallest << " m; thinnest:";
    for (const terrain::ThinPlace& tp : lr.places)
      w << " " << p.material_names.at(tp.layer + 1) << " " << tp.thickness << " m at (" << tp.at.x + origin.x << ", "
        << tp.at.y + origin.y << ", " << tp.at.z << ");";
    log(LogLevel::kWarning, w.str());
  }
  g.x0 += origin.x;  // the mesh is made in world coordinates (plc_to_world)
  g.y0 += origin.y;
  std::ostringstream label;
  label << "terrain: 2D spacing + " << ds.grade << " x depth, in [" << ds.hmin << ", " << ds.hmax << "], at most "
        << ls.factor << " x layer thickness (graded " << ls.grade << ")";
  return fdr::grid_spacing3(std::move(g), label.str());
}

std::vector<LayerFigures> layer_figures(const quality::Report3& rep, const plc::Plc& p, const std::vector<double>& expected) {
  std::vector<LayerFigures> out;
  for (std::size_t s = 0; s < expected.size(); ++s) {
    LayerFigures l;
    l.material = static_cast<std::int32_t>(s + 1);
    l.name = p.material_names.at(s + 1);
    l.expected = expected[s];
    for (const auto& mf : rep.materials)
      if (mf.material == l.material) l.tets = mf.tets, l.volume = mf.volume;
    out.push_back(l);
  }
  return out;
}

void write_report_json(const Result3& r, const std::string& path) {
  OutFile out(path);
  out.write(report_json3(r) + "\n");
  out.commit();
}

// The PLC moved from the local frame to world coordinates (each coordinate rounded once): the mesh
// is made where it is written, so the exact predicates' decisions hold for the written numbers.
void plc_to_world(plc::Plc& p, Point2 origin) {
  for (Point3& q : p.points) q = {q.x + origin.x, q.y + origin.y, q.z};
  for (plc::Region& r : p.regions) r.point = {r.point.x + origin.x, r.point.y + origin.y, r.point.z};
}

bool is_poly(const std::string& p) {
  return p.size() >= 5 && (p.compare(p.size() - 5, 5, ".poly") == 0 || p.compare(p.size() - 5, 5, ".POLY") == 0);
}

// The terrain PLC (world coordinates) as TetGen .poly files (for TetGen, or to mesh it again).
void write_plc_outputs(const std::vector<std::string>& paths, const plc::Plc& p) {
  for (const std::string& path : paths) tetio::write_poly(path, p);
}

}  // namespace

std::string report_json3(const Result3& r) {
  std::ostringstream s;
  quality::write_json3(r.report, s);
  if (r.layers.empty()) return s.str();
  nlohmann::ordered_json j = nlohmann::ordered_json::parse(s.str());
  nlohmann::ordered_json layers = nlohmann::ordered_json::array();
  for (const LayerFigures& l : r.layers)
    layers.push_back({{"material", l.material}, {"name", l.name}, {"tets", l.tets}, {"volume", l.volume},
                      {"expected_volume", l.expected},
                      {"relative_difference", l.expected > 0 ? (l.volume - l.expected) / l.expected : 0.0},
                      {"pinch_out_triangles", l.pinch_out_triangles}, {"pinch_out_volume_moved", l.pinch_out_volume}});
  j["layers"] = layers;
  return j.dump(2);
}

std::optional<double> base_elevation(const std::string& base) {
  char* end = nullptr;
  const double z = std::strtod(base.c_str(), &end);
  if (base.empty() || end == base.c_str() || *end != '\0' || !std::isfinite(z)) return std::nullopt;
  return z;
}

Result3 run_terrain(const Options& opt, const ProgressFn& progress, const LogFn& log) {
  const auto t_start = std::chrono::steady_clock::now();
  check_terrain_options(opt);
  auto report_progress = [&](double frac, const char* stage) {
    if (progress && !progress(frac, stage)) throw Error(ExitCode::kCancelled, std::string("cancelled during ") + stage);
  };
  Result3 r;
  StageClock clock(&r.stages);
  const ProgressFn tin_progress = [&](double f, std::string_view s) { return !progress || progress(0.3 * f, s); };
  const TerrainInputs inputs = terrain_inputs(opt);
  Result r2 = run(tin_options(opt, inputs), tin_progress, log);
  clock.lap("tin");
  if (r2.mesh.z.size() != r2.mesh.vertices.size()) throw Error(ExitCode::kInternal, "terrain TIN without elevations");
  const terrain::Tin tin = tin_of(r2.mesh);
  const gis::Frame frame = gis::Frame::from_crs(r2.mesh.crs_wkt, r2.mesh.origin);
  // Layers thinner than the resolution collapse by default (terrain::default_min_thickness).
  const double min_thickness = opt.min_thickness.value_or(
      terrain::default_min_thickness(spacing_range(opt, *r2.f, tin.xy).first, opt.vertical_tol.value_or(0.0)));
  const std::vector<terrain::Surface> stack = surface_stack(opt, r2.mesh, tin, frame, min_thickness, log);
  const terrain::PinchOutRepair pinch = end_pinch_outs(tin, stack, r2.mesh.origin, log);
  const terrain::Layering& layering = pinch.layering;
  terrain::TerrainPlc tp = terrain::build_terrain_plc(tin, stack, layering);
  tp.plc.source = opt.input.empty() ? opt.dem : opt.input;
  const double well_h = opt.well_spacing.value_or(spacing_range(opt, *r2.f, tin.xy).first);
  TerrainWells wells;
  if (!opt.wells.empty()) {
    const Box2 b = box_of(tin.xy);
    const double match = std::max(opt.snap.value_or(0.0), 1e-6 * std::hypot(b.width(), b.height()));
    wells = add_terrain_wells(opt, frame, tin, stack, tp, well_h, match, log);
  }
  const sizing::SizingPtr3 f =
      terrain_spacing(opt, tp.plc, *r2.f, tin, stack, layering, r2.mesh.origin, wells.lines, well_h, log);
  plc_to_world(tp.plc, r2.mesh.origin);
  clock.lap("surfaces");
  if (log) log(LogLevel::kInfo, "terrain PLC: " + std::to_string(tp.plc.points.size()) + " vertices, " +
                                    std::to_string(tp.plc.facets.size()) + " facets, " + std::to_string(stack.size() - 1) +
                                    " layers; spacing " + f->describe());

  std::vector<std::string> poly_out, gpkg_out, mesh_out;
  for (const std::string& o : opt.outputs) (is_poly(o) ? poly_out : is_gpkg_path(o) ? gpkg_out : mesh_out).push_back(o);
  if (!poly_out.empty() && mesh_out.empty() && gpkg_out.empty()) {  // the PLC only: nothing to mesh
    write_plc_outputs(poly_out, tp.plc);
    r.written = poly_out;
    r.measured = false;
    r.report.input_file = tp.plc.source;
    r.report.vertices = tp.plc.points.size();
    return r;
  }

  tet::TetOptions to = tet_options(opt, tp.plc.points.size());
  to.progress = [&](double x) { report_progress(0.35 + 0.5 * std::clamp(x, 0.0, 1.0), "refine"); };
  report_progress(0.35, "refine");
  TetResult tr = fdr::tetrahedralize(tp.plc, *f, to);
  clock.lap("tetrahedralize");
  r.mesh = std::move(tr.mesh);
  if (!wells.chains.empty()) mark_well_edges(r.mesh, wells, tp.plc);

  report_progress(0.85, "report");
  r.measured = true;  // the layer volumes need the per-material figures
  quality::TetValues values;
  r.report = quality::measure_tets(r.mesh, *f, tr.stats, &values);
  r.mesh.cell_fields.emplace_back("r_over_f", std::move(values.r_over_f));
  r.mesh.cell_fields.emplace_back("radius_edge", std::move(values.radius_edge));
  r.mesh.cell_fields.emplace_back("min_dihedral_deg", std::move(values.min_dihedral_deg));
  r.report.input_file = tp.plc.source;
  r.layers = layer_figures(r.report, tp.plc, terrain::layer_volumes(tin, stack, layering));
  for (std::size_t k = 0; k < r.layers.size(); ++k)
    r.layers[k].pinch_out_triangles = pinch.triangles[k], r.layers[k].pinch_out_volume = pinch.volume[k];
  clock.lap("report");
  if (opt.check) {
    quality::check_tets(r.mesh, tp.plc, *f, tr.stats.bound);  // Error(kCheckFailed) before anything is written
    r.report.check_passed = true;
    clock.lap("check");
  }

  report_progress(0.9, "write");
  std::vector<std::string> surfaces;
  for (const terrain::Surface& sf : stack) surfaces.push_back(sf.name);
  std::vector<std::string> gpkg_done;
  try {  // all or nothing: the GeoPackages written go when a later output fails
    for (const std::string& g : gpkg_out) {
      write_top_gpkg(g, r2, r, surfaces, tp.plc.source);
      gpkg_done.push_back(g);
      if (!wells.chains.empty()) terrain::write_wells_layer(g, r2.mesh.crs_wkt, well_lines(wells, tp.plc));
    }
    tetio::write_tets_all(mesh_out, r.mesh);
    write_plc_outputs(poly_out, tp.plc);
  } catch (...) {
    std::error_code ec;
    for (const std::string& g : gpkg_done) std::filesystem::remove(g, ec);
    throw;
  }
  r.written = opt.outputs;
  clock.lap("write");
  time_report3(r, t_start);
  if (!opt.report_json.empty()) {
    write_report_json(r, opt.report_json);
    r.written.push_back(opt.report_json);
  }
  report_progress(1.0, "done");
  return r;
}

}  // namespace fdr::pipeline
