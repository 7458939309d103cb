// Step: the listing of removed water (removed.hpp).
#include "coast/removed.hpp"

#include <optional>

#include "base/parallel.hpp"
#include "coast/report.hpp"

namespace fdr::coast {

// The input minus the result, computed on a thread of its own from the start (`now`) or by the
// first get(). Its operands are released once it is computed.
class GoneWater {
 public:
  GoneWater(GeomPtr w0, std::unique_ptr<OGRMultiPolygon> result, bool overlay, bool now)
      : w0_(std::move(w0)), rm_(std::move(result)), overlay_(overlay) {
    if (now) worker_ = std::make_unique<Worker>([this] { done_ = compute(); });
  }
  GeomPtr get() {
    if (!worker_) return compute();
    if (std::exception_ptr e = worker_->join()) std::rethrow_exception(e);
    worker_.reset();
    return std::move(done_);
  }

 private:
  GeomPtr compute() {
    GdalQuiet q2;
    GeomPtr d = difference_by_faces(w0_.get(), rm_.get(), "difference input - result", overlay_);
    w0_.reset();
    rm_.reset();
    return d;
  }
  GeomPtr w0_;
  std::unique_ptr<OGRMultiPolygon> rm_;
  bool overlay_;
  GeomPtr done_;
  std::unique_ptr<Worker> worker_;  // last: joined before the members it writes go
};

namespace {

// Removed water (input minus result, `gone`), listed piece by piece above list_area; pieces
// thinner than `hair` (the snapping distance) are rounding, not features; a piece holding a
// water body listed as removed (listed_at) is not listed again.
RemovedWater list_removed_water(GeomPtr gone_all, const std::vector<Point2>& listed_at, double hair, double list_area,
                                double close_width) {
  RemovedWater out;
  std::vector<std::unique_ptr<OGRPolygon>> gone;
  polygons_of(gone_all.get(), gone);
  gone_all.reset();
  for (const auto& g : gone) {
    const double a = g->get_Area();
    double per = g->getExteriorRing()->get_Length();
    for (int k = 0; k < g->getNumInteriorRings(); ++k) per += g->getInteriorRing(k)->get_Length();
    if (!(a > 0) || 2 * a <= hair * per) continue;
    bool listed = false;  // a cut-off water body already listed
    OGREnvelope ge;
    g->getEnvelope(&ge);
    for (const Point2 w : listed_at) {
      if (!(ge.MinX <= w.x && w.x <= ge.MaxX && ge.MinY <= w.y && w.y <= ge.MaxY)) continue;
      OGRPoint pt(w.x, w.y);
      if (g->Intersects(&pt)) { listed = true; break; }
    }
    if (listed) continue;
    out.areas.push_back(a);
    if (a < list_area) {
      ++out.corner_pieces;
      continue;
    }
    ++out.closed;
    out.repairs.push_back({"narrow_water_closed", inside_point(g.get()), a,
                           "dead-end water narrower than the resolution (" + num(close_width) +
                               " m, --close-width) removed: " + num(a) + " m^2 (inlet, gap or sliver)",
                           -1});
  }
  return out;
}

// Adds a listing to the result (areas one by one, in order: the same sum as before the listing
// could be deferred).
void add_removed(Result& res, RemovedWater w) {
  for (const double a : w.areas) res.closed_area += a;
  res.corner_pieces += w.corner_pieces;
  res.closed += w.closed;
  for (auto& r : w.repairs) res.repairs.push_back(std::move(r));
}

}  // namespace

std::shared_ptr<GoneWater> start_gone(const OGRGeometry& W0, const OwnedPolygons& outp, const Options& o, bool* early) {
  auto rm = std::make_unique<OGRMultiPolygon>();
  for (const auto& p : outp) rm->addGeometry(p.get());
  // Deferred with the listing (defer_removed): the caller starts both where a core is free,
  // unless the input is large (early_listing_rss): then at once, on the read's arena (its freed
  // pages are kept and on huge pages while the read runs, and a large input's read goes on long
  // enough that the listing is done before the mesh stages release pages eagerly; an arena of
  // its own raised the peak).
  *early = false;
  if (o.defer_removed && o.early_listing_rss > 0 && max_threads() >= 2) {
    const std::optional<ProcessMemory> mm = process_memory();
    *early = mm && mm->rss >= o.early_listing_rss;
  }
  const bool now = max_threads() >= 2 && (*early || !o.defer_removed);
  return std::make_shared<GoneWater>(GeomPtr(W0.clone()), std::move(rm), o.diff_overlay, now);
}

void report_removed_bodies(const OGRGeometry& W0, const OGRGeometry& R, const Options& o, Result& res) {
  std::vector<std::unique_ptr<OGRPolygon>> wps;
  polygons_of(&W0, wps);
  std::vector<std::unique_ptr<OGRPolygon>> rps;
  polygons_of(&R, rps);
  std::vector<OGREnvelope> renv(rps.size());
  for (std::size_t j = 0; j < rps.size(); ++j) rps[j]->getEnvelope(&renv[j]);
  std::vector<std::unique_ptr<OGRPoint>> rin(rps.size());
  for (const auto& w : wps) {
    OGREnvelope we;
    w->getEnvelope(&we);
    bool any = false;
    std::unique_ptr<Prepared> pw;
    for (std::size_t j = 0; j < rps.size(); ++j) {
      if (!we.Intersects(renv[j])) continue;
      if (!rin[j]) {
        const Point2 q = inside_point(rps[j].get());
        rin[j] = std::make_unique<OGRPoint>(q.x, q.y);
      }
      if (!pw) pw = std::make_unique<Prepared>(w.get());
      if (pw->intersects(rin[j].get())) { any = true; break; }
    }
    if (any) continue;
    const double a = w->get_Area();
    ++res.closed;
    res.closed_area += a;
    res.repairs.push_back({"water_body_removed", inside_point(w.get()), a,
                           "water body of " + num(a) + " m^2 is nowhere " + num(o.min_feature) +
                               " m wide (--min-feature); it was removed",
                           -1});
  }
}

void list_removed(std::shared_ptr<GoneWater> gone, bool early, const Options& o, Result& res) {
  // The places of the water bodies already listed as removed (collected once: the repairs list
  // holds thousands of entries, the removed pieces are thousands too).
  std::vector<Point2> listed_at;
  for (const auto& r : res.repairs)
    if (r.kind == "cut_off_water_removed" || r.kind == "water_body_removed") listed_at.push_back(r.where);
  auto listing = [gone = std::move(gone), listed_at = std::move(listed_at), hair = 0.05 * o.close_width,
                  list_area = o.list_area, close_width = o.close_width] {
    GdalQuiet q2;
    FilterLaps l3("  listing");
    StepLaps s3(debug::Aid::kStages, "stage listing:");  // sub-stages of the listing (beside)
    GeomPtr g = gone->get();
    l3("difference");
    s3("difference");
    RemovedWater w = list_removed_water(std::move(g), listed_at, hair, list_area, close_width);
    l3("list");
    s3("list");
    return w;
  };
  if (o.defer_removed) {
    // Started by the caller (start_removed) where a core is free; finish_removed() takes it.
    res.removed_pending = std::make_shared<PendingRemoved>();
    res.removed_pending->listing = std::move(listing);
    if (early) start_removed(res, false);  // its difference already runs: the listing goes on from it
  } else {
    add_removed(res, listing());
  }
}

void start_removed(Result& res, bool own_arena) {
  PendingRemoved* p = res.removed_pending.get();
  if (!p || !p->listing || p->runner || max_threads() < 2) return;
  // The listing's allocations in an arena of its own, which keeps its freed pages through the
  // mesh stages' eager release.
  if (own_arena) p->arena = std::make_shared<OwnArena>();
  p->runner = std::make_unique<Worker>([p] {
    if (p->arena) p->arena->bind();
    p->done = p->listing();
  });
}

std::vector<pslg::Repair> finish_removed(Result& res) {
  PendingRemoved* p = res.removed_pending.get();
  if (!p || !p->listing) return {};
  RemovedWater w;
  if (p->runner) {
    if (std::exception_ptr e = p->runner->join()) std::rethrow_exception(e);
    w = std::move(p->done);
  } else {
    w = p->listing();
  }
  p->runner.reset();
  p->arena.reset();  // its pages back to the system
  res.removed_pending.reset();
  const std::size_t first = res.repairs.size();
  add_removed(res, std::move(w));
  return {res.repairs.begin() + static_cast<std::ptrdiff_t>(first), res.repairs.end()};
}

}  // namespace fdr::coast
