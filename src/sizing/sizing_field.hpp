// SizingField: the spacing function f(x) that drives Functional Delaunay Refinement.
#pragma once
#include <limits>
#include <memory>
#include <string>
#include "base/types.hpp"

namespace fdr::sizing {

// f(p) > 0 is the desired local edge length (same unit as the mesh coordinates).
// Evaluated in the mesher's local frame. Implementations must be deterministic and
// cheap: refine calls it once per new triangle (at its circumcenter).
class SizingField {
 public:
  virtual ~SizingField() = default;
  virtual double operator()(Point2 p) const = 0;
  // Known Lipschitz constant alpha (|f(x)-f(y)| <= alpha |x-y|), or negative if unknown.
  virtual double lipschitz() const { return -1.0; }
  // True if operator() may be called from several threads at once (no mutable state); the
  // smoothing uses both cores only then.
  virtual bool thread_safe() const { return false; }
  // An upper bound of f over the plane, or +infinity if unknown (with lipschitz(), bounds
  // the Lipschitz constant of a product f * k).
  virtual double upper_bound() const { return std::numeric_limits<double>::infinity(); }
  // Human description for reports, e.g. "constant 0.5" or "expr: 0.1*abs(x-5)+0.1".
  virtual std::string describe() const = 0;
};

using SizingPtr = std::shared_ptr<const SizingField>;

}  // namespace fdr::sizing
