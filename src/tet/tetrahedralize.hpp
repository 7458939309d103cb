// The 3D mesher's one call: a conforming Delaunay tetrahedralization of a PLC refined by FDR
// until every tetrahedron has R/f(c) <= B (the paper's three rules) and radius-edge <= 2.
#pragma once
#include <cstddef>
#include <functional>
#include <string>
#include <vector>
#include "base/point3.hpp"
#include "plc/plc.hpp"
#include "sizing/spacing3d.hpp"
#include "tet/tet_mesh.hpp"

namespace fdr::tet {

struct TetOptions {
  double bound = 0;               // B; 0: the default, 1 as in 2D (radius-edge <= 2 is enforced apart)
  bool refine = true;             // false: the conforming Delaunay tetrahedralization only
  std::size_t max_vertices = 0;   // a cap on the vertices (0: automatic); reaching it is reported
  // After rule 3, tetrahedra whose smallest dihedral angle is under sliver_angle_deg are split by a
  // point near their circumcentre that makes no new sliver (tet/slivers.hpp); R/f <= B, radius-edge
  // <= 2 and the conforming Delaunay property are kept.
  bool remove_slivers = true;
  double sliver_angle_deg = 15.0;
  // TetMesh::cell_fields (r_over_f, radius_edge, min_dihedral_deg) filled; a caller that measures
  // every tetrahedron itself turns it off and spares computing and holding them twice.
  bool cell_fields = true;
  std::function<void(double)> progress;  // fraction done in [0, 1], for the CLI's 0...10...20
};

// A place where a guarantee could not be met (e.g. a small input angle protected by shells).
struct Shortfall {
  Point3 where;
  std::string what;
};

struct TetStats {
  std::size_t input_vertices = 0;
  std::size_t segment_splits = 0;  // rule 1
  std::size_t facet_splits = 0;    // rule 2
  std::size_t tet_splits = 0;      // rule 3
  std::size_t rejected = 0;        // circumcentres not inserted because they encroached
  double bound = 0;                // the B used
  bool capped = false;             // max_vertices reached before every rule was met
  std::vector<Shortfall> shortfalls;
  // Sliver removal: the threshold used (0: not run), the points it inserted, the times a sliver's
  // point yielded to the boundary (split instead), and the domain's smallest dihedral angles before
  // it ran (histogram of each tetrahedron's smallest angle in 10-degree bins, as the report's) and
  // after (slivers still under the threshold, the first few listed with their centroids).
  double sliver_angle_deg = 0;
  std::size_t sliver_splits = 0;
  std::size_t sliver_yields = 0;
  std::size_t slivers_before = 0;
  std::size_t slivers_left = 0;
  double min_dihedral_before_deg = 0;
  std::vector<std::size_t> dihedral_hist_before;
  std::vector<Shortfall> slivers_listed;
  // Theorems 4.4 and 4.5's per-vertex figures (shortest and longest edge at a vertex over f there)
  // on the mesh rule 3 leaves, before sliver removal adds vertices the theorems do not cover: the
  // report judges the theorems on these and shows the final mesh's figures beside them. Set only
  // when sliver removal ran; without it the final mesh is rule 3's.
  bool fdr_vertex_figures = false;
  double fdr_nn_over_f_min = 0;
  double fdr_el_over_f_max = 0;
};

struct TetResult {
  TetMesh mesh;   // tetrahedra with material ids, subfacets with markers, subsegments
  TetStats stats;
};

// Throws fdr::Error (plc::check's exit codes) on bad input; nothing else is changed.
TetResult tetrahedralize(const plc::Plc& plc, const sizing::SizingField3& f, const TetOptions& options = {});

}  // namespace fdr::tet
