#include "tet/tetrahedralize.hpp"
#include "plc/check.hpp"
#include "tet/refiner3.hpp"
#include "tet/tet_output.hpp"

namespace fdr::tet {

TetResult tetrahedralize(const plc::Plc& plc, const sizing::SizingField3& f, const TetOptions& options) {
  const plc::FacetTriangulation ft = plc::check_and_triangulate(plc, {.closed = !plc.facets.empty()});
  Refiner3 r(plc, ft, f, options);
  r.conform();
  if (options.refine) {
    r.refine();
  } else {
    r.flood_regions();
  }
  TetResult out;
  out.mesh = make_tet_mesh(r);
  out.stats = r.stats();
  if (options.progress) options.progress(1.0);
  return out;
}

}  // namespace fdr::tet
