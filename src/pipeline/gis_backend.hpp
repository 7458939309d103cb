// The GIS side of the pipeline behind one table of functions: everything that needs GDAL, PROJ,
// netCDF or SQLite (OGR/GDAL inputs, depths, reprojection, the mesh writers and readers).
//
// Programs that link `fdr_pipeline` (tests, the Python module, users of fdrmesh::gis) have it
// built in. The fdrmesh command links only `fdr_pipeline_core` and loads the table from the
// shared module fdrmesh_gis.so (installed in <libdir>/fdrmesh) the first time a run needs it, so
// that a .poly run without output files never maps the ~110 shared libraries GDAL pulls in
// (README "Benchmark": start-up memory).
#pragma once
#include <cstddef>
#include <string>
#include <utility>
#include <vector>
#include "base/progress.hpp"
#include "base/version.hpp"
#include "io/writer.hpp"
#include "mesh/mesh_view.hpp"
#include "pipeline/gis_stage.hpp"
#include "pipeline/options.hpp"
#include "pipeline/stage_time.hpp"
#include "predicates/predicates.hpp"
#include "sizing/grid.hpp"

namespace fdr::pipeline {

struct GisBackend {
  // Checked when the module is loaded (a module left from another build is refused): the version
  // and the layouts of the types that cross between the program and the module.
  const char* version;
  std::size_t layout[5];
  // Read, spacing and clean stages of a GIS run (read_gis_input, gis_spacing, clean_gis_input).
  PreparedInput (*prepare_gis)(const Options&, StageClock&, const ProgressFn&, const LogFn&);
  std::vector<double> (*sample_depths)(const mesh::MeshView&, const PreparedInput&, const LogFn&);
  std::pair<double, double> (*tin_error)(const mesh::MeshView&, const sizing::Grid&, const LogFn&);
  // --output-crs: the mesh reprojected from the run's working CRS (in.frame) to `crs`.
  void (*reproject_mesh)(mesh::MeshView&, const PreparedInput&, const std::string& crs);
  void (*write_meshes)(const mesh::MeshView&, const std::vector<std::string>& paths,
                       const std::vector<io::Format>&, const io::WriteOptions&, unsigned threads);
  void (*write_mesh)(const mesh::MeshView&, const std::string& path, io::Format, const io::WriteOptions&);
  // --write-spacing: the final spacing grid of a GIS run as GeoTIFF.
  void (*write_spacing_geotiff)(const PreparedInput&, const std::string& path);
  mesh::MeshView (*read_mesh)(const std::string& path);
  sizing::Grid (*read_raster_native)(const std::string& path, Point2 origin);
  // The predicate counters of this thread in the table's copy of the predicates (a module has
  // its own), returned and reset: the caller adds them to its own (same figures as built in).
  predicates::Counters (*take_predicate_counters)();
};

// What `layout` must hold for this build.
#define FDR_GIS_BACKEND_LAYOUT                                                                    \
  {                                                                                               \
    sizeof(::fdr::pipeline::Options), sizeof(::fdr::pipeline::PreparedInput),                     \
        sizeof(::fdr::mesh::MeshView), sizeof(::fdr::io::WriteOptions), sizeof(::fdr::sizing::Grid) \
  }

// The table: built in, or loaded from the module (throws Error(kInternal) naming the paths tried
// and the loader's message when the module is missing or from another build).
const GisBackend& gis_backend();

// True once the table is available without loading anything more (built in, or loaded already).
bool gis_backend_loaded();

}  // namespace fdr::pipeline

// Defined by the built-in table (gis_backend_impl.cpp, in fdr_pipeline); weak in the core.
extern "C" const fdr::pipeline::GisBackend* fdr_builtin_gis_backend();
// Exported by the module (gis_module.cpp).
extern "C" const fdr::pipeline::GisBackend* fdr_gis_module_backend();
