// Step: closing that keeps tips (tips.hpp).
#include "coast/tips.hpp"

#include <algorithm>
#include <atomic>
#include <limits>
#include <unordered_set>

#include "base/parallel.hpp"
#include "coast/report.hpp"
#include "pslg/segment_grid.hpp"

namespace fdr::coast {
namespace {

struct LandRing {                 // one land piece: the outside of an outer ring, or an island
  bool outer = false;
  GeomPtr base;                   // closing of the outer ring's polygon, or opening of the island
  std::vector<std::size_t> tips;  // indices into `pieces`
};
struct PolyRings {
  std::size_t outer = 0;
  std::vector<std::size_t> holes;
};
// The land of W ring by ring: its closing (outer rings) or opening (islands), and the thin land
// that the closing cuts.
struct ThinLand {
  std::vector<LandRing> rings;
  std::vector<PolyRings> polys;
  std::vector<std::unique_ptr<OGRPolygon>> pieces;  // thin land
  std::vector<std::size_t> piece_ring;
  // W's vertices: a tip's coast is made of them, its cut of the closing's arc points.
  std::unordered_set<std::uint64_t> wv;
};

// Every ring is closed (outer) or opened (island) on its own: the rings are shared out to the
// threads (an atomic counter), the results kept per ring and combined in ring order, so they do
// not depend on the thread count.
ThinLand close_rings(const OGRGeometry* W, double rc, bool overlay) {
  ThinLand t;
  auto& rings = t.rings;
  auto& polys = t.polys;
  auto& pieces = t.pieces;
  auto& piece_ring = t.piece_ring;
  auto& wv = t.wv;
  std::vector<std::unique_ptr<OGRPolygon>> wps;
  polygons_of(W, wps);
  struct Job {
    const OGRLinearRing* ring;
    bool outer;
    GeomPtr base;
    std::vector<std::unique_ptr<OGRPolygon>> thin;
  };
  std::vector<Job> jobs;
  for (const auto& wp : wps) {
    jobs.push_back({wp->getExteriorRing(), true, nullptr, {}});
    for (int k = 0; k < wp->getNumInteriorRings(); ++k) jobs.push_back({wp->getInteriorRing(k), false, nullptr, {}});
  }
  for (const Job& jb : jobs)
    for (int k = 0; k < jb.ring->getNumPoints(); ++k) wv.insert(point_key(jb.ring->getX(k), jb.ring->getY(k)));
  auto run = [&](Job& j) {
    OGRPolygon rp;
    rp.addRing(const_cast<OGRLinearRing*>(j.ring));
    if (j.outer) {
      GeomPtr grown = checked(rp.Buffer(rc, kQuadSegs), "buffer of an outer ring");
      j.base = offset(*grown, -rc);
      GeomPtr t = difference_contained(*j.base, rp, "thin land outside an outer ring", overlay);
      polygons_of(t.get(), j.thin);
    } else {
      j.base = opening(rp, rc);
      if (j.base->IsEmpty()) {
        j.thin.emplace_back(rp.clone());
      } else {
        GeomPtr d = difference_contained(rp, *j.base, "thin land of an island", overlay);
        polygons_of(d.get(), j.thin);
      }
    }
  };
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    GdalQuiet q;
    for (std::size_t i; (i = next.fetch_add(1)) < jobs.size();) run(jobs[i]);
  };
  if (std::min<unsigned>(max_threads(), 2) >= 2) run_beside(worker, worker);
  else worker();
  std::size_t j = 0;
  for (const auto& wp : wps) {
    PolyRings pr;
    for (int k = -1; k < wp->getNumInteriorRings(); ++k, ++j) {
      LandRing r;
      r.outer = jobs[j].outer;
      r.base = std::move(jobs[j].base);
      (k < 0 ? pr.outer : (pr.holes.push_back(0), pr.holes.back())) = rings.size();
      for (auto& q : jobs[j].thin) { pieces.push_back(std::move(q)); piece_ring.push_back(rings.size()); }
      rings.push_back(std::move(r));
    }
    polys.push_back(std::move(pr));
  }
  return t;
}

// Other land: the boundaries of the closed rings (without a tip's own cut), as segments (pairs
// of bp); islands the closing leaves below min_island_area, by their vertices.
void other_land(const ThinLand& t, double min_island_area, std::vector<Point2>& bp,
                std::unordered_set<std::uint64_t>& small_island) {
  const auto& rings = t.rings;
  for (const auto& r : rings) {
    std::vector<std::unique_ptr<OGRPolygon>> cps;
    polygons_of(r.base.get(), cps);
    for (const auto& cp : cps) {
      auto add = [&](const OGRLinearRing* lr, bool small) {
        for (int k = 0; k < lr->getNumPoints(); ++k) {
          if (k + 1 < lr->getNumPoints()) {
            bp.push_back({lr->getX(k), lr->getY(k)});
            bp.push_back({lr->getX(k + 1), lr->getY(k + 1)});
          }
          if (small) small_island.insert(point_key(lr->getX(k), lr->getY(k)));
        }
      };
      add(cp->getExteriorRing(), !r.outer && cp->get_Area() < min_island_area);
      for (int k = 0; k < cp->getNumInteriorRings(); ++k) add(cp->getInteriorRing(k), false);
    }
  }
}

// The thin pieces kept as tips (keep[i] = 1, listed in their ring's tips, counted in res).
void keep_tips(ThinLand& t, const std::vector<Point2>& bp, const std::unordered_set<std::uint64_t>& small_island,
               const Options& o, Result& res, std::vector<char>& keep) {
  const double clear = o.tip_clearance;
  auto& rings = t.rings;
  const auto& pieces = t.pieces;
  const auto& piece_ring = t.piece_ring;
  const auto& wv = t.wv;
  if (!bp.empty() && !pieces.empty()) {
    Box2 box;
    double total = 0;
    for (std::size_t k = 0; k < bp.size(); k += 2) {
      box.add(bp[k]);
      box.add(bp[k + 1]);
      total += dist(bp[k], bp[k + 1]);
    }
    const std::size_t nseg = bp.size() / 2;
    pslg::SegmentGrid grid(box, nseg, std::max(total / static_cast<double>(nseg), 1e-6));
    for (std::size_t k = 0; k < nseg; ++k) grid.add_segment(static_cast<Index>(k), bp[2 * k], bp[2 * k + 1]);
    std::vector<Index> near;
    // True when a segment of other land (no endpoint in `own`) is within lim of p.
    auto land_near = [&](Point2 p, double lim, const std::unordered_set<std::uint64_t>& own) {
      Box2 qb;
      qb.add({p.x - lim, p.y - lim});
      qb.add({p.x + lim, p.y + lim});
      grid.segments_near(qb, &near);
      for (Index k : near) {
        const Point2 s0 = bp[2 * k], s1 = bp[2 * k + 1];
        if (!own.empty() && (own.count(point_key(s0.x, s0.y)) || own.count(point_key(s1.x, s1.y)))) continue;
        if (dist_to_segment(p, s0, s1) < lim) return true;
      }
      return false;
    };
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      const OGRLinearRing* r = pieces[i]->getExteriorRing();
      // Tips: pieces longer than 2 close widths (perimeter > 4 cw). The shorter pieces the
      // closing cuts off convex land corners are kept the same way when the cut would move the
      // coast by more than kCornerKeep close widths (their far end, the corner, is that far from
      // the cut), the piece is one run of coast and one of cut (not a short bridge of land
      // between two waters, which has two of each), and no other land lies within
      // tip_clearance of the corner: the rounding would only move the coast (a reflex corner of
      // the water needs no small elements), and a kept corner keeps the input coast there.
      // Smaller fractions kept notches a third of f deep, near which a Steiner vertex can come
      // closer to an input vertex than the theory allows.
      const bool long_piece = r->get_Length() > 4 * o.close_width;
      std::vector<Point2> coast, cut;
      std::unordered_set<std::uint64_t> own;
      int runs = 0;  // changes between coast and cut around the ring
      bool prev_on = false;
      for (int k = 0; k < r->getNumPoints(); ++k) {
        const std::uint64_t key = point_key(r->getX(k), r->getY(k));
        const bool on_w = wv.count(key) > 0;
        (on_w ? coast : cut).push_back({r->getX(k), r->getY(k)});
        if (!on_w) own.insert(key);
        if (k > 0 && on_w != prev_on) ++runs;
        prev_on = on_w;
      }
      if (!long_piece && (runs != 2 || coast.empty() || cut.empty())) continue;
      bool crowded = false;
      for (const Point2& q : cut)
        if (small_island.count(point_key(q.x, q.y))) { crowded = true; break; }
      if (crowded) {
      } else if (cut.empty()) {  // a whole thin island
        for (const Point2& c : coast)
          if ((crowded = land_near(c, clear, own))) break;
      } else {
        // The far end: the coast vertex farthest from the cut.
        double far = -1;
        Point2 e{};
        for (const Point2& c : coast) {
          double d = std::numeric_limits<double>::infinity();
          for (const Point2& q : cut) d = std::min(d, dist(c, q));
          if (d > far) { far = d; e = c; }
        }
        constexpr double kCornerKeep = 0.45;
        if (!long_piece && !(far > kCornerKeep * o.close_width)) continue;
        crowded = !(far > 0) || land_near(e, long_piece ? std::min(clear, 0.9 * far) : clear, own);
      }
      if (!crowded) {
        keep[i] = 1;
        rings[piece_ring[i]].tips.push_back(i);
        ++res.tips_kept;
      }
    }
  }
}

// Closed water: per polygon, close(O) without its kept tips, minus the islands' openings with
// theirs.
GeomPtr closed_water(ThinLand& t, double hair, bool overlay) {
  auto& rings = t.rings;
  auto& polys = t.polys;
  const auto& pieces = t.pieces;
  auto with_tips = [&](LandRing& r) -> GeomPtr {
    if (r.tips.empty()) return std::move(r.base);
    std::vector<std::unique_ptr<OGRPolygon>> ps;
    for (std::size_t i : r.tips) ps.emplace_back(pieces[i]->clone());
    if (!r.outer) polygons_of(r.base.get(), ps);
    GeomPtr u = union_pieces(ps, hair, "kept tips");
    return r.outer ? difference_contained(*r.base, *u, "closed water without kept tips", overlay) : std::move(u);
  };
  std::vector<std::unique_ptr<OGRPolygon>> out;
  const bool two = max_threads() >= 2;
  for (auto& pr : polys) {
    // The outer ring's kept tips (an overlay of the closed outer ring) and the islands' (their
    // union) are independent: one on each core when there are two.
    LandRing& outer = rings[pr.outer];
    GeomPtr b, hu;
    auto islands = [&] {
      std::vector<std::unique_ptr<OGRPolygon>> hs;
      for (std::size_t h : pr.holes) {
        GeomPtr g = with_tips(rings[h]);
        if (g && !g->IsEmpty()) polygons_of(g.get(), hs);
      }
      if (!hs.empty()) hu = union_pieces(hs, hair, "union of islands");
    };
    if (two && !outer.tips.empty() && !pr.holes.empty()) {
      run_beside(
          [&] {
            GdalQuiet q2;
            b = with_tips(outer);
          },
          islands);
    } else {
      b = with_tips(outer);
      islands();
    }
    if (hu) b = overlay ? checked(b->Difference(hu.get()), "closed water minus islands")
                        : minus_disjoint(std::move(b), *hu, "closed water minus islands");
    polygons_of(b.get(), out);
  }
  if (out.size() > 1) return union_pieces(out, hair, "union of closed water");
  return GeomPtr(multi(out).release());
}

}  // namespace

// Closing of W at close_width/2 (land thinner than close_width becomes water), except for tips
// of land (the thin end of a needle, a spit or a cape), which stay land unless other land is
// near their end. Why keep them: the cut leaves a blunt end exactly close_width wide, two
// corners a fraction of hmin apart around which the mesh refines to their distance, and the tip
// it removes is coast the model loses; a kept tip is a sharp wedge that the resampling and the
// refinement handle with one element. A tip is cut as before when other land lies nearer its far
// end than both `tip_clearance` and 0.9 times the tip's own length (the water between them
// would need elements that narrow), or when it belongs to an island that the closing leaves
// below --min-island (removed as before); a whole island thinner than close_width is kept only
// with no other land within `tip_clearance` of it.
// Ring by ring: the closing of W is the opening of the land, and the opening of disjoint pieces
// of land is the union of their openings, so closed = close(O) - U open(H) for each outer ring O
// and its islands H, and the thin land is (close(O) - O) and (H - open(H)). Small overlays per
// ring instead of one overlay of closed with W.
// *land_cut: the area of thin land that became water.
GeomPtr closing_keep_tips(const OGRGeometry* W, const Options& o, Result& res, double* land_cut) {
  FilterLaps lap("  closing");
  const double rc = 0.5 * o.close_width;
  const double hair = std::max(1e-6 * o.close_width, 1e-9);
  ThinLand t = close_rings(W, rc, o.diff_overlay);
  lap("rings");
  std::vector<Point2> bp;
  std::unordered_set<std::uint64_t> small_island;
  other_land(t, o.min_island_area, bp, small_island);
  std::vector<char> keep(t.pieces.size(), 0);
  lap("other land");
  keep_tips(t, bp, small_island, o, res, keep);
  *land_cut = 0;
  for (std::size_t i = 0; i < t.pieces.size(); ++i)
    if (!keep[i]) *land_cut += t.pieces[i]->get_Area();
  lap("tips");
  GeomPtr closed = closed_water(t, hair, o.diff_overlay);
  lap("with tips, minus islands");
  return closed;
}

GeomPtr close_thin_land(GeomPtr W, const Options& o, Result& res) {
  if (!(o.close_width > 0)) return W;
  const double rc = 0.5 * o.close_width;
  double land_cut = -1;  // >= 0 when the tips were judged one by one
  GeomPtr closed;
  if (o.tip_clearance > 0) {
    closed = closing_keep_tips(W.get(), o, res, &land_cut);
  } else {
    GeomPtr dil = offset(*W, rc);
    closed = offset(*dil, -rc);
  }
  // Closing never removes water; what it adds is reported (land taken away).
  const double added = land_cut >= 0 ? land_cut : area_of(closed.get()) - area_of(W.get());
  if (added > 0) res.land_removed_area += added;
  return closed;
}

}  // namespace fdr::coast
