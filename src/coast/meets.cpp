// Meets (meets.hpp).
#include "coast/meets.hpp"

namespace fdr::coast {

std::size_t Meets::count(const OGRPolygon& piece, std::size_t* first) {
  OGREnvelope e;
  piece.getEnvelope(&e);
  e.MinX -= grow_; e.MinY -= grow_; e.MaxX += grow_; e.MaxY += grow_;
  const bool ungrown = alone_ungrown_ && ps_.size() == 1;
  std::size_t n = 0;
  GeomPtr grown;
  for (std::size_t i = 0; i < ps_.size(); ++i) {
    if (!env_[i].Intersects(e)) continue;
    if (!prep_[i]) prep_[i] = std::make_unique<Prepared>(ps_[i].get());
    // A polygon the piece meets as it is, the grown piece meets too: the buffer only for the others.
    if (!prep_[i]->intersects(&piece)) {
      if (ungrown) continue;
      if (!grown) grown = checked(piece.Buffer(grow_, 1), "buffer of a piece");
      if (!prep_[i]->intersects(grown.get())) continue;
    }
    if (n == 0 && first) *first = i;
    if (++n >= 2) break;
  }
  return n;
}

}  // namespace fdr::coast
