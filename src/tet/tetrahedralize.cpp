#include "tet/tetrahedralize.hpp"
#include "base/debug.hpp"
#include "base/error.hpp"
#include "base/step_laps.hpp"
#include "plc/check.hpp"
#include "tet/dt_queries.hpp"
#include "tet/refiner3.hpp"
#include "tet/tet_output.hpp"

namespace fdr::tet {

TetResult tetrahedralize(const plc::Plc& plc, const sizing::SizingField3& f, const TetOptions& options) {
  StepLaps lap(debug::Aid::kStages, "stage tet:");
  const plc::FacetTriangulation ft = plc::check_and_triangulate(plc, {.closed = !plc.facets.empty()});
  lap("plc check and facets");
  Refiner3 r(plc, ft, f, options);
  lap("start (points, boundary)");
  r.conform();
  lap("first conform");
  if (options.refine) {
    r.refine();
  } else {
    r.flood_regions();
  }
  lap("refine");
  // A boundary left unrecovered lets the region flood cross it: the mesh would lose its volume.
  // At the vertex cap the run stops with its own exit code and message instead.
  if (!r.stats().capped) {
    const std::string missing = r.missing_boundary();
    if (!missing.empty())
      throw Error(ExitCode::kInternal, plc.source + ": the 3D refinement left " + missing +
                                           (r.gave_up() ? " (boundary splits stopped at their cap)" : "") +
                                           "; nothing written");
  }
  lap("boundary check");
  release_query_scratch();  // before the mesh is copied out beside the tetrahedralization
  TetResult out;
  out.mesh = make_tet_mesh(r, options.cell_fields);
  lap("mesh out");
  // Facets that enclose a volume and no tetrahedron inside: a boundary subfacet was lost and the
  // outside flooded in.
  if (!plc.facets.empty() && out.mesh.tets.empty() && !r.stats().capped)
    throw Error(ExitCode::kInternal, plc.source + ": the 3D refinement lost a boundary subfacet and no "
                                     "tetrahedron was left inside; nothing written");
  out.stats = r.stats();
  if (options.progress) options.progress(1.0);
  return out;
}

}  // namespace fdr::tet
