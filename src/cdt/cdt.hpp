// Constrained Delaunay triangulation of a PSLG (Triangle .poly semantics for holes/exterior).
#pragma once
#include <string>
#include <vector>
#include "mesh/triangulation.hpp"
#include "pslg/pslg.hpp"
#include "pslg/resolve.hpp"

namespace fdr::cdt {

struct CdtOptions {
  // Which triangles are removed after the segments are in:
  //  kAuto: seeds (exterior + hole seeds, Triangle semantics) when the PSLG has holes,
  //         constraint parity otherwise; a PSLG without segments keeps its convex hull.
  //  kParity: keep regions at odd nesting depth (number of segment crossings from outside;
  //           breaklines, marker 4, are interior constraints and do not count).
  //  kSeeds: remove the exterior and the regions containing hole seeds.
  //  kNone: keep the convex hull (only the super-triangle is removed).
  //  kHull: the convex hull of all vertices bounds the domain (Triangle -c); hole seeds remove
  //         their regions.
  // With kSeeds and kHull a hole seed that lies outside the domain, on a segment or on a vertex
  // is an error (kInvalidGeometry naming the hole index and its world coordinates).
  enum class Regions { kAuto, kParity, kSeeds, kNone, kHull } regions = Regions::kAuto;
  std::string source = "input";  // named in error messages
  // true: the input is first resolved by pslg::resolve (crossings split, duplicates and
  // overlaps merged, ...; see pslg/resolve.hpp) and vertex ids refer to the resolved PSLG.
  // false: conflicts throw, as documented for build_cdt.
  bool resolve = false;
  std::vector<pslg::Repair>* repairs = nullptr;  // fixes made by resolve (optional)
};

struct CdtStats {
  std::size_t duplicate_points = 0;    // merged with an existing vertex
  std::size_t segments_split_at_vertices = 0;
  std::size_t removed_triangles = 0;
  // Work counts (for complexity checks): visibility-walk steps while inserting the input points,
  // triangles created by those insertions, and the edges segment recovery examined (rotations
  // around a segment's end, crossed edges, flip attempts).
  std::size_t walk_steps = 0;
  std::size_t new_triangles = 0;
  std::size_t recovery_steps = 0;
  // The points were inserted anew in random rounds (steps.hpp insert_points); the counts above
  // include the abandoned first pass.
  bool random_rounds = false;
};

// Builds the CDT of `in` (local coordinates). An input segment that ends up (partly) between two
// removed regions is outside the domain: its Triangulation::input_segments entry gets b = a. Vertex i of the PSLG becomes vertex i of the
// triangulation (duplicates are merged into the first one). Throws fdr::Error
// (kInvalidGeometry) when two segments cross, naming both segments and the location.
mesh::Triangulation build_cdt(const pslg::Pslg& in, const CdtOptions& opt = {}, CdtStats* stats = nullptr);

// Inserts segment a-b into a triangulation that has no boundary yet (before region removal).
void insert_segment(mesh::Triangulation& tri, Index a, Index b, Index segment_id, const std::string& source,
                    CdtStats* stats);

}  // namespace fdr::cdt
