// Internals shared by the io writers and readers: boundary chains, marker names, number formatting.
#pragma once
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>
#include "base/error.hpp"
#include "base/out_file.hpp"
#include "io/boundaries.hpp"
#include "io/writer.hpp"
#include "mesh/mesh_view.hpp"

namespace fdr::io::detail {

// The all-or-nothing file output of base, under the names the io writers use.
using fdr::commit_all;
using fdr::fail_output;
using fdr::TempFile;
using fdr::TextOut;

// Name of an edge marker: "none", "land", "island", "open", "breakline", else "marker<N>".
std::string kind_name(std::int32_t marker);
// Inverse of kind_name for the five known names; returns false for anything else.
bool kind_from_name(std::string_view name, std::int32_t& marker);

// The $Comments line of an msh written on the sphere, followed by the radius in metres: what tells
// the reader to turn x, y, z back into lon/lat and take the elevation from $NodeData "z".
inline constexpr std::string_view kMshSphereComment = "fdrmesh sphere_radius_m";

// An ordered chain of constrained edges sharing (marker, part).
struct Chain {
  std::int32_t marker = 0;
  std::int32_t part = 0;
  bool closed = false;        // a cycle: last node connects back to nodes[0] (not repeated)
  std::vector<Index> nodes;   // >= 2 nodes
};

// Orders the constrained edges of each (marker, part) group into paths and cycles.
// Deterministic: groups sorted by (marker, part); each walk starts at the endpoint of the
// earliest-listed unused edge (path ends first, then cycles); each chain is oriented so the
// mesh lies on its left (counter-clockwise around the domain, clockwise around islands) when
// most of its edges are boundary edges, else it follows the stored direction of its first edge.
std::vector<Chain> build_chains(const mesh::MeshView& m);

// Rebuilds MeshView::edges from chains (consecutive node pairs, closing edge for cycles).
void edges_from_chain(mesh::MeshView& m, const std::vector<Index>& nodes, bool closed,
                      std::int32_t marker, std::int32_t part);

// Checks array sizes, vertex ids and finite coordinates; throws kOutputError naming `path`.
void validate_for_output(const mesh::MeshView& m, const std::string& path);

// Per-triangle geometry in the local frame.
// The metadata table's rows (GeoPackage, PostGIS): the caller's, then the title and the bound B
// when the caller's rows lack them.
std::vector<std::pair<std::string, std::string>> metadata_rows(const WriteOptions& o);

double triangle_area(const mesh::MeshView& m, std::size_t t);
double triangle_min_angle_deg(const mesh::MeshView& m, std::size_t t);
// Mean-ratio quality 4 sqrt(3) area / (sum of squared edges), 1 for an equilateral triangle.
double triangle_quality(const mesh::MeshView& m, std::size_t t);
// The triangle's quality column: the precomputed value when given, else triangle_quality.
double triangle_quality(const mesh::MeshView& m, std::size_t t, const WriteOptions& o);
// Circumradius and circumcentre (local frame); R = +inf for a degenerate triangle.
double circumradius(const mesh::MeshView& m, std::size_t t, Point2& centre);
// Distance from each vertex to its nearest neighbour over triangle edges (+inf if isolated).
std::vector<double> nearest_neighbour_distance(const mesh::MeshView& m);

// Boundary node lists as each model format writes them, all from extract_boundaries (same
// runs, same order, same orientation: mesh on the left); only closure conventions differ:
//  * kFort14: a closed run (an island, or an outer loop of one kind) repeats its first node at
//    the end (ADCIRC fort.14 rule);
//  * kGr3/kLl: islands are not repeated (SCHISM closes them itself); an outer loop of one kind is
//    split in two segments (SCHISM refuses a looped exterior segment);
//  * k2dm: every closed run is split in two nodestrings (SMS refuses a nodestring that starts and
//    ends on the same node).
enum class BoundaryFlavor { kFort14, kGr3, kLl, k2dm };
struct BoundaryList {
  BoundaryKind kind = BoundaryKind::kLand;
  std::vector<Index> nodes;
};
struct BoundaryLists {
  std::vector<BoundaryList> open, walls;  // walls: land and island runs, in loop order
  std::vector<BoundaryList> all() const {
    std::vector<BoundaryList> r = open;
    r.insert(r.end(), walls.begin(), walls.end());
    return r;
  }
};
BoundaryLists model_boundary_lists(const mesh::MeshView& m, const std::string& path, BoundaryFlavor flavor,
                                   BoundaryCache* cache = nullptr);

// Format back ends (write_mesh validates the mesh first and dispatches here).
void write_gpkg(const mesh::MeshView& m, const std::string& path, const WriteOptions& o);
void write_ugrid(const mesh::MeshView& m, const std::string& path, const WriteOptions& o);
// ADCIRC fort.14 and SCHISM hgrid.gr3 / hgrid.ll (flavor kFort14, kGr3, kLl).
void write_adcirc(const mesh::MeshView& m, const std::string& path, const WriteOptions& o, BoundaryFlavor flavor);
// Telemac Selafin geometry <path> and boundary conditions <base>.cli.
void write_selafin(const mesh::MeshView& m, const std::string& path, const WriteOptions& o);
// Delft3D FM UGRID net file.
void write_dflowfm_net(const mesh::MeshView& m, const std::string& path, const WriteOptions& o);

// Lower-case extension including the dot (".gpkg"), "" if none; and the file name part.
std::string lower_extension(const std::string& path);
std::string file_name(const std::string& path);
std::string to_lower(std::string s);

}  // namespace fdr::io::detail
