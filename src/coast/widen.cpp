// Step: widening of narrow water (widen.hpp).
#include "coast/widen.hpp"

#include <algorithm>
#include <cstdio>

#include "base/parallel.hpp"
#include "coast/geometry_ops.hpp"
#include "coast/meets.hpp"
#include "coast/report.hpp"
#include "coast/ring_union.hpp"

namespace fdr::coast {
namespace {

// The vertices of g's rings (for the kFilter developer aid).
std::size_t vertices_of(const OGRGeometry* g, std::size_t* rings) {
  std::vector<std::unique_ptr<OGRPolygon>> ps;
  polygons_of(g, ps);
  std::size_t nr = 0, nv = 0;
  for (const auto& p : ps) {
    nr += 1 + p->getNumInteriorRings();
    nv += p->getExteriorRing()->getNumPoints();
    for (int k = 0; k < p->getNumInteriorRings(); ++k) nv += p->getInteriorRing(k)->getNumPoints();
  }
  if (rings) *rings = nr;
  return nv;
}

// Envelopes of grown pieces of two different bodies that meet (grown by `hair`): the pieces may
// join those bodies, which only an overlay of them together finds.
bool bodies_may_join(const std::vector<OwnedPolygons>& grown, double hair) {
  std::vector<std::pair<OGREnvelope, std::size_t>> env;
  for (std::size_t b = 0; b < grown.size(); ++b)
    for (const auto& d : grown[b]) {
      env.emplace_back();
      d->getEnvelope(&env.back().first);
      env.back().second = b;
    }
  std::sort(env.begin(), env.end(), [](const auto& x, const auto& y) { return x.first.MinX < y.first.MinX; });
  for (std::size_t i = 0; i < env.size(); ++i)
    for (std::size_t j = i + 1; j < env.size() && env[j].first.MinX <= env[i].first.MaxX + hair; ++j)
      if (env[j].second != env[i].second && env[j].first.MinY <= env[i].first.MaxY + hair &&
          env[i].first.MinY <= env[j].first.MaxY + hair)
        return true;
  return false;
}

// The water bodies with the grown pieces that meet each (grown[b] for wps[b]) added, body by
// body and ring by ring (union_by_rings); one union of everything (union_pieces) when pieces of
// two bodies may meet or a body's rings cannot be done one by one. wps and grown are emptied.
GeomPtr unite_widened(OwnedPolygons& wps, std::vector<OwnedPolygons>& grown, double hair) {
  const char* what = "union of the widened water";
  OwnedPolygons out;
  bool by_rings = !bodies_may_join(grown, hair);
  std::vector<GeomPtr> united(wps.size());
  for (std::size_t b = 0; by_rings && b < wps.size(); ++b)
    if (!grown[b].empty()) by_rings = (united[b] = union_by_rings(*wps[b], grown[b], what)) != nullptr;
  if (by_rings) {
    for (std::size_t b = 0; b < wps.size(); ++b) {
      if (united[b]) polygons_of(united[b].get(), out);
      else out.push_back(std::move(wps[b]));
    }
    return multi(out);
  }
  std::vector<int> family;  // 0: the water bodies, 1: the grown pieces (each set disjoint)
  for (auto& p : wps) {
    out.push_back(std::move(p));
    family.push_back(0);
  }
  for (auto& g : grown)
    for (auto& d : g) {
      out.push_back(std::move(d));
      family.push_back(1);
    }
  return union_pieces(out, hair, what, &family);
}

// Thin water widened. The parts of W no disk of radius rw fits in, T = W - open(W, rw), that are
// at least 2 s wide (their core C = (W - s) - open(W, rw), a strip w - 2 s wide along a channel
// w wide) are grown by rw - s: the channel becomes w + 2 rw - 4 s >= 2 rw wide (for w >= 2 s),
// each bank moved by rw - 2 s into the land. Why: a
// channel narrower than the resolution keeps its coast only with elements as narrow as itself
// (every edge across it is < w); widened to 2 rw it holds elements near hmin and the coast moves
// by a fraction of hmin, where closing it would move the coast by its whole length. Convex water
// corners leave core bits too (sharper corners larger ones): they are blunted the same way, as a
// wedge of water would need elements as narrow as itself. A grown piece that would join two
// separate water bodies (come within the close width of another one) is not used; the rest
// stays inside W's bounding box (an open boundary there does not move). The grown pieces are
// simplified (they are new coast; the resampler's tolerance is far coarser).
GeomPtr widen_thin_water(const OGRGeometry& W, double rw, double s, const Options& o,
                         Result& res) {
  FilterLaps lap("  widen");
  const bool dbg = lap.on();
  // The opening and the erosion are independent: one on each core (as the openings below).
  GeomPtr Wo, We;
  run_beside(
      [&W, &We, s] {
        GdalQuiet q2;
        We = offset(W, -s);
      },
      [&] { Wo = opening(W, rw); });
  lap("opening + erosion");
  if (We->IsEmpty()) return GeomPtr(W.clone());
  GeomPtr C = Wo->IsEmpty() ? GeomPtr(We->clone()) : checked(We->Difference(Wo.get()), "thin water core");
  if (C->IsEmpty()) return GeomPtr(W.clone());
  lap("core");
  {  // bits of the core in right-angled water corners (about 0.3 rw - s across) are no channels;
     // those of acute corners are larger and kept: the corner is blunted, as a wedge of water
     // would need elements as narrow as itself
    std::vector<std::unique_ptr<OGRPolygon>> cps, big;
    polygons_of(C.get(), cps);
    for (auto& cp : cps)
      if (cp->get_Area() >= 0.05 * s * s) big.push_back(std::move(cp));
    if (big.size() < cps.size()) C = multi(big);
    if (C->IsEmpty()) return GeomPtr(W.clone());
  }
  // The grown pieces are new coast: their arcs need not be finer than the resampling keeps
  // (a tenth of the move; every arc point would otherwise go through the openings below).
  C = checked(C->SimplifyPreserveTopology(0.1 * (rw - s)), "thin water core simplified");
  lap("grown: simplify core");
  GeomPtr D = offset(*C, rw - s, 2);
  lap("grown: offset");
  D = checked(D->SimplifyPreserveTopology(0.1 * (rw - s)), "widened water simplified");
  lap("grown");
  if (dbg) {
    auto nverts = [](const OGRGeometry* g) {
      std::vector<std::unique_ptr<OGRPolygon>> ps;
      polygons_of(g, ps);
      std::size_t nv = 0;
      for (const auto& p : ps) {
        nv += p->getExteriorRing()->getNumPoints();
        for (int k = 0; k < p->getNumInteriorRings(); ++k) nv += p->getInteriorRing(k)->getNumPoints();
      }
      return nv;
    };
    std::fprintf(stderr, "  widen: W %zu, W-s %zu, open(W) %zu, core %zu, grown %zu vertices\n", nverts(&W), nverts(We.get()),
                 nverts(Wo.get()), nverts(C.get()), nverts(D.get()));
  }
  OGREnvelope we;
  W.getEnvelope(&we);
  {
    OGRPolygon box = box_polygon(we);
    D = checked(D->Intersection(&box), "widened water inside the domain's box");
  }
  std::vector<std::unique_ptr<OGRPolygon>> wps, dps;
  polygons_of(&W, wps);
  polygons_of(D.get(), dps);
  std::vector<OwnedPolygons> grown(wps.size());  // the grown pieces used, by the body they meet
  // Tested grown by the close width: land thinner than that between a piece and another water
  // body would be removed by the closing below and join them all the same.
  Meets bodies(wps, 2 * s, true);
  for (auto& d : dps) {
    if (!(d->get_Area() > 0)) continue;
    std::size_t body = 0;
    const std::size_t meets = bodies.count(*d, &body);
    if (meets != 1) {  // would join two water bodies (or meets none: cannot happen)
      OGREnvelope e;
      d->getEnvelope(&e);
      if (debug::value(debug::Aid::kFilter))
        std::fprintf(stderr, "widen: piece of %.0f m^2 near %.1f %.1f meets %zu water bodies: not used\n",
                     d->get_Area(), 0.5 * (e.MinX + e.MaxX), 0.5 * (e.MinY + e.MaxY), meets);
      continue;
    }
    ++res.widened;
    const double a = d->get_Area();
    if (a >= o.list_area)
      res.repairs.push_back({"water_widened", inside_point(d.get()), a,
                             "water narrower than " + num(2 * rw) + " m was widened (banks moved by about " +
                                 num(rw - 2 * s) + " m into the land); the widened part covers " + num(a) + " m^2",
                             -1});
    grown[body].push_back(std::move(d));
  }
  lap("pieces");
  GeomPtr out = unite_widened(wps, grown, 1e-6 * rw);
  lap("union");
  const double added = area_of(out.get()) - area_of(&W);
  if (added > 0) res.widened_area += added;
  return out;
}

}  // namespace

GeomPtr widen(GeomPtr W, const Options& o, Result& res) {
  if (!(o.widen_width > o.close_width && o.close_width > 0)) return W;
  W = widen_thin_water(*W, 0.5 * o.widen_width, 0.5 * o.close_width, o, res);
  if (debug::on(debug::Aid::kFilter)) {
    std::size_t nr = 0;
    const std::size_t nv = vertices_of(W.get(), &nr);
    std::vector<std::unique_ptr<OGRPolygon>> ps;
    polygons_of(W.get(), ps);
    std::fprintf(stderr, "widened: %zu polygons, %zu rings, %zu vertices\n", ps.size(), nr, nv);
  }
  return W;
}

}  // namespace fdr::coast
