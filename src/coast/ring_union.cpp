// The union of a water polygon with overlapping pieces, ring by ring (ring_union.hpp).
#include "coast/ring_union.hpp"

#include <algorithm>
#include <cmath>

#include "base/parallel.hpp"
#include "coast/box_index.hpp"

namespace fdr::coast {

namespace {

// The outer ring of p united with the pieces that cross it (those inside it add nothing).
GeomPtr outer_with_pieces(const OGRPolygon& p, const OwnedPolygons& pieces, const char* what) {
  auto outer = std::make_unique<OGRPolygon>();
  outer->addRing(const_cast<OGRLinearRing*>(p.getExteriorRing()));
  OGRLineString line;
  line.addSubLineString(p.getExteriorRing());
  const Prepared crosses(&line);
  OGRMultiPolygon m;
  for (const auto& d : pieces)
    if (crosses.intersects(d.get())) m.addGeometry(d.get());
  if (m.IsEmpty()) return GeomPtr(outer.release());
  return checked(outer->Union(&m), what);
}

// The rings left of hole h of p where the pieces near it (their indices in `near`) reach in:
// the outer rings of h - D_h in GEOS's order, h itself when no piece meets it; `has_holes` when
// a remainder has holes of its own.
void hole_remainder(const OGRLinearRing* h, const OwnedPolygons& pieces, const std::vector<std::size_t>& near,
                    const char* what, std::vector<std::unique_ptr<OGRLinearRing>>& out, bool& has_holes) {
  OGRPolygon hp;
  hp.addRing(const_cast<OGRLinearRing*>(h));
  OGRMultiPolygon dm;
  // Prepared once for all the pieces near it: a large hole (a continent) has many, and each plain
  // test would build its graph anew.
  const Prepared php(&hp);
  for (const std::size_t i : near)
    if (php.intersects(pieces[i].get())) dm.addGeometry(pieces[i].get());
  if (dm.IsEmpty()) {
    out.emplace_back(h->clone());
    return;
  }
  GeomPtr r = checked(hp.Difference(&dm), what);
  OwnedPolygons rps;
  polygons_of(r.get(), rps);
  for (auto& rp : rps) {
    if (rp->getNumInteriorRings() > 0) has_holes = true;
    out.emplace_back(rp->getExteriorRing()->clone());
  }
}

}  // namespace

GeomPtr union_by_rings(const OGRPolygon& p, const OwnedPolygons& pieces, const char* what) {
  const std::size_t nh = static_cast<std::size_t>(p.getNumInteriorRings());
  std::vector<OGREnvelope> penv(pieces.size());
  for (std::size_t i = 0; i < pieces.size(); ++i) pieces[i]->getEnvelope(&penv[i]);
  const BoxIndex index(penv);
  // Chunk 0 the outer ring (the largest job, claimed first), chunk k the remainder of hole k - 1.
  GeomPtr outer;
  std::vector<std::vector<std::unique_ptr<OGRLinearRing>>> rest(nh);
  std::vector<char> has_holes(nh, 0);
  parallel_chunks(nh + 1, [&](std::size_t c, unsigned) {
    GdalQuiet quiet;
    if (c == 0) {
      outer = outer_with_pieces(p, pieces, what);
      return;
    }
    const OGRLinearRing* h = p.getInteriorRing(static_cast<int>(c - 1));
    OGREnvelope he;
    h->getEnvelope(&he);
    std::vector<std::size_t> near;
    index.near(he, &near);
    if (near.empty()) {
      rest[c - 1].emplace_back(h->clone());
      return;
    }
    bool bad = false;
    hole_remainder(h, pieces, near, what, rest[c - 1], bad);
    has_holes[c - 1] = bad;
  });
  if (std::find(has_holes.begin(), has_holes.end(), 1) != has_holes.end()) return nullptr;
  OwnedPolygons ops;
  polygons_of(outer.get(), ops);
  std::vector<std::unique_ptr<OGRLinearRing>> all;
  for (auto& v : rest)
    for (auto& r : v) all.push_back(std::move(r));
  return with_holes(ops, all, what);
}

}  // namespace fdr::coast
