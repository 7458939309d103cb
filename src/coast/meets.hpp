// How many polygons of a set a piece of water meets (the openings' pieces, the widened pieces).
#pragma once
#include <memory>
#include <vector>

#include "coast/geometry_ops.hpp"

namespace fdr::coast {

// How many of a set of polygons a piece meets, the piece grown by `grow` (the count stops at
// two): the openings' pieces are judged by it (a piece and O1 share boundary points only up to
// GEOS rounding) and so are the widened pieces (land thinner than the close width between them
// and another water body would be closed all the same). With `alone_ungrown`, a set of one
// polygon is tested against the piece itself (no buffer per piece).
class Meets {
 public:
  Meets(const std::vector<std::unique_ptr<OGRPolygon>>& ps, double grow, bool alone_ungrown = false)
      : ps_(ps), env_(ps.size()), prep_(ps.size()), grow_(grow), alone_ungrown_(alone_ungrown) {
    for (std::size_t i = 0; i < ps.size(); ++i) ps[i]->getEnvelope(&env_[i]);
  }
  // How many polygons of the set the piece meets (0, 1 or 2: the count stops at two); `first`
  // (optional) gets the index of the first one met.
  std::size_t count(const OGRPolygon& piece, std::size_t* first = nullptr);

 private:
  const std::vector<std::unique_ptr<OGRPolygon>>& ps_;
  std::vector<OGREnvelope> env_;
  std::vector<std::unique_ptr<Prepared>> prep_;
  double grow_;
  bool alone_ungrown_;
};

}  // namespace fdr::coast
