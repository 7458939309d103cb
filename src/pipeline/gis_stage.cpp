// Read stage of GIS runs: layers into a projected local frame, the spacing from rasters and rules
// (sizing::spacing_from_rules, gradient-limited), the PSLG cleaned and resampled; the .poly read
// stage; the depths stage (raster sampled at the mesh's vertices) and the TIN error.
#include "base/num_format.hpp"
#include "base/debug.hpp"
#include "pipeline/gis_stage.hpp"
#include <algorithm>
#include <cstdlib>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>
#include "api/core_stages.hpp"
#include "base/error.hpp"
#include "base/memory.hpp"
#include "gis/crs.hpp"
#include "gis/raster_input.hpp"
#include "gis/reproject.hpp"
#include "gis/united_domain.hpp"
#include "gis/vector_input.hpp"
#include "pipeline/global_stage.hpp"
#include "pipeline/memory_policy.hpp"
#include "pipeline/plan.hpp"
#include "pslg/poly_io.hpp"
#include "pslg/resample.hpp"
#include "pslg/snap_loose_ends.hpp"
#include "quality/tin_error.hpp"
#include "sizing/resample_grid.hpp"
#include "sizing/fields.hpp"
#include "sizing/gradient_limiter.hpp"
#include "sizing/grid_field.hpp"
#include "sizing/make_spacing.hpp"
#include "sizing/spacing_grid.hpp"
#include "sizing/spacing_rules.hpp"

namespace fdr::pipeline {
namespace {

class ShiftedField : public sizing::SizingField {
 public:
  ShiftedField(sizing::SizingPtr f, Point2 o) : f_(std::move(f)), o_(o) {}
  // (scalar additions: see sizing::ShiftedField)
  __attribute__((optimize("no-tree-slp-vectorize"))) double operator()(Point2 p) const override {
    return (*f_)({p.x + o_.x, p.y + o_.y});
  }
  double lipschitz() const override { return f_->lipschitz(); }
  bool thread_safe() const override { return f_->thread_safe(); }
  double upper_bound() const override { return f_->upper_bound(); }
  std::string describe() const override { return f_->describe() + " (world coordinates)"; }

 private:
  sizing::SizingPtr f_;
  Point2 o_;
};

std::string num(double v) { return num6(v); }

}  // namespace

gis::GisInput read_gis_input(const Options& opt, StageClock& clock, const ProgressFn& progress, const LogFn& log) {
  if (!opt.output_crs.empty()) gis::check_crs(opt.output_crs);  // fail before any work on an unknown CRS
  auto info = [&](const std::string& s) { if (log) log(LogLevel::kInfo, s); };
  gis::DomainOptions d;
  if (!opt.land.empty()) {
    d.land = {opt.land, opt.layer, opt.where};
    if (opt.global) {
      d.global_pole = opt.pole ? LonLat{(*opt.pole)[0], (*opt.pole)[1]} : LonLat{0, -90};
    } else {
      d.extent = opt.extent;
      if (!opt.extent) throw Error(ExitCode::kUsage, "--land needs --extent XMIN,YMIN,XMAX,YMAX");
    }
  } else {
    d.domain = {opt.input, opt.layer, opt.where};
  }
  if (!opt.open_boundary.empty()) d.open_boundary = {opt.open_boundary, opt.open_boundary_layer, ""};
  if (!opt.breaklines.empty()) d.breaklines = {opt.breaklines, opt.breaklines_layer, ""};
  if (!opt.points.empty()) d.points = {opt.points, opt.points_layer, ""};
  check_layer_options(opt);
  d.s_srs = opt.s_srs;
  d.t_srs = opt.t_srs;
  d.densify_deg = opt.densify_deg;
  d.clean = false;
  // Resolution filter: union of overlapping polygons always; closing of sub-resolution water and
  // removal of small islands unless --keep-coast. hmin as below (default: domain diameter / 500).
  d.features = [&opt](const Box2& b) {
    const double hmin = opt.hmin.value_or(std::hypot(b.width(), b.height()) / 500.0);
    if (!(hmin > 0) || (opt.hmax && !(*opt.hmax >= hmin)))
      throw Error(ExitCode::kInvalidSpacing, "need 0 < --hmin <= --hmax (got hmin " + num(hmin) + ", hmax " +
                                                 (opt.hmax ? num(*opt.hmax) : std::string("auto")) + ")");
    coast::Options fo = coast::resolution_options(hmin);
    const bool keep = opt.keep_coast;
    fo.close_width = opt.close_width.value_or(keep ? 0.0 : fo.close_width);
    fo.min_feature = opt.min_feature.value_or(fo.min_feature);
    fo.widen_width = opt.widen_width.value_or(keep ? 0.0 : fo.widen_width);
    fo.min_island_area = opt.min_island_factor.value_or(keep ? 0.0 : 0.3) * hmin * hmin;
    fo.grow_island_area = 0;  // growing small islands blocked narrow estuaries: off
    if (keep) {
      fo.connect_area = fo.narrow_gap = fo.islet_side = fo.islet_shift = fo.islet_clearance = 0;
      fo.join_islets = false;
    }
    fo.defer_removed = true;  // listed beside the stages that follow (start_features, finish_features)
    // At once when the filter holds 512 MiB or more: a large input, whose listing the rest of its
    // read hides; a smaller one's starts after the spacing stage, whose peak it would raise.
    fo.early_listing_rss = std::size_t{512} << 20;
    if (!(fo.close_width >= 0) || !(fo.min_feature >= 0) || !(fo.min_island_area >= 0) || !(fo.widen_width >= 0))
      throw Error(ExitCode::kUsage, "--close-width, --widen-width, --min-feature and --min-island must be >= 0");
    return fo;
  };
  if (opt.snap) d.snap_distance_m = *opt.snap;
  gis::GisInput g = [&d] {
    // Freed pages stay for reuse while the input is read and filtered: GEOS's millions of small
    // objects (base/memory.hpp; purged when it ends).
    const PhaseMemory memory(MemoryPhase::kGisRead, true);
    return gis::read_domain(d);
  }();
  clock.lap("read");
  if (progress) progress(0.01, "read");
  const gis::Frame& frame = g.frame;
  info("working CRS: " + frame.name() + ", local origin (" + num(frame.origin().x) + ", " + num(frame.origin().y) + ")");
  info("domain: " + std::to_string(g.counts.polygons) + " polygons, " + std::to_string(g.counts.outer_rings) +
       " outer rings, " + std::to_string(g.counts.holes) + " holes, " + std::to_string(g.counts.boundary_segments) +
       " boundary segments, " + std::to_string(g.counts.open_parts) + " open-boundary parts, " +
       std::to_string(g.counts.breakline_segments) + " breakline segments, " + std::to_string(g.counts.fixed_points) +
       " fixed points; area " + num(g.domain_area_m2 / 1e6) + " km^2");
  if (g.counts.long_chords > 0 && log)
    log(LogLevel::kWarning, std::to_string(g.counts.long_chords) +
                                " lon/lat boundary segments span more than 1 degree and are projected as straight "
                                "chords (as GDAL does); --densify 0.1 makes them follow their lon/lat line");
  return g;
}

GisSpacing gis_spacing(const Options& opt, const gis::GisInput& g, StageClock& clock, const ProgressFn& progress,
                       const LogFn& log) {
  if (opt.global) return global_spacing(opt, g, clock, log);
  auto info = [&](const std::string& s) { if (log) log(LogLevel::kInfo, s); };
  const gis::Frame& frame = g.frame;
  // Spacing, in ground metres on a grid over the domain box, then to grid units.
  const double diam = std::hypot(g.raw.bbox().width(), g.raw.bbox().height());
  const Box2 box = sizing::spacing_box(g.raw.bbox());
  const bool any_rule = opt.dist_grade || opt.slope_rule || opt.wavelength_rule || opt.vertical_tol ||
                        !opt.size_raster.empty();
  const double hmin = opt.hmin.value_or(diam / 500.0);
  const double hmax = opt.hmax.value_or(diam / 20.0);
  if (!(hmin > 0) || !(hmax >= hmin))
    throw Error(ExitCode::kInvalidSpacing, "need 0 < --hmin <= --hmax (got hmin " + num(hmin) + ", hmax " + num(hmax) + ")");
  sizing::SizingPtr f_ground;
  std::shared_ptr<sizing::Grid> zgrid;
  std::shared_ptr<const sizing::Grid> fgrid;
  const bool want_grid = !opt.raster.empty() || any_rule || opt.spacing.empty();
  if (want_grid) {
    const double native = !opt.raster.empty() ? gis::grid_cell_size_hint(opt.raster, frame, box) : 0;
    double cell = opt.cell_size.value_or(0);
    if (!(cell > 0)) cell = sizing::spacing_grid_cell(box, hmin);
    sizing::Grid like;
    if (!opt.raster.empty()) {
      // The raster is warped at its own resolution (or the spacing cell when coarser): warping a
      // 5' ETOPO tile onto a 4M-cell grid cost a second for nothing. Depths are sampled from it;
      // depth rules resample it to the spacing grid (bilinear, as the warp did).
      const double zcell = std::max(native, cell);
      zgrid = std::make_shared<sizing::Grid>(gis::read_raster_to_frame(opt.raster, frame, box, zcell, &g.raw.points));
      clock.lap("raster");
      info("raster " + opt.raster + ": " + std::to_string(zgrid->nx) + " x " + std::to_string(zgrid->ny) +
           " cells of " + num(zcell) + " m");
    }
    if (zgrid && zgrid->dx == cell) {
      like = *zgrid;
    } else {
      like = sizing::spacing_grid(box, cell);
    }
    sizing::SpacingRules rules;
    rules.hmin = hmin;
    rules.hmax = hmax;
    rules.dist_grade = opt.dist_grade;
    rules.slope = opt.slope_rule;
    rules.wavelength = opt.wavelength_rule;
    rules.wave_period_s = opt.wave_period_s;
    rules.vertical_tol = opt.vertical_tol;
    rules.size_raster = opt.size_raster;
    if (opt.channel_elements > 0) rules.channel_elements = opt.channel_elements;
    std::vector<std::pair<Point2, Point2>> shore;     // land and island edges; open boundaries are not shore
    std::vector<std::pair<Point2, Point2>> boundary;  // every ring edge (the channel rule's water mask)
    for (const auto& s : g.raw.segments) {
      if (!s.is_boundary()) continue;
      boundary.push_back({g.raw.points[s.a], g.raw.points[s.b]});
      if (s.marker == static_cast<int>(mesh::EdgeKind::kLand) || s.marker == static_cast<int>(mesh::EdgeKind::kIsland))
        shore.push_back({g.raw.points[s.a], g.raw.points[s.b]});
    }
    std::optional<sizing::Grid> size;
    if (!opt.size_raster.empty())
      size = sizing::size_raster_rule(gis::read_raster_to_frame(opt.size_raster, frame, box, like.dx, &g.raw.points), like);
    sizing::RuleGrid rg = sizing::spacing_from_rules(rules, {&like, &shore, zgrid.get(), size ? &*size : nullptr, &boundary});
    clock.lap("sizing");
    sizing::limit_gradient(rg.h, opt.gradation);
    clock.lap("limit");
    const std::string desc = sizing::describe_rules(rg, rules, opt.gradation);
    info("spacing: " + desc);
    auto field = std::make_shared<sizing::GridField>(std::move(rg.h), desc);
    // The grid --write-spacing writes is the field's own (an aliasing pointer that keeps the field
    // alive), not a copy: a copy held a second grid of fresh pages to the end of the run.
    fgrid = std::shared_ptr<const sizing::Grid>(field, &field->grid());
    f_ground = std::move(field);
  }
  if (!opt.spacing.empty()) {
    sizing::SizingPtr e = std::make_shared<ShiftedField>(sizing::make_spacing(opt.spacing), frame.origin());
    f_ground = f_ground ? std::make_shared<sizing::MinField>(std::vector<sizing::SizingPtr>{f_ground, e}) : e;
  }
  double kdev = 0;
  sizing::SizingPtr f = gis::ground_to_grid(f_ground, frame, box, &kdev);
  info("projection scale factor: max |k - 1| = " + num(kdev) + (kdev > 1e-3 ? " (spacing corrected)" : ""));

  if (progress) progress(0.03, "clean");
  return {f, zgrid, fgrid, hmin, kdev, nullptr, nullptr};
}

PreparedInput clean_gis_input(const Options& opt, gis::GisInput g, const GisSpacing& sp, StageClock& clock,
                              const LogFn& log, bool defer_listing) {
  auto info = [&](const std::string& s) { if (log) log(LogLevel::kInfo, s); };
  const gis::Frame& frame = g.frame;
  const sizing::SizingPtr& f = sp.f;
  const double hmin = sp.hmin;
  // Geometry repair with the spacing known.
  pslg::CleanOptions co;
  co.snap_distance = g.snap_distance_m;
  co.min_island_area_factor = 0;  // islands: resolution filter (in hmin^2)
  if (opt.simplify) {
    co.simplify_factor = *opt.simplify;
    co.simplify_tolerance = hmin / 10.0;
  }
  co.spacing = [f](Point2 p) { return (*f)(p); };
  clock.restart();
  // Breaklines were clipped a hair inside a filtered domain (vector_input.cpp): their ends go
  // back onto the coast.
  std::vector<pslg::Repair> loose_reps =
      pslg::snap_loose_ends(g.raw, std::max(g.snap_distance_m, 0.1 * g.features.close_width));
  gis::clean_domain(g, co);
  for (auto& r : loose_reps) {
    gis::RepairRecord rec;
    rec.lonlat = frame.to_lonlat(r.where);
    rec.repair = std::move(r);
    rec.repair.where = frame.to_world(rec.repair.where);
    g.repairs.push_back(std::move(rec));
  }
  // The report's coast deviation against the boundary of the domain the mesher meshes: the input
  // polygons united (borders between adjacent polygons are no coast and have no mesh edges).
  // Timed with the repair: both make the input the domain the mesher meshes.
  std::vector<std::pair<Point2, Point2>> input_boundary;
  std::vector<std::pair<std::string, double>> coast_figures;
  {
    const auto& input = g.input_polygons.empty() ? g.domain_polygons : g.input_polygons;
    const std::optional<coast::Polygons> united = gis::united_domain(input, g.features.united > 0);
    const coast::Polygons& boundary = united ? *united : input;
    coast_figures.push_back({"input_polygons", static_cast<double>(input.size())});
    coast_figures.push_back({"input_polygons_united", static_cast<double>(boundary.size())});
    for (const auto& poly : boundary)
      for (const auto& ring : poly)
        for (std::size_t i = 0; i < ring.size(); ++i) input_boundary.push_back({ring[i], ring[(i + 1) % ring.size()]});
  }
  clock.lap("repair");
  // Boundaries resampled to f (model-ready coast) unless --keep-coast.
  if (!opt.keep_coast) {
    if (!(opt.coast_tol >= 0)) throw Error(ExitCode::kUsage, "--coast-tol must be >= 0");
    pslg::ResampleOptions ro;
    ro.spacing = [f](Point2 p) { return (*f)(p); };
    ro.tolerance_factor = opt.coast_tol;
    ro.domain_by_parity = true;  // as the CDT decides the GIS domain
    pslg::ResampleStats rs;
    if (const char* dbg = debug::value(debug::Aid::kPslg)) pslg::write_poly(g.pslg, std::string(dbg) + ".before.poly");
    g.pslg = pslg::resample(g.pslg, ro, &rs);
    if (const char* dbg = debug::value(debug::Aid::kPslg)) pslg::write_poly(g.pslg, std::string(dbg) + ".after.poly");
    info("coast resampled to f: " + std::to_string(rs.vertices_in) + " -> " + std::to_string(rs.vertices_out) +
         " boundary vertices in " + std::to_string(rs.chains) + " chains (tolerance " + num(opt.coast_tol) +
         " f, max deviation " + num(rs.max_deviation) + " m; " + std::to_string(rs.pieces_restored) +
         " pieces kept as input to avoid crossings)");
    coast_figures.push_back({"boundary_vertices_input", static_cast<double>(rs.vertices_in)});
    coast_figures.push_back({"boundary_vertices_resampled", static_cast<double>(rs.vertices_out)});
    coast_figures.push_back({"resample_max_deviation_m", rs.max_deviation});
    coast_figures.push_back({"resample_pieces_restored", static_cast<double>(rs.pieces_restored)});
    clock.lap("resample");
  }
  PreparedInput out;
  out.hmin = hmin;
  out.coast_figures = std::move(coast_figures);
  out.input_boundary = std::move(input_boundary);
  out.pslg = std::move(g.pslg);
  out.f = f;
  out.crs_name = frame.name();
  out.metadata.push_back({"crs_wkt", frame.wkt()});
  out.metadata.push_back({"crs_epsg", std::to_string(frame.epsg())});
  out.metadata.push_back({"local_origin", num(frame.origin().x) + "," + num(frame.origin().y)});
  out.metadata.push_back({"domain_area_m2", num(g.domain_area_m2)});
  if (!opt.raster.empty()) out.metadata.push_back({"raster", opt.raster});
  out.metadata.push_back({"max_abs_scale_factor_minus_1", num(sp.kdev)});
  out.crs_wkt = frame.wkt();
  out.frame = std::make_shared<const gis::Frame>(frame);
  out.dem = sp.dem;
  out.spacing_grid = sp.spacing_grid;
  if (sp.sphere_f) attach_sphere(out, sp, opt, log);
  // The filter's removed-water listing (started beside the stages since the spacing), then the
  // figures and repairs that need it. Deferred: run by complete_input() once the refinement is
  // done, so that the listing has the core the refinement leaves free (and its memory does not
  // add to the spacing stage's, the process's peak).
  g.raw = {};
  g.domain_polygons.clear();
  g.input_polygons.clear();
  auto rest = std::make_shared<gis::GisInput>(std::move(g));
  auto complete = [rest, log](PreparedInput& in) {
    auto info = [&](const std::string& s) { if (log) log(LogLevel::kInfo, s); };
    gis::finish_features(*rest);
    const auto& ff = rest->features;
    auto& cf = in.coast_figures;
    cf.push_back({"input_pieces", static_cast<double>(ff.input_pieces)});
    cf.push_back({"filtered_pieces", static_cast<double>(ff.output_pieces)});
    cf.push_back({"polygons_united", static_cast<double>(ff.united)});
    cf.push_back({"narrow_water_closed", static_cast<double>(ff.closed)});
    cf.push_back({"water_removed_m2", ff.closed_area});
    cf.push_back({"corner_pieces_removed", static_cast<double>(ff.corner_pieces)});
    cf.push_back({"channels_kept", static_cast<double>(ff.channels_kept)});
    cf.push_back({"islands_removed", static_cast<double>(ff.islands_removed)});
    cf.push_back({"islands_removed_m2", ff.islands_area});
    cf.push_back({"thin_land_removed_m2", ff.land_removed_area});
    cf.push_back({"tips_kept", static_cast<double>(ff.tips_kept)});
    cf.push_back({"islets_simplified", static_cast<double>(ff.islets_replaced)});
    cf.push_back({"islets_joined", static_cast<double>(ff.islets_joined)});
    cf.push_back({"islets_joined_water_m2", ff.islets_joined_area});
    cf.push_back({"narrow_gaps_kept", static_cast<double>(ff.narrow_gaps)});
    cf.push_back({"narrow_gaps_made", static_cast<double>(ff.narrow_gaps_made)});
    cf.push_back({"water_connections_widened", static_cast<double>(ff.reconnected)});
    cf.push_back({"water_connections_widened_m2", ff.reconnected_area});
    cf.push_back({"water_widened", static_cast<double>(ff.widened)});
    cf.push_back({"water_widened_m2", ff.widened_area});
    cf.push_back({"input_area_m2", ff.input_area});
    info("features: " + std::to_string(ff.input_pieces) + " water bodies in, " + std::to_string(ff.output_pieces) +
         " out; " + std::to_string(ff.closed) + " narrow water pieces closed (" + num(ff.closed_area / 1e6) +
         " km^2 with corner rounding), " + std::to_string(ff.channels_kept) + " narrow connections kept, " +
         std::to_string(ff.islands_removed) + " islands removed (" + num(ff.islands_area / 1e6) + " km^2), " +
         std::to_string(ff.islets_replaced) + " islets kept as triangles, " + std::to_string(ff.islets_joined) +
         " joined to land, " +
         num(ff.land_removed_area / 1e6) + " km^2 of thin land removed, " + std::to_string(ff.tips_kept) +
         " tips of land kept, " + std::to_string(ff.widened) + " narrow water pieces widened (" +
         num(ff.widened_area / 1e6) + " km^2 of land), " + std::to_string(ff.reconnected) +
         " cut-off water bodies kept with their connection widened (" + num(ff.reconnected_area / 1e6) +
         " km^2 of land), " + std::to_string(ff.narrow_gaps) + " places narrower than hmin/2 left (" +
         std::to_string(ff.narrow_gaps_made) + " of them made by these steps), " + std::to_string(ff.united) +
         " overlaps united");
    std::map<std::string, std::size_t> kinds;
    for (const auto& r : rest->repairs) ++kinds[r.repair.kind];
    std::string rep = "repairs: " + std::to_string(rest->repairs.size());
    for (const auto& [k, n] : kinds) rep += ", " + k + " " + std::to_string(n);
    info(rep);
    for (const auto& r : rest->repairs) {
      const Point2 w = r.repair.where;
      in.repairs.push_back({r.repair.kind, w.x, w.y, r.repair.size, r.repair.reason, r.repair.part});
    }
  };
  if (defer_listing) out.complete = std::move(complete);
  else complete(out);
  return out;
}

PreparedInput prepare_gis_input(const Options& opt, const ProgressFn& progress, const LogFn& log) {
  std::vector<StageTime> stages;
  StageClock clock(&stages);
  return prepare_gis_input(opt, clock, progress, log);
}

PreparedInput prepare_gis_input(const Options& opt, StageClock& clock, const ProgressFn& progress, const LogFn& log,
                                bool defer_listing) {
  // What the allocator maps for GEOS's objects, the spacing grids and the cleaned and resampled
  // PSLG goes on huge pages (base/memory.hpp).
  const PhaseMemory memory(MemoryPhase::kGisInput, true);
  gis::GisInput g = read_gis_input(opt, clock, progress, log);
  const GisSpacing sp = gis_spacing(opt, g, clock, progress, log);
  // The filter's removed-water listing from here on (unless the filter started it: a large input,
  // coast::Options::early_listing_rss), on an arena of its own, waited for after the
  // refinement (pipeline.cpp). Beside the spacing stage it would take a core from its parallel
  // loops and add its memory to that stage's, the process's peak.
  gis::start_features(g);
  return clean_gis_input(opt, std::move(g), sp, clock, log, defer_listing);
}

std::vector<double> sample_depths(const mesh::MeshView& m, const PreparedInput& in, const LogFn& log) {
  if (in.lonlat_dem) return global_depths(m, in);
  if (!in.dem) return {};
  int filled = 0;
  std::vector<double> z = gis::sample_depths(*in.dem, m.vertices, &filled);
  if (filled > 0 && log)
    log(LogLevel::kWarning, std::to_string(filled) + " nodes got their depth from the nearest valid raster cell (nodata)");
  return z;
}

std::pair<double, double> tin_error(const mesh::MeshView& m, const sizing::Grid& dem, const LogFn& log) {
  const auto [emax, erms] = quality::tin_vertical_error(m, dem);
  if (log) log(LogLevel::kInfo, "TIN vertical error against the DEM: max " + num(emax) + " m, RMS " + num(erms) + " m");
  return {emax, erms};
}

}  // namespace fdr::pipeline
