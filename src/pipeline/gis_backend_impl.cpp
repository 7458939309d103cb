// The GIS side of the pipeline as one table (gis_backend.hpp), exported by the GIS library
// fdrmesh_gis.so: linked by tests and the Python module, loaded by the fdrmesh command.
#include "base/error.hpp"
#include "gis/raster_input.hpp"
#include "gis/raster_output.hpp"
#include "io/reader.hpp"
#include "io/write_many.hpp"
#include "pipeline/gis_backend.hpp"
#include "pipeline/reproject_mesh.hpp"
#include "pipeline/terrain_run.hpp"

namespace fdr::pipeline {
namespace {

PreparedInput prepare_gis(const Options& opt, StageClock& clock, const ProgressFn& progress, const LogFn& log) {
  // read (gis), spacing (sizing), clean, resample (pslg); the removed-water listing completes
  // after the refinement (pipeline.cpp: complete_input)
  return prepare_gis_input(opt, clock, progress, log, true);
}

const gis::Frame& frame_of(const PreparedInput& in) {
  if (!in.frame) throw Error(ExitCode::kInternal, "no working CRS (not a GIS run)");
  return *in.frame;
}

void reproject(mesh::MeshView& m, const PreparedInput& in, const std::string& crs) {
  reproject_mesh(m, frame_of(in), crs);
}

void write_spacing(const PreparedInput& in, const std::string& path) {
  gis::write_grid_geotiff(*in.spacing_grid, frame_of(in), path);
}

void write_many(const mesh::MeshView& m, const std::vector<std::string>& paths, const std::vector<io::Format>& fmts,
                const io::WriteOptions& wo, unsigned threads) {
  io::write_meshes(m, paths, fmts, wo, threads);
}

mesh::MeshView read_mesh(const std::string& path) { return io::read_mesh(path); }

const GisBackend kTable{
    kVersion,
    &prepare_gis,
    &pipeline::sample_depths,
    &pipeline::tin_error,
    &reproject,
    &write_many,
    &io::write_mesh,
    &write_spacing,
    &read_mesh,
    &gis::read_raster_native,
    &run_terrain,
};

}  // namespace
}  // namespace fdr::pipeline

extern "C" __attribute__((visibility("default"))) const fdr::pipeline::GisBackend* fdr_gis_backend_table() {
  return &fdr::pipeline::kTable;
}
