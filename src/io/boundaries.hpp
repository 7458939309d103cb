// Boundary loops and runs of a finished mesh: the one source of boundary tags, order and
// orientation for every writer (fort.14, hgrid.gr3/.ll, 2DM nodestrings, Selafin IPOBO + .cli,
// Delft3D FM net file edge types), so that all formats of one run agree.
#pragma once
#include <cstdint>
#include <mutex>
#include <string>
#include <vector>
#include "mesh/mesh_view.hpp"

namespace fdr::io {

// What a boundary edge or run is, as the model formats see it.
enum class BoundaryKind : std::int8_t {
  kOpen = 0,    // open (ocean / liquid) boundary: EdgeKind::kOpen on the mesh boundary
  kLand = 1,    // wall on an outer loop (mainland): ADCIRC IBTYPE 0, SCHISM type 0
  kIsland = 2,  // wall on an inner loop (island, hole): ADCIRC IBTYPE 1, SCHISM type 1
};

// One closed loop of boundary edges (edges with a triangle on one side only).
//
//   nodes[0] -> nodes[1] -> ... -> nodes[k-1] -> nodes[0]   with the mesh on the LEFT of each step:
//   outer loops run counter-clockwise, inner loops (islands) clockwise.
//
// edge_open[i] tells whether the edge nodes[i] -> nodes[(i+1) % k] is open.
struct BoundaryLoop {
  bool outer = true;                // positive signed area (counter-clockwise)
  std::vector<Index> nodes;         // >= 3 nodes, first not repeated at the end
  std::vector<char> edge_open;      // same length as nodes
  double signed_area = 0;           // of the polygon nodes[] (local frame)
};

// A maximal stretch of one kind along a loop. Consecutive runs share their end nodes (the node
// where an open boundary meets land belongs to both). A loop of a single kind gives one closed
// run (nodes not repeated).
struct BoundaryRun {
  BoundaryKind kind = BoundaryKind::kLand;
  std::size_t loop = 0;            // index into Boundaries::loops
  bool closed = false;
  std::vector<Index> nodes;        // >= 2 nodes in loop order
};

struct Boundaries {
  std::vector<BoundaryLoop> loops;  // outer loops first, then inner loops; see extract_boundaries
  std::vector<BoundaryRun> runs;    // loop by loop, in loop order
  // Boundary nodes in loop order, each loop once (the Telemac IPOBO / .cli order).
  std::vector<Index> ordered_nodes() const;
  // True when a node is on an open edge (the open runs' nodes, end nodes included).
  std::vector<char> open_nodes(std::size_t num_vertices) const;
};

// Builds the boundary loops of `m` from its triangles. Kinds come from MeshView::edges: a
// boundary edge listed there with marker EdgeKind::kOpen is open; every other boundary edge is a
// wall (land on outer loops, island on inner loops, whatever its marker).
//
// Order (deterministic, independent of the vertex numbering where possible):
//  * loops: outer loops before inner loops; within each group by their start node (below) in
//    (x + y, x, index) order, i.e. south-west first;
//  * each loop starts at its south-west-most node (smallest x + y) or, when the loop has open
//    and wall edges, at the start of the first open run met from there along the loop, so the
//    outer boundary lists an open boundary first (ADCIRC, SCHISM and Telemac habit).
// Pinch nodes (a node on two loops, or twice on one) are allowed here; callers that cannot
// represent them (Selafin IPOBO) check with pinch_node().
// Throws Error(kOutputError) naming `path` if the triangles do not form a valid surface (an edge
// used twice in the same direction).
Boundaries extract_boundaries(const mesh::MeshView& m, const std::string& path);

// extract_boundaries once for several writers of the same mesh, from any thread: the first
// get() extracts (naming its path in errors; after a failure the next get() tries again), the
// others wait for it and share the result.
class BoundaryCache {
 public:
  const Boundaries& get(const mesh::MeshView& m, const std::string& path);

 private:
  std::mutex mu_;
  bool done_ = false;
  Boundaries b_;
};

// The mesh's boundaries for a writer: from `cache` when given, else extracted into `own`.
const Boundaries& boundaries_for(const mesh::MeshView& m, const std::string& path, BoundaryCache* cache,
                                 Boundaries& own);

// The first node that appears more than once in the loops' node lists, or kNoId.
Index pinch_node(const Boundaries& b, std::size_t num_vertices);

}  // namespace fdr::io
