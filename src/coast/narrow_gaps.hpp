// Step of the coast generalisation: the places where the result's water stays narrower than the
// mesh can resolve (two pieces of land nearer than `Options::narrow_gap`), listed.
//
// Why list them: the steps before remove, widen or join what they can; what is left (a gap the
// input itself has, where widening would join two water bodies or closing would cut one off, or
// one a step made) forces elements as narrow as the gap. Each place becomes a `narrow_gap_kept`
// repair with its width and location, so that the shortest edges of the mesh have a reason the
// user can see, and a gap the generalisation made is told apart from one of the input.
#pragma once
#include <vector>

#include "coast/generalise.hpp"
#include "coast/geometry_ops.hpp"
#include "coast/islet_placer.hpp"

namespace fdr::coast {

struct NarrowGap {
  Point2 where;           // midway between the two coasts
  double width = 0;       // the water's width there (m)
  bool in_input = false;  // both coasts lie on the input's coast (within 5 % of the limit)
  Point2 ends[2];         // the nearest points of the two coasts
  bool on_input[2] = {false, false};  // each end on the input's coast
};

// The places where the water of `polygons` (outer rings counter-clockwise, holes clockwise) is
// narrower than `width`: two coast segments facing each other across water nearer than `width`,
// of two rings, or of one ring when the way along it between them is more than three times their
// distance (a notch shallower than its width is no gap). One place per cluster: a gap within
// 2 `width` of a narrower one listed is left out. `input`: the input's polygons, to tell the
// gaps the input has (both coasts on its coast) from those the steps made (null: none counts as
// input). In order of width, then position; the same for any thread count.
std::vector<NarrowGap> narrow_gaps(const Polygons& polygons, double width, const Polygons* input);

// What made the coast at an end of a gap that is not on the input's coast: "an islet's
// triangle" or "an islet joined to land" when the end lies within tol of one that `islets`
// placed or joined (null: none), else "a widened bank or a cut".
const char* gap_end_cause(Point2 end, const IsletPlacer* islets, double tol);

// narrow_gaps(res.polygons, o.narrow_gap, input) as narrow_gap_kept repairs, counted in
// res.narrow_gaps and res.narrow_gaps_made, a gap made by a step naming the step that moved each
// coast (gap_end_cause); nothing when o.narrow_gap is 0.
void list_narrow_gaps(const Options& o, const OGRGeometry& input, Result& res, const IsletPlacer* islets = nullptr);

}  // namespace fdr::coast
