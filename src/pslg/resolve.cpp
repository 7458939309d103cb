// Triangle-semantics constraint resolution on top of pslg::clean's exact splitting core.
#include "pslg/resolve.hpp"
#include <algorithm>
#include <cmath>
#include "base/error.hpp"
#include "pslg/validate.hpp"

namespace fdr::pslg {

namespace {
// True if validate() finds nothing and no vertex pair or vertex-segment pair is within tol.
bool clean_within(const Pslg& in, double tol, const std::string& source) {
  try {
    validate(in, source);
  } catch (const Error&) {
    return false;
  }
  if (!(tol > 0)) return true;
  std::vector<Index> order(in.points.size());
  for (Index i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](Index a, Index b) { return in.points[a].x < in.points[b].x; });
  for (std::size_t i = 0; i < order.size(); ++i)
    for (std::size_t j = i + 1; j < order.size() && in.points[order[j]].x - in.points[order[i]].x <= tol; ++j)
      if (dist(in.points[order[i]], in.points[order[j]]) <= tol) return false;
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
