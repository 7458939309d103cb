// Triangle-semantics constraint resolution on top of pslg::clean's exact splitting core.
#include "pslg/resolve.hpp"
#include <algorithm>
#include <cmath>
#include <cstdint>
#include "base/error.hpp"
#include "pslg/validate.hpp"

namespace fdr::pslg {

namespace {
// True if two points lie within tol of each other. Why cells tol wide, sorted: two such points
// lie in the same or adjacent cells, so each point looks only at its neighbour cells' few points
// (a sweep along x alone would compare every pair of points on one vertical line).
bool points_within(const std::vector<Point2>& points, double tol) {
  if (points.empty()) return false;
  Box2 box;
  for (const Point2& p : points) box.add(p);
  struct Cell {
    std::int64_t cx, cy;
    Index id;
    bool operator<(const Cell& o) const { return cx != o.cx ? cx < o.cx : cy != o.cy ? cy < o.cy : id < o.id; }
  };
  std::vector<Cell> cells(points.size());
  for (Index i = 0; i < points.size(); ++i)
    cells[i] = {static_cast<std::int64_t>(std::floor((points[i].x - box.lo.x) / tol)),
                static_cast<std::int64_t>(std::floor((points[i].y - box.lo.y) / tol)), i};
  std::sort(cells.begin(), cells.end());
  for (const Cell& c : cells)
    for (std::int64_t dx = 0; dx <= 1; ++dx) {
      // Cells (cx, cy..cy+1) and (cx+1, cy-1..cy+1): every neighbouring pair is met once.
      const std::int64_t y0 = dx == 0 ? c.cy : c.cy - 1;
      auto it = std::lower_bound(cells.begin(), cells.end(), Cell{c.cx + dx, y0, 0});
      for (; it != cells.end() && it->cx == c.cx + dx && it->cy <= c.cy + 1; ++it)
        if (it->id != c.id && dist(points[c.id], points[it->id]) <= tol) return true;
    }
  return false;
}

// True if validate() finds nothing and no vertex pair or vertex-segment pair is within tol.
bool clean_within(const Pslg& in, double tol, const std::string& source) {
  try {
    validate(in, source);
  } catch (const Error&) {
    return false;
  }
  if (!(tol > 0)) return true;
  if (points_within(in.points, tol)) return false;
  return vertices_near_segments(in.points, in.segments, nullptr, tol).empty();
}
}  // namespace

Pslg resolve(const Pslg& in, const ResolveOptions& options, std::vector<Repair>* repairs) {
  if (options.strict) {
    validate(in, options.source);
    return in;
  }
  // Errors that no repair can fix, worded as validate() words them.
  const std::size_t n = in.points.size();
  for (Index i = 0; i < n; ++i)
    if (!std::isfinite(in.points[i].x) || !std::isfinite(in.points[i].y))
      throw Error(ExitCode::kInvalidGeometry, options.source + ": vertex " + std::to_string(i) + " has a non-finite coordinate");
  for (Index s = 0; s < in.segments.size(); ++s)
    if (in.segments[s].a >= n || in.segments[s].b >= n)
      throw Error(ExitCode::kInvalidGeometry, options.source + ": segment " + std::to_string(s) + " refers to vertex " +
                                                  std::to_string(std::max(in.segments[s].a, in.segments[s].b)) +
                                                  " but there are only " + std::to_string(n) + " vertices");
  CleanOptions co;
  co.boundary_parity = false;
  // Snap tolerance ("pixel"): 2^-36 of the extent, at least 16 ulps of the largest coordinate.
  // Vertices closer than this merge, and a vertex this close to a segment splits it, so the
  // resolved PSLG has no feature far below floating-point resolution (which the refiner could
  // not split) while moving nothing by more than ~1.5e-11 of the extent.
  {
    const Box2 b = in.bbox();
    const double mag = std::max({std::fabs(b.lo.x), std::fabs(b.hi.x), std::fabs(b.lo.y), std::fabs(b.hi.y)});
    const double pixel = std::max(std::ldexp(std::max(b.width(), b.height()), -36), std::ldexp(mag, -48));
    if (options.snap && pixel > 0 && std::isfinite(pixel)) co.snap_distance = co.segment_snap = pixel;
  }
  // Fast path (a clean input costs no more than validate()): no exact conflict, no two vertices
  // and no vertex and segment closer than the snap tolerance -> the input as it is.
  if (clean_within(in, co.snap_distance, options.source)) return in;
  co.max_iterations = options.max_iterations;
  Pslg work = in;
  for (std::size_t s = 0; s < work.segments.size(); ++s) work.segments[s].part = static_cast<std::int32_t>(s);
  Pslg out;
  try {
    out = clean(work, co, repairs);
  } catch (const Error& e) {
    if (e.code() == ExitCode::kInternal) throw;
    std::string msg = e.what();
    if (msg.rfind("clean: ", 0) == 0) msg = msg.substr(7);
    throw Error(e.code(), options.source + ": " + msg);
  }
  for (Segment& s : out.segments) s.part = in.segments[static_cast<std::size_t>(s.part)].part;
  return out;
}

}  // namespace fdr::pslg
