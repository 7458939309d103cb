// The steps of build_cdt (cdt.hpp), each usable and testable on its own.
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>
#include "cdt/cdt.hpp"

namespace fdr::cdt {

// A point as "(x, y)" with 15 significant digits, for error messages.
std::string point_text(Point2 p);

// The input points as vertices 0..n-1 (with their markers) and a super-triangle of three more
// vertices around `box`, their bounding box.
void start_triangulation(mesh::Triangulation& T, const pslg::Pslg& in, const Box2& box);
// An insertion order (a permutation of 0..n-1, the same for the same input): along a Hilbert
// curve over `box`, or with `rounds` in random rounds of doubling size, each along the curve.
std::vector<Index> insertion_order(const std::vector<Point2>& points, const Box2& box, bool rounds);
// Inserts the input points along the Hilbert curve, or, when that costs more than a constant
// work per point, anew in random rounds (CdtStats::random_rounds); returns per input point the vertex it became (a
// duplicate: the earlier vertex at the same place).
std::vector<Index> insert_points(mesh::Triangulation& T, const pslg::Pslg& in, const Box2& box,
                                 const std::string& source, CdtStats* stats);
// Records the input segments (with aliased ends) and inserts each as a chain of constrained edges.
void insert_segments(mesh::Triangulation& T, const pslg::Pslg& in, const std::vector<Index>& alias,
                     const std::string& source, CdtStats* stats);

// The regions of a triangulation: connected components of live triangles across unconstrained
// edges, and how they touch across constrained ones.
struct Components {
  std::vector<Index> of_slot;  // per triangle slot its component (kNoId: dead)
  std::vector<std::vector<std::pair<Index, int>>> adjacent;  // per component: (neighbour, depth step)
  std::vector<bool> touches_super;  // per component: has a super-triangle vertex
  Index size() const { return static_cast<Index>(adjacent.size()); }
};
// Steps across breaklines (marker pslg::kBreaklineMarker) are 0, across other constraints 1.
Components find_components(const mesh::Triangulation& T);
// Per component the fewest non-breakline constraints crossed from a component touching the
// super-triangle (-1: unreachable).
std::vector<int> nesting_depth(const Components& c);
// Which components go: by the mode (kAuto resolved from the input), then by the hole seeds.
// Throws kInvalidGeometry for a hole seed outside the domain or on a segment or vertex.
std::vector<bool> components_to_remove(const mesh::Triangulation& T, const pslg::Pslg& in, const CdtOptions& opt,
                                       const Components& c, const std::vector<int>& depth);
// Per triangle the Pslg::regions entry whose seed is in its component (a later seed wins).
void assign_regions(mesh::Triangulation& T, const pslg::Pslg& in, const Components& c);
// Removes the removed components' triangles and every super-triangle's; input segments between
// two removed triangles are dropped; boundary edges left unconstrained (the convex hull) become
// constrained edges of no input segment.
void remove_components(mesh::Triangulation& T, const Components& c, const std::vector<bool>& remove, CdtStats* stats);
// All of the above after the segments are in.
void remove_regions(mesh::Triangulation& T, const pslg::Pslg& in, const CdtOptions& opt, CdtStats* stats);

}  // namespace fdr::cdt
