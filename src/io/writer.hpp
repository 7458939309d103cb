// Mesh writers for modelers' formats (GeoPackage, SMS 2dm, Gmsh msh, Triangle node/ele, VTU, ADCIRC fort.14, UGRID,
// Telemac Selafin + .cli, SCHISM hgrid.gr3/.ll, Delft3D FM net file).
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>
#include "base/point3.hpp"
#include "io/postgis_options.hpp"
#include "mesh/mesh_view.hpp"
#include "sizing/sizing_field.hpp"

namespace fdr::io {

enum class Format { kGpkg, k2dm, kMsh, kNode, kVtu, kFort14, kUgrid, kSelafin, kGr3, kLl, kDflowfm, kPostgis };

// What the option table publishes about each format (--help, --json-usage, the QGIS plugin).
struct FormatInfo {
  Format format;
  const char* name;        // --of value (format_name)
  const char* extensions;  // e.g. ".14 .grd fort.14"
  const char* label;       // short description ("ADCIRC fort.14 mesh")
  const char* carries;     // depth sign, boundaries, CRS
};
// Every writable format, in the order they are documented.
const std::vector<FormatInfo>& format_infos();

// Short upper-case name of a format as accepted by --of ("GPKG", "2DM", ...).
const char* format_name(Format f);

// Format from the file name (.gpkg .2dm .msh .node/.ele .vtu .14/.grd/fort.14 .nc .slf .gr3 .ll,
// *_net.nc), or from `of_override` (GPKG, 2DM, MSH, NODE, VTU, FORT14, UGRID, SELAFIN, GR3, LL,
// DFLOWFM, POSTGRESQL; case-insensitive) when non-empty. A "PG:" connection string is PostGIS.
// Unknown name or extension -> Error(kUsage) listing the known ones.
Format format_from_path(const std::string& path, const std::string& of_override = "");

// One fix made while cleaning the input (reported in the GeoPackage `repairs` layer).
struct RepairRow {
  std::string kind;     // e.g. "snap", "split_crossing", "drop_sliver"
  double x = 0, y = 0;  // world coordinates
  double size = 0;      // size of the fix (distance moved, area dropped, ...)
  std::string reason;
  std::int32_t part = -1;  // input ring/line id, -1 unknown
  std::vector<std::int64_t> ids{};  // vertex/segment ids concerned (.poly inputs: input ids)
};

class BoundaryCache;  // io/boundaries.hpp

struct WriteOptions {
  // Spacing function in the mesh's local frame; when set, triangles get an R/f(c)
  // column and nodes without a per-vertex f get f evaluated at the vertex.
  const sizing::SizingField* f = nullptr;
  double bound_B = 0;  // the refinement bound B, stored in the metadata
  std::vector<std::pair<std::string, std::string>> metadata;  // version, command line, inputs, ...
  std::vector<RepairRow> repairs;
  std::string title;  // mesh name (2dm MESHNAME, fort.14 title line, msh/vtu/UGRID comment)
  std::optional<std::string> output_crs_wkt;  // handled by the caller (reprojection); ignored here
  // z sign convention of ADCIRC fort.14: MeshView z is positive up, fort.14 stores depth positive
  // down, so DP = -z by default. false writes DP = z unchanged (z already holds depths).
  bool fort14_depth_positive_down = true;
  // GeoPackage R-tree spatial indexes on the nodes/triangles/boundaries/repairs layers (what QGIS
  // uses for fast panning), bulk-loaded after the rows are written.
  bool gpkg_spatial_index = true;
  // GeoPackage in lon/lat of a global mesh: triangles and boundary lines across the antimeridian
  // written with their longitudes continued past +-180 (io/antimeridian_ll.hpp).
  bool continue_across_antimeridian = false;
  // A global mesh on the sphere: Earth-centred Cartesian coordinates in metres, one per vertex, on
  // the sphere of radius `sphere_radius`. VTU and msh write them as node coordinates (what
  // sphere-based models and 3D viewers take); the other formats keep the mesh's own coordinates.
  const std::vector<Point3>* sphere_xyz = nullptr;
  double sphere_radius = 0;
  // Per-triangle values precomputed in the metric frame (used instead of computing them from the
  // written coordinates, e.g. when nodes are reprojected to lon/lat by --output-crs).
  const std::vector<double>* triangle_r_over_f = nullptr;
  const std::vector<double>* triangle_min_angle = nullptr;
  const std::vector<double>* triangle_area = nullptr;
  const std::vector<double>* triangle_quality = nullptr;  // 4 sqrt(3) area / sum of squared edges
  // Telemac: Selafin in double precision ("SERAFIND") instead of single; LIHBOR LIUBOR LIVBOR
  // of the open-boundary nodes in the .cli (default 5 4 4: prescribed elevation, free velocity).
  bool slf_double = false;
  std::array<int, 3> telemac_open_codes{5, 4, 4};
  // Boundary loops shared by the writers of one mesh (write_meshes sets it when several outputs
  // carry boundaries, so they are extracted once); null: each writer extracts its own.
  BoundaryCache* boundary_cache = nullptr;
  // PostGIS output ("PG:..." path): table prefix, schema, replacing an existing mesh.
  PostgisOptions postgis;
};

// Parses --telemac-open "L,U,V" (three Telemac boundary codes 0..6, comma or blank separated);
// throws Error(kUsage) otherwise.
std::array<int, 3> parse_telemac_codes(const std::string& text);

// Writes `mesh` to `path` in `format`. The file is written to "<path>.tmp-XXXXXX" in the same
// folder and renamed to `path` on success; on any failure the temp file is removed and
// Error(kOutputError, "<path>: <reason>") is thrown, so no half-written file ever remains.
// Format::kNode writes both <base>.node and <base>.ele (path may end in either); Format::kSelafin
// writes <path> and <base>.cli beside it.
void write_mesh(const mesh::MeshView& mesh, const std::string& path, Format format,
                const WriteOptions& options = {});

}  // namespace fdr::io
