// The GIS stage of the pipeline: OGR/GDAL inputs -> PSLG in a projected local frame + spacing f.
#pragma once
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>
#include "base/progress.hpp"
#include "gis/crs.hpp"
#include "gis/vector_input.hpp"
#include "io/writer.hpp"
#include "mesh/mesh_view.hpp"
#include "pipeline/options.hpp"
#include "pipeline/stage_time.hpp"
#include "pslg/pslg.hpp"
#include "sizing/grid.hpp"
#include "sizing/sizing_field.hpp"

namespace fdr::gis {
// --global runs (gis/global_spacing.hpp): held here by pointer only, so that the core pipeline,
// which passes them on, never runs their code.
class StereoSpacing;
struct LonLatRaster;
}  // namespace fdr::gis

namespace fdr::pipeline {

struct PreparedInput {
  pslg::Pslg pslg;                        // local frame (pslg.origin = world offset)
  sizing::SizingPtr f;                    // spacing in the local frame (grid units, corrected for scale)
  std::string crs_name;                   // printed and stored
  std::vector<io::RepairRow> repairs;     // world coordinates
  std::vector<std::pair<std::string, std::string>> metadata;  // extra provenance
  // GIS runs (plain values, used by the later stages):
  // Working CRS + local origin (null for .poly). Behind a pointer made by the GIS side, so that
  // the core pipeline (fdr_pipeline_core) never runs PROJ/GDAL code (gis_backend.hpp).
  std::shared_ptr<const gis::Frame> frame;
  std::string crs_wkt;                    // WKT of the working CRS ("" for .poly)
  std::shared_ptr<const sizing::Grid> dem;           // --raster in the local frame: depths, TIN error
  std::shared_ptr<const sizing::Grid> spacing_grid;  // final f grid in ground metres (--write-spacing)
  // --global runs: the spacing on the sphere (f is it), the lon/lat raster for the depths, and
  // what measures the finished mesh on the sphere (figures appended to coast_figures).
  std::shared_ptr<const gis::StereoSpacing> sphere_f;
  std::shared_ptr<const gis::LonLatRaster> lonlat_dem;
  // Its arguments: the mesh, input_boundary (the coast deviation on the sphere), the figures.
  std::function<void(const mesh::MeshView&, const std::vector<std::pair<Point2, Point2>>&,
                     std::vector<std::pair<std::string, double>>&)>
      sphere_figures;
  // --global: the vertices of a mesh in this frame on the sphere of radius sphere_radius (Earth-
  // centred x, y, z in metres), what the VTU and msh outputs are written in.
  std::function<std::vector<Point3>(const mesh::MeshView&)> sphere_xyz;
  double sphere_radius = 0;
  // Model-readiness inputs for the report (GIS runs).
  double hmin = 0;                        // metres
  std::vector<std::pair<Point2, Point2>> input_boundary;  // input domain rings, local frame
  std::vector<std::pair<std::string, double>> coast_figures;  // filter/resample counts for the report
  // GIS runs prepared with defer_listing: what completes `repairs` and `coast_figures` (the
  // resolution filter's removed-water listing, running beside the stages meanwhile); run it with
  // complete_input() before reading them.
  std::function<void(PreparedInput&)> complete;
};

// Runs in.complete once (nothing when there is none). Inline: the core pipeline calls it
// without linking the GIS side (the function it runs comes from there).
inline void complete_input(PreparedInput& in) {
  if (!in.complete) return;
  auto c = std::move(in.complete);
  in.complete = nullptr;
  c(in);
}

// Read stage, GIS inputs: the OGR/GDAL layers named in `opt` (any non-.poly input) in a
// projected local frame, through the resolution filter (gis::read_domain). Laps "read".
gis::GisInput read_gis_input(const Options& opt, StageClock& clock, const ProgressFn& progress, const LogFn& log);

// Spacing stage, GIS inputs: rasters and rules on a grid in ground metres
// (sizing::spacing_from_rules), gradient-limited, min with --spacing, corrected for the
// projection's scale. Laps "raster", "sizing", "limit".
struct GisSpacing {
  sizing::SizingPtr f;                               // local frame, grid units
  std::shared_ptr<const sizing::Grid> dem;           // --raster in the local frame (depths)
  std::shared_ptr<const sizing::Grid> spacing_grid;  // final f grid, ground metres (--write-spacing)
  double hmin = 0;                                   // metres
  double kdev = 0;                                   // max |k - 1| of the projection's scale
  std::shared_ptr<const gis::StereoSpacing> sphere_f;  // --global: f (the same object)
  std::shared_ptr<const gis::LonLatRaster> lonlat_dem; // --global: --raster in lon/lat
};
GisSpacing gis_spacing(const Options& opt, const gis::GisInput& g, StageClock& clock, const ProgressFn& progress,
                       const LogFn& log);

// Clean/resample stage, GIS inputs: loose ends snapped (pslg::snap_loose_ends), the domain
// cleaned with f known, boundaries resampled to f (pslg::resample) unless --keep-coast; the
// PSLG and what the later stages need. Laps "repair", "resample".
PreparedInput clean_gis_input(const Options& opt, gis::GisInput g, const GisSpacing& spacing, StageClock& clock,
                              const LogFn& log, bool defer_listing = false);

// The three GIS stages above in order (for tests and callers that want the prepared input), the
// allocator's new memory on huge pages while they run (base::HugePageArenas).
// defer_listing: the removed-water listing is left to PreparedInput::complete (complete_input).
PreparedInput prepare_gis_input(const Options& opt, StageClock& clock, const ProgressFn& progress, const LogFn& log,
                                bool defer_listing = false);
PreparedInput prepare_gis_input(const Options& opt, const ProgressFn& progress, const LogFn& log);

// Read stage, .poly/.node inputs: the PSLG in its local frame and f from --spacing (default: the
// bounding-box diagonal / 20). Core code (poly_stage.cpp); everything else here is the GIS side.
PreparedInput prepare_poly_input(const Options& opt, const LogFn& log);

// Depths stage (GIS runs): the raster sampled at the vertices (positive up; the nearest valid
// cell for nodata, with a warning); empty without a raster.
std::vector<double> sample_depths(const mesh::MeshView& m, const PreparedInput& in, const LogFn& log);

// Terrain runs: (max, RMS) vertical error of the TIN (m.z) against the DEM, logged.
std::pair<double, double> tin_error(const mesh::MeshView& m, const sizing::Grid& dem, const LogFn& log);

}  // namespace fdr::pipeline
