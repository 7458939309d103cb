// The ADCIRC fort.14 / SCHISM hgrid.gr3 / hgrid.ll grid as the MDAL driver serves it: vertices,
// triangles and quads, depths, extent and CRS. Standard C++ only (no GDAL, no fdrmesh library), so
// that the driver MDAL loads into QGIS depends on nothing but the C++ runtime.
#pragma once
#include <string>
#include <vector>

namespace fdr_mdal {

struct Grid {
  std::vector<double> xyz;           // x, y and bed elevation (= -depth, positive up) per vertex
  std::vector<double> depth;         // the file's depth column, positive down
  std::vector<int> face_end;         // face i's nodes are face_nodes[face_end[i-1] .. face_end[i])
  std::vector<int> face_nodes;       // 0-based vertex indices, in the file's order
  double xmin = 0, xmax = 0, ymin = 0, ymax = 0;
  std::string crs;                   // "EPSG:4326" or empty (unknown)
  int vertex_count() const { return static_cast<int>(depth.size()); }
  int face_count() const { return static_cast<int>(face_end.size()); }
};

// True for the names the driver claims: fort.14, *.14, *.grd, *.gr3, *.ll (any case).
bool has_grid_name(const std::string& path);

// A cheap look at the first lines: a title, "NE NP" (two non-negative integers) and, when NP > 0,
// a node line "JN X Y DP". Rejects other files that share the extensions (Surfer .grd among them).
bool looks_like_grid(const std::string& path);

// Reads the whole grid. The boundary section after the elements is optional; when present its
// counts and node ids are checked, so a file cut short or with wrong counts is refused.
// Returns an empty string on success, else "<path>:<line>: <reason>" (out is then unspecified).
std::string read_grid(const std::string& path, Grid& out);

// The CRS of a read grid: hgrid.ll is lon/lat by definition; a fort.14 or gr3 whose every node lies
// within lon [-180, 360], lat [-90, 90] is taken as lon/lat (ADCIRC's spherical meshes store
// degrees; a projected mesh in metres lies far outside that box); otherwise unknown.
std::string grid_crs(const std::string& path, const Grid& g);

}  // namespace fdr_mdal
