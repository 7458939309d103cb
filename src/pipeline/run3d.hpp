// The 3D run of `fdrmesh mesh`: read the PLC, make f, tetrahedralize (FDR), measure, check, write.
#pragma once
#include <chrono>
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>
#include "base/progress.hpp"
#include "pipeline/options.hpp"
#include "pipeline/stage_time.hpp"
#include "quality/report3d.hpp"
#include "tet/tet_mesh.hpp"
#include "tet/tetrahedralize.hpp"

namespace fdr::pipeline {

// A layer of a terrain volume: its material, tetrahedra and volume against the volume between
// its surfaces as triangulated.
struct LayerFigures {
  std::int32_t material = 0;
  std::string name;
  std::size_t tets = 0;
  double volume = 0, expected = 0;
  // Where the layer's pinch-outs were ended at walls (terrain::end_pinch_outs): the TIN triangles
  // it left and the volume it held there (now the neighbouring layer's).
  std::size_t pinch_out_triangles = 0;
  double pinch_out_volume = 0;
};

struct Result3 {
  tet::TetMesh mesh;
  quality::Report3 report;
  bool measured = false;              // false: -q without --report or VTU output (counts only)
  std::vector<std::string> written;   // output paths
  std::vector<StageTime> stages;
  std::vector<LayerFigures> layers;   // terrain runs (--dem): one per layer, from the top down
};

// Whether the run is a 3D one: a 3D input (api: a .poly or .node whose dimension line says 3,
// .smesh, .off, .stl, .ply), or a terrain volume (--dem).
bool is_3d_run(const Options& opt);

// Every usage error of a 3D run, before any I/O: 2D-only options given (named), outputs that are
// not 3D formats, a bound that is not positive. Throws Error(kUsage).
void check_3d_options(const Options& opt);

// The options every 3D run shares (--bound, --sliver-angle, --no-sliver-removal). Throws
// Error(kUsage).
void check_tet_options(const Options& opt);
// The mesher's options from the run's: B, the vertex cap over the PLC's own points, slivers.
tet::TetOptions tet_options(const Options& opt, std::size_t plc_points);

// True if `path` names a GeoPackage (.gpkg, any case): the top surface of a terrain run.
bool is_gpkg_path(const std::string& path);

// Every usage error of a terrain run (--dem), before any I/O: a base missing, --raster given
// beside --dem, --points beside --wells, outputs that are not 3D formats, .poly (the terrain PLC) or .gpkg (the
// top surface), a negative depth grade or minimum thickness, hmin above hmax, a bound that is not
// positive, a well spacing that is not. Without INPUT (nor --land) the DEM's valid data is the
// domain. Throws Error(kUsage).
void check_terrain_options(const Options& opt);

// The terrain options given to a run without --dem (usage error naming the first); used by the 2D
// plan and by the 3D run of a PLC file.
void check_no_terrain_options(const Options& opt);

// The run's whole wall time since t_start, its peak RSS and its stages' times, into r.report.
void time_report3(Result3& r, std::chrono::steady_clock::time_point t_start);

// Runs one 3D meshing job (a terrain volume through the GIS side: terrain_run.hpp); the same all-or-nothing writing as pipeline::run. Throws fdr::Error.
Result3 run3d(const Options& opt, const ProgressFn& progress, const LogFn& log);

// What the command line prints after a 3D run: the text report, stages, written files.
void write_summary3(const Result3& r, std::ostream& out);

}  // namespace fdr::pipeline
