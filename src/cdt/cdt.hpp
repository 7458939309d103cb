// Constrained Delaunay triangulation of a PSLG (Triangle .poly semantics for holes/exterior).
#pragma once
#include <string>
#include <vector>
#include "mesh/triangulation.hpp"
#include "pslg/pslg.hpp"

namespace fdr::cdt {

struct CdtOptions {
  // Which triangles are removed after the segments are in:
  //  kAuto: seeds (exterior + hole seeds, Triangle semantics) when the PSLG has holes,
  //         constraint parity otherwise; a PSLG without segments keeps its convex hull.
  //  kParity: keep regions at odd nesting depth (number of segment crossings from outside;
  //           breaklines, marker 4, are interior constraints and do not count).
  //  kSeeds: remove the exterior and the regions containing hole seeds.
  //  kNone: keep the convex hull (only the super-triangle is removed).
  enum class Regions { kAuto, kParity, kSeeds, kNone } regions = Regions::kAuto;
  std::string source = "input";  // named in error messages
};

struct CdtStats {
  std::size_t duplicate_points = 0;    // merged with an existing vertex
  std::size_t segments_split_at_vertices = 0;
  std::size_t removed_triangles = 0;
};

// Builds the CDT of `in` (local coordinates). Vertex i of the PSLG becomes vertex i of the
// triangulation (duplicates are merged into the first one). Throws fdr::Error
// (kInvalidGeometry) when two segments cross, naming both segments and the location.
mesh::Triangulation build_cdt(const pslg::Pslg& in, const CdtOptions& opt = {}, CdtStats* stats = nullptr);

// Inserts segment a-b into a triangulation that has no boundary yet (before region removal).
void insert_segment(mesh::Triangulation& tri, Index a, Index b, Index segment_id, const std::string& source,
                    CdtStats* stats);

}  // namespace fdr::cdt
