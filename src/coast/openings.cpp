// Step: the openings, channels kept and dead ends closed (openings.hpp).
#include "coast/openings.hpp"

#include <algorithm>
#include <cstdio>

#include "base/memory.hpp"
#include "coast/meets.hpp"
#include "coast/report.hpp"
#include "coast/restore.hpp"

namespace fdr::coast {

// One opening after the other on this thread, not one beside the other: each opening's GEOS
// intermediates are several times its result, and two of them alive at once set the
// generalisation's peak memory; one thread also lets the second opening reuse the pages the first
// freed (jemalloc gives another thread another arena). The buffers inside each opening still use
// both cores where a polygon is big (offset).
// Freed memory goes back to the system before each opening: the steps before them worked partly
// on other threads, whose arenas would keep those pages resident beside this thread's new ones,
// and the first opening's intermediates would sit beside the second's.
// The restorer's index of W is built after the first opening, whose intermediates set the
// generalisation's peak memory.
TwoOpenings two_openings(const OGRGeometry& W, double r1, double r2, double hair, bool full_rounds) {
  FilterLaps lap("  openings:");
  release_free_memory();
  TwoOpenings out;
  GeomPtr o1 = opening(W, r1);
  lap("O1 opening");
  const CoastRestorer restorer(&W, hair, full_rounds);
  lap("restorer");
  out.O1 = restorer.restore(std::move(o1));
  lap("O1 restored");
  if (r2 > 0) {
    release_free_memory();
    GeomPtr o2 = opening(W, r2);
    lap("O2 opening");
    out.O2 = restorer.restore(std::move(o2));
    lap("O2 restored");
  } else {
    out.O2 = GeomPtr(W.clone());
  }
  return out;
}

namespace {

// Dropping a dead end next to a kept channel can leave two kept parts touching at a point (GEOS
// calls that valid, the mesher would need zero-size elements there): R opened once more at the
// connection scale r2, only where such a point exists (GEOS writes every point where rings meet
// as a vertex of each, so a vertex that occurs twice, or a ring that repeats one, finds them
// all). The opening is local, in squares around the pinch points: opening(R) at a point depends
// on R within 2 r2 of it, so R clipped to squares 3 r2 larger gives the same result in the inner
// squares, for a fraction of the work of opening the whole of R.
GeomPtr open_pinch_points(GeomPtr R, double r2) {
  const std::vector<Point2> pins = pinch_points(R.get());
  if (debug::on(debug::Aid::kFilter))
    for (const Point2& p : pins) std::fprintf(stderr, "pinch at %.3f %.3f\n", p.x, p.y);
  if (!pins.empty()) {
    auto squares = [&](double half) {
      std::vector<std::unique_ptr<OGRPolygon>> sq;
      for (const Point2& p : pins) {
        OGRLinearRing lr;
        lr.addPoint(p.x - half, p.y - half);
        lr.addPoint(p.x + half, p.y - half);
        lr.addPoint(p.x + half, p.y + half);
        lr.addPoint(p.x - half, p.y + half);
        lr.closeRings();
        auto poly = std::make_unique<OGRPolygon>();
        poly->addRing(&lr);
        sq.push_back(std::move(poly));
      }
      return union_pieces(sq, 0, "squares around pinch points");
    };
    const GeomPtr D = squares(3 * r2), D2 = squares(6 * r2);
    std::vector<std::unique_ptr<OGRPolygon>> rps, near_ps, far_ps;
    polygons_of(R.get(), rps);
    OGREnvelope de;
    D2->getEnvelope(&de);
    for (auto& rp : rps) {
      OGREnvelope re;
      rp->getEnvelope(&re);
      (re.Intersects(de) ? near_ps : far_ps).push_back(std::move(rp));
    }
    GeomPtr Rn = multi(near_ps);
    GeomPtr local = checked(Rn->Intersection(D2.get()), "water near pinch points");
    GeomPtr opened = opening(*local, r2);
    // (Rn - D) + (opened & D) = Rn - ((Rn & D) - opened), as opened lies in Rn: one overlay of
    // the big polygon with the small removed part instead of a difference and a union; the
    // coordinates go back to the input's in step 3.
    GeomPtr in_d = checked(local->Intersection(D.get()), "water near pinch points");
    GeomPtr removed = checked(in_d->Difference(opened.get()), "water the local opening removes");
    GeomPtr Rn2 = removed->IsEmpty() ? std::move(Rn) : checked(Rn->Difference(removed.get()), "water with opened pinch points");
    polygons_of(Rn2.get(), far_ps);
    R = multi(far_ps);
  }
  return R;
}

}  // namespace

GeomPtr open_water(const GeomPtr& W, const Options& o, Result& res) {
  if (!(o.close_width > 0)) return GeomPtr(W->clone());
  FilterLaps lap("  openings");
  const bool dbg_time = lap.on();
  std::vector<std::unique_ptr<OGRPolygon>> dropped;  // dead-end water closed
  const double r1 = 0.5 * o.close_width;
  const double r2 = 0.5 * std::clamp(o.min_feature, 0.0, o.close_width);
  auto [O1, O2] = two_openings(*W, r1, r2, 0.05 * o.close_width, o.restore_full_rounds);
  // The openings' freed intermediates back to the system: the steps after them work partly on
  // other threads, whose allocator arenas would not reuse these pages but grow beside them.
  release_free_memory();
  lap("O1+O2");
  std::vector<std::unique_ptr<OGRPolygon>> comps;
  polygons_of(O1.get(), comps);
  GeomPtr rest = O1->IsEmpty() ? GeomPtr(O2->clone())
                               : difference_by_faces(O2.get(), O1.get(), "difference of openings", o.diff_overlay);
  std::vector<std::unique_ptr<OGRPolygon>> pieces;
  polygons_of(rest.get(), pieces);
  lap("diff");
  std::vector<std::unique_ptr<OGRPolygon>> keep;
  for (auto& c : comps) keep.emplace_back(c->clone());
  // Pieces are tested against slightly grown copies: a piece and O1 share boundary points up
  // to GEOS rounding.
  const double grow = std::max(1e-6 * o.close_width, 1e-9);
  Meets o1_parts(comps, grow, false, true);
  for (auto& piece : pieces) {
    if (!(piece->get_Area() > 0)) continue;
    const std::size_t touching = o1_parts.count(*piece);
    if (touching == 1) {  // dead end: inlet, gap, corner or sliver (closed)
      dropped.push_back(std::move(piece));
      continue;
    }
    if (touching >= 2) ++res.channels_kept;  // a connection between water bodies
    keep.push_back(std::move(piece));         // or a water body of its own
  }
  if (dbg_time) {
    std::size_t nk = 0, vk = 0;
    for (const auto& k : keep) {
      ++nk;
      vk += k->getExteriorRing()->getNumPoints();
      for (int q = 0; q < k->getNumInteriorRings(); ++q) vk += k->getInteriorRing(q)->getNumPoints();
    }
    std::fprintf(stderr, "filter pieces %zu (O1 comps %zu), kept %zu with %zu vertices, dropped %zu\n", pieces.size(),
                 comps.size(), nk, vk, dropped.size());
  }
  lap("classify");
  GeomPtr R = union_pieces(keep, grow, "union of the kept water");
  lap("union kept");
  if (r2 > 0) R = open_pinch_points(std::move(R), r2);
  lap("final opening");
  return R;
}

}  // namespace fdr::coast
