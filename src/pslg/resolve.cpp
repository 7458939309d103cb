// Triangle-semantics constraint resolution on top of pslg::clean's exact splitting core.
#include "pslg/resolve.hpp"
#include <algorithm>
#include <cmath>
#include "base/error.hpp"
#include "pslg/validate.hpp"

namespace fdr::pslg {

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
  Pslg work = in;
  for (std::size_t s = 0; s < work.segments.size(); ++s) work.segments[s].part = static_cast<std::int32_t>(s);
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
  co.max_iterations = options.max_iterations;
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
