// Coast restoration: the input's exact coast given back where a buffer result runs along it.
#pragma once
#include <memory>

#include <ogr_geometry.h>

#include "coast/geometry_ops.hpp"

namespace fdr::coast {

// Gives the input's exact coast back wherever a buffer result runs within `hair` of it (runs of
// result vertices along an input ring become that ring's vertices), where the polygon stays
// valid. full_rounds: every round of the validity check examines everything (for the test that
// the rounds after the first, which examine only what changed, give the same result).
class CoastRestorer {
 public:
  CoastRestorer(const OGRGeometry* input, double hair, bool full_rounds = false);
  ~CoastRestorer();
  CoastRestorer(const CoastRestorer&) = delete;
  CoastRestorer& operator=(const CoastRestorer&) = delete;
  // g with the input's coast given back (a new geometry; g itself when nothing changes). Const:
  // several threads may restore at once.
  GeomPtr restore(GeomPtr g) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Moves every vertex within `hair` of an input vertex onto the nearest one (ties: the smaller x,
// then y), so boundaries the buffers left unchanged up to rounding are bitwise the input's.
class Snapper {
 public:
  Snapper(const OGRGeometry* input, double hair);
  ~Snapper();
  Snapper(const Snapper&) = delete;
  Snapper& operator=(const Snapper&) = delete;
  void snap(OGRPolygon* p) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Each polygon of outp snapped to the input (Snapper), unless the snap makes it invalid (a vertex
// moved across a nearby edge): that polygon keeps the buffers' coordinates.
void snap_to_input(std::vector<std::unique_ptr<OGRPolygon>>& outp, const Snapper& snapper);

}  // namespace fdr::coast
