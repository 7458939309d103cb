// Step: the lost connections of large cut-off water bodies, widened (reconnect.hpp).
#include "coast/reconnect.hpp"

#include <algorithm>
#include <limits>

#include "coast/geometry_ops.hpp"
#include "coast/meets.hpp"

namespace fdr::coast {
namespace {

// g clipped to the box (null when it does not reach it).
GeomPtr clipped(const OGRGeometry& g, const OGRPolygon& box, const OGREnvelope& be) {
  OGREnvelope ge;
  g.getEnvelope(&ge);
  if (!ge.Intersects(be)) return nullptr;
  if (ge.MinX >= be.MinX && ge.MaxX <= be.MaxX && ge.MinY >= be.MinY && ge.MaxY <= be.MaxY)
    return GeomPtr(g.clone());
  return checked(g.Intersection(&box), "water clipped to a box around a cut-off body");
}

// p with only the holes whose boxes meet b (the others do not change p's clip to b).
OGRPolygon near_part(const OGRPolygon& p, const OGREnvelope& b) {
  OGRPolygon q;
  q.addRing(const_cast<OGRLinearRing*>(p.getExteriorRing()));
  for (int k = 0; k < p.getNumInteriorRings(); ++k) {
    const OGRLinearRing* h = p.getInteriorRing(k);
    OGREnvelope he;
    h->getEnvelope(&he);
    if (he.Intersects(b)) q.addRing(const_cast<OGRLinearRing*>(h));
  }
  return q;
}

// e reaches the box's edge (within tol) where the box is not already the body's own box.
bool reaches_edge(const OGREnvelope& e, const OGREnvelope& box, const OGREnvelope& body, double tol) {
  return (e.MinX <= box.MinX + tol && box.MinX > body.MinX) || (e.MaxX >= box.MaxX - tol && box.MaxX < body.MaxX) ||
         (e.MinY <= box.MinY + tol && box.MinY > body.MinY) || (e.MaxY >= box.MaxY - tol && box.MaxY < body.MaxY);
}

}  // namespace

GeomPtr lost_connection(const OGRPolygon& body, const OGRPolygon& piece, const OGRPolygon& main, double reach,
                        double hair) {
  OGREnvelope pe, bodye;
  piece.getEnvelope(&pe);
  body.getEnvelope(&bodye);
  const double tol = 10 * hair;
  // Why a growing box: the connection is usually short, and the body (a whole sea) is large;
  // its overlay with the result is cut to the box.
  for (double e = reach; ; e *= 2) {
    OGREnvelope be;
    be.MinX = std::max(pe.MinX - e, bodye.MinX);
    be.MinY = std::max(pe.MinY - e, bodye.MinY);
    be.MaxX = std::min(pe.MaxX + e, bodye.MaxX);
    be.MaxY = std::min(pe.MaxY + e, bodye.MaxY);
    const OGRPolygon box = box_polygon(be);
    GeomPtr bw = clipped(near_part(body, be), box, be);
    if (!bw || bw->IsEmpty()) return nullptr;
    OwnedPolygons pw, mw;  // the piece and the main water, clipped
    if (GeomPtr c = clipped(near_part(piece, be), box, be)) polygons_of(c.get(), pw);
    if (GeomPtr c = clipped(near_part(main, be), box, be)) polygons_of(c.get(), mw);
    GeomPtr lost = std::move(bw);
    for (OwnedPolygons* r : {&pw, &mw})
      if (!r->empty()) {
        OwnedPolygons copy;
        for (const auto& q : *r) copy.emplace_back(q->clone());
        lost = checked(lost->Difference(multi(copy).get()), "water lost near a cut-off body");
      }
    // Hairlines where the result's coast and the input's differ by rounding would join
    // everything along the coast: shrunk by `hair`, they vanish (the rest stays within `tol` of
    // what it meets, and is grown far more than `hair` below).
    if (hair > 0 && !lost->IsEmpty()) lost = offset(*lost, -hair);
    OwnedPolygons parts;
    polygons_of(lost.get(), parts);
    Meets at_piece(pw, tol), at_main(mw, tol);
    int best = -1;
    bool truncated = false;
    for (std::size_t i = 0; i < parts.size(); ++i) {
      if (!(parts[i]->get_Area() > 0)) continue;
      if (at_piece.count(*parts[i]) >= 1 && at_main.count(*parts[i]) >= 1) {
        if (best < 0 || parts[i]->get_Area() < parts[static_cast<std::size_t>(best)]->get_Area())
          best = static_cast<int>(i);
        continue;
      }
      OGREnvelope ce;
      parts[i]->getEnvelope(&ce);
      if (reaches_edge(ce, be, bodye, tol) && at_piece.count(*parts[i]) >= 1) truncated = true;
    }
    if (best >= 0) return GeomPtr(parts[static_cast<std::size_t>(best)].release());
    const bool whole = be.MinX <= bodye.MinX && be.MinY <= bodye.MinY && be.MaxX >= bodye.MaxX && be.MaxY >= bodye.MaxY;
    if (!truncated || whole) return nullptr;
  }
}

GeomPtr widened_connection(const OGRGeometry& connection, double width, const OGREnvelope& inbox,
                           const std::vector<const OGRPolygon*>& others) {
  GeomPtr g = checked(connection.Buffer(0.5 * width, kQuadSegs), "widened connection");
  OGREnvelope ge;
  g->getEnvelope(&ge);
  if (ge.MinX < inbox.MinX || ge.MinY < inbox.MinY || ge.MaxX > inbox.MaxX || ge.MaxY > inbox.MaxY) {
    const OGRPolygon box = box_polygon(inbox);
    g = checked(g->Intersection(&box), "widened connection inside the domain's box");
  }
  for (const OGRPolygon* q : others) {
    OGREnvelope qe;
    q->getEnvelope(&qe);
    if (qe.Intersects(ge) && q->Intersects(g.get())) return nullptr;
  }
  return g;
}

}  // namespace fdr::coast
