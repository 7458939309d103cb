// The GIS side of the pipeline behind one table of functions: everything that needs GDAL, PROJ,
// netCDF or SQLite (OGR/GDAL inputs, depths, reprojection, the mesh writers and readers).
//
// The table lives in the GIS library fdrmesh_gis.so (installed in <libdir>/fdrmesh), on top of the
// shared core. Programs that link that library (tests, the Python module, users of fdrmesh::gis)
// have it built in. The fdrmesh command links only the core and loads the library the first time a
// run needs it, so that a .poly run without output files never maps the many shared libraries
// GDAL pulls in. Both sides share the core's one copy of every type and counter.
#pragma once
#include <string>
#include <utility>
#include <vector>
#include "base/progress.hpp"
#include "base/version.hpp"
#include "io/writer.hpp"
#include "mesh/mesh_view.hpp"
#include "pipeline/gis_stage.hpp"
#include "pipeline/options.hpp"
#include "pipeline/run3d.hpp"
#include "pipeline/stage_time.hpp"
#include "sizing/grid.hpp"

namespace fdr::pipeline {

struct GisBackend {
  // Checked when the library is loaded: a library left from another version is refused.
  const char* version;
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
  // A terrain volume (--dem): the whole 3D run from GIS layers (terrain_run.hpp).
  Result3 (*run_terrain)(const Options&, const ProgressFn&, const LogFn&);
};

// The table: built in, or loaded from the GIS library (throws Error(kInternal) naming the paths
// tried and the loader's message when the library is missing or from another version).
const GisBackend& gis_backend();

// True once the table is available without loading anything more (built in, or loaded already).
bool gis_backend_loaded();

}  // namespace fdr::pipeline

// Defined by the GIS library (gis_backend_impl.cpp); the core refers to it weakly and, when the
// program does not link the library, finds it with dlsym after loading it.
extern "C" const fdr::pipeline::GisBackend* fdr_gis_backend_table();
