#include "tet/tetrahedralize.hpp"
#include "plc/check.hpp"
#include "tet/delaunay3.hpp"

namespace fdr::tet {

// First version: the checked PLC's vertices tetrahedralized (Delaunay), without refinement or
// facet recovery; the FDR rules replace it.
TetResult tetrahedralize(const plc::Plc& plc, const sizing::SizingField3& f, const TetOptions& options) {
  (void)f;
  const plc::FacetTriangulation ft = plc::check_and_triangulate(plc, {.closed = !plc.facets.empty()});
  Delaunay3 dt;
  dt.insert_all(plc.points);
  TetResult r;
  r.mesh = dt.to_mesh();
  r.mesh.tet_material.assign(r.mesh.tets.size(), 0);
  for (std::size_t i = 0; i < ft.triangles.size(); ++i)
    for (const auto& t : ft.triangles[i]) {
      r.mesh.faces.push_back(t);
      r.mesh.face_marker.push_back(plc.facets[i].marker);
    }
  r.stats.input_vertices = plc.points.size();
  r.stats.bound = options.bound;
  if (options.progress) options.progress(1.0);
  return r;
}

}  // namespace fdr::tet
