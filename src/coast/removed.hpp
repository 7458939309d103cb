// Step of the coast generalisation: the listing of removed water (input minus result), which
// may run on a thread of its own beside what follows the generalisation.
#pragma once
#include <functional>
#include <memory>

#include "base/memory.hpp"
#include "base/parallel.hpp"
#include "coast/generalise.hpp"
#include "coast/geometry_ops.hpp"

namespace fdr::coast {

class GoneWater;  // the input minus the result, being computed

// A deferred removed-water listing (Options::defer_removed).
struct PendingRemoved {
  std::function<RemovedWater()> listing;  // the work (run by `runner` or by finish_removed)
  RemovedWater done;                      // the runner's result
  std::shared_ptr<OwnArena> arena;        // the runner's allocations (base/memory.hpp)
  std::unique_ptr<Worker> runner;         // start_removed; last: joined before the rest goes
};

// Starts the input W0 minus the result polygons outp (the removed water): on another thread at
// once when the listing is not deferred or starts early (*early: the process holds at least
// early_listing_rss), else when the listing asks for it.
std::shared_ptr<GoneWater> start_gone(const OGRGeometry& W0, const OwnedPolygons& outp, const Options& o, bool* early);

// Whole input water bodies (of W0) of which R keeps nothing, reported (water_body_removed;
// counted in res.closed and closed_area).
void report_removed_bodies(const OGRGeometry& W0, const OGRGeometry& R, const Options& o, Result& res);

// The removed water listed piece by piece (narrow_water_closed above list_area; pieces thinner
// than the snapping distance are rounding; water bodies already reported are not listed again):
// added to res now or, with defer_removed, left pending (res.removed_pending; start_removed,
// finish_removed).
void list_removed(std::shared_ptr<GoneWater> gone, bool early, const Options& o, Result& res);

}  // namespace fdr::coast
