// Quality smoothing after FDR: free Steiner vertices (circumcentre insertions) move towards the
// area-weighted mean of their star's circumcentres (an optimal-Delaunay-triangulation step,
// Chen & Xu 2004), falling back to shorter steps; a move is kept only if, decided with exact
// predicates, every triangle of the star stays counter-clockwise, the mesh stays constrained
// Delaunay (no vertex inside the circumcircle of a moved triangle across an unconstrained
// edge), no subsegment becomes encroached, every moved triangle keeps R/f(c) <= B, the star's
// worst quality does not drop (and its min angle not below the --min-angle target) and its
// summed quality rises. Input vertices never move (Steiner vertices on segments slide along
// them), so the constraints, the domain
// and the FDR bound stay exactly as refinement left them. Vertices are cut into blocks of
// Morton-consecutive vertices; each sweep moves the blocks independently (concurrently when
// f.thread_safe()), each only where a move's triangles lie inside the block, then the deferred
// vertices in the blocks of a second, shifted blocking (concurrently too), then those deferred
// again on one thread: the result is deterministic and the same for every thread count. After the
// sweeps, free vertices are added in the wide angles of fixed vertices' fans (smooth_fan.hpp) and
// two more sweeps relax them.
#pragma once
#include <cstddef>
#include "mesh/triangulation.hpp"
#include "sizing/sizing_field.hpp"

namespace fdr::refine {

struct SmoothOptions {
  int passes = 4;               // sweeps over the free vertices
  double bound = 1.0;           // B: every moved triangle keeps R/f(c) <= B
  double min_angle_deg = 0.0;   // a move may not make a star's min angle drop below this
  bool fan_insertions = true;   // then free vertices added in wide fan angles (smooth_fan.hpp), two sweeps more
  std::size_t block_vertices = 8192;  // vertices per block of the concurrent sweeps (tests use small ones)
};

struct SmoothStats {
  std::size_t candidates = 0;   // free vertices
  std::size_t moves = 0;        // accepted moves, all passes
  std::size_t segment_moves = 0;  // of which slides of segment vertices along their segment
  std::size_t shifted = 0;      // tries in the second blocking (vertices the first deferred)
  std::size_t deferred = 0;     // tries left to the serial phase of a sweep (star or flips across blocks of both blockings)
  std::size_t fan_vertices = 0;  // free vertices added in wide fan angles
  int passes = 0;
};

SmoothStats smooth(mesh::Triangulation& tri, const sizing::SizingField& f, const SmoothOptions& options);

}  // namespace fdr::refine
