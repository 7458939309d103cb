// fdrmesh GIS API: the whole `fdrmesh mesh` run (OGR/GDAL inputs or .poly -> mesh + CRS + depths
// + boundaries + repairs + report) as one library call, and the writers for any mesh.
//
//   #include "pipeline/mesh_domain.hpp"
//   fdr::DomainOptions o;              // the fields of `fdrmesh mesh` options (pipeline/options.hpp)
//   o.input = "water.gpkg"; o.raster = "bathy.tif"; o.hmin = 200; o.hmax = 5000;
//   fdr::GisMesh m = fdr::mesh_domain(o);
//   fdr::write_mesh(m, "mesh.14");     // or o.outputs = {"mesh.14"} to write during the run
//
// Same result as the CLI with the same options, bit for bit (it is pipeline::run).
#pragma once
#include <string>
#include <vector>
#include "api/triangulate.hpp"
#include "base/progress.hpp"
#include "pipeline/options.hpp"
#include "pipeline/pipeline.hpp"

namespace fdr {

// The options of a GIS run are those of `fdrmesh mesh` (one field per long option); outputs
// listed in `outputs` are written during the run, atomically.
using DomainOptions = pipeline::Options;

// A mesh from the GIS pipeline: Mesh (view in the working CRS's local frame, report) plus
//   view.z        depth/elevation per vertex (positive up) when a raster was given,
//   view.crs_wkt  the working CRS, view.edges the boundaries (land/island/open/breakline kinds),
// and what the run did.
struct GisMesh : Mesh {
  std::string crs_name;                 // working CRS name ("" for .poly input)
  std::vector<io::RepairRow> repairs;   // every fix made to the input (world coordinates)
  std::vector<std::string> written;     // files written during the run (DomainOptions::outputs)
  std::vector<pipeline::StageTime> stages;
  std::string output_crs;               // --output-crs of the run ("" none)
};

// Runs one meshing job (pipeline::run). Throws fdr::Error with the CLI's exit code and message.
GisMesh mesh_domain(const DomainOptions& options, const ProgressFn& progress = {}, const LogFn& log = {});

// Writes a mesh in any output format (GPKG, 2DM, FORT14, MSH, UGRID, NODE, VTU), chosen by the
// extension of `path` or by `format` (as --of). Quality columns use Mesh::f when set; GIS meshes
// also get their repairs layer and CRS. Atomic (temporary file, then rename); Error(kOutputError).
// A GisMesh made with --output-crs cannot be written here (Error(kUsage)): list the file in
// DomainOptions::outputs instead (the reprojection is part of the run).
void write_mesh(const Mesh& mesh, const std::string& path, const std::string& format = "");
void write_mesh(const GisMesh& mesh, const std::string& path, const std::string& format = "");

}  // namespace fdr
