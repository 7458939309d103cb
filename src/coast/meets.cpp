// Meets (meets.hpp).
#include "coast/meets.hpp"

#include <algorithm>

namespace fdr::coast {

Meets::Meets(const std::vector<std::unique_ptr<OGRPolygon>>& ps, double grow, bool alone_ungrown, bool shared_vertices)
    : ps_(ps), env_(ps.size()), prep_(ps.size()), grow_(grow), alone_ungrown_(alone_ungrown) {
  for (std::size_t i = 0; i < ps.size(); ++i) ps[i]->getEnvelope(&env_[i]);
  if (!shared_vertices) return;
  for (std::size_t i = 0; i < ps.size(); ++i)
    for (int k = -1; k < ps[i]->getNumInteriorRings(); ++k) {
      const OGRLinearRing* r = k < 0 ? ps[i]->getExteriorRing() : ps[i]->getInteriorRing(k);
      for (int j = 0; j + 1 < r->getNumPoints(); ++j) vertices_.push_back({r->getX(j), r->getY(j), i});
    }
  std::sort(vertices_.begin(), vertices_.end());
}

void Meets::polygons_at(double x, double y, std::vector<std::size_t>& out) const {
  auto it = std::lower_bound(vertices_.begin(), vertices_.end(), At{x, y, 0});
  for (; it != vertices_.end() && it->x == x && it->y == y; ++it)
    if (std::find(out.begin(), out.end(), it->polygon) == out.end()) out.push_back(it->polygon);
}

std::size_t Meets::count(const OGRPolygon& piece, std::size_t* first) {
  OGREnvelope e;
  piece.getEnvelope(&e);
  e.MinX -= grow_; e.MinY -= grow_; e.MaxX += grow_; e.MaxY += grow_;
  const bool ungrown = alone_ungrown_ && ps_.size() == 1;
  // Polygons sharing a vertex with the piece meet it (a common point): known without GEOS. Only
  // when no `first` is asked for (the first met in the set's order may be one found by GEOS).
  std::vector<std::size_t> at;
  if (!vertices_.empty() && !first) {
    for (int k = -1; k < piece.getNumInteriorRings() && at.size() < 2; ++k) {
      const OGRLinearRing* r = k < 0 ? piece.getExteriorRing() : piece.getInteriorRing(k);
      for (int j = 0; j + 1 < r->getNumPoints() && at.size() < 2; ++j) polygons_at(r->getX(j), r->getY(j), at);
    }
    if (at.size() >= 2) return 2;
  }
  std::size_t n = at.size();
  GeomPtr grown;
  for (std::size_t i = 0; i < ps_.size(); ++i) {
    if (!env_[i].Intersects(e)) continue;
    if (std::find(at.begin(), at.end(), i) != at.end()) continue;  // counted
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
