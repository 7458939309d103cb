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
// polygon is tested against the piece itself (no buffer per piece). With `shared_vertices`, a
// polygon that has a vertex of the piece among its own (exact coordinates) meets it without a
// GEOS test; why: the openings' pieces share most of their vertices with O1, whose largest
// polygon would otherwise be searched by GEOS once per piece.
class Meets {
 public:
  Meets(const std::vector<std::unique_ptr<OGRPolygon>>& ps, double grow, bool alone_ungrown = false,
        bool shared_vertices = false);
  // How many polygons of the set the piece meets (0, 1 or 2: the count stops at two); `first`
  // (optional) gets the index of the first one met.
  std::size_t count(const OGRPolygon& piece, std::size_t* first = nullptr);

 private:
  // The set's polygons with a vertex at exactly p (sorted vertex index; empty without
  // shared_vertices).
  void polygons_at(double x, double y, std::vector<std::size_t>& out) const;

  const std::vector<std::unique_ptr<OGRPolygon>>& ps_;
  std::vector<OGREnvelope> env_;
  std::vector<std::unique_ptr<Prepared>> prep_;
  double grow_;
  bool alone_ungrown_;
  struct At {
    double x, y;
    std::size_t polygon;
    bool operator<(const At& o) const { return x != o.x ? x < o.x : (y != o.y ? y < o.y : polygon < o.polygon); }
  };
  std::vector<At> vertices_;
};

}  // namespace fdr::coast
