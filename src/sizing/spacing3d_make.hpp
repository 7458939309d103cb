// make_spacing3: a 3D spacing function from a command-line specification.
#pragma once
#include <string>
#include "sizing/spacing3d.hpp"

namespace fdr::sizing {

// The paper's test functions lifted to [0,10]^3, evaluated natively (thread-safe, no parser).
// f1 = k ((|x-5| + |y-5| + |z-5|) 0.1 + 0.1), Lipschitz k 0.1 sqrt(3).
class PaperF1Field3 final : public SizingField3 {
 public:
  explicit PaperF1Field3(double k = 1) : k_(k) {}
  double operator()(Point3 p) const override;
  double lipschitz() const override;
  std::string describe() const override;

 private:
  double k_;
};

// f2 = k (|sin(x+y+z)| + |cos(x+y+z)|) 0.1, Lipschitz k 0.1 sqrt(3).
class PaperF2Field3 final : public SizingField3 {
 public:
  explicit PaperF2Field3(double k = 1) : k_(k) {}
  double operator()(Point3 p) const override;
  double lipschitz() const override;
  double upper_bound() const override;
  std::string describe() const override;

 private:
  double k_;
};

// Grammar as the 2D make_spacing (make_spacing.hpp), surrounding blanks ignored:
//   spec := number                  constant, e.g. "0.5"
//         | "paper-f1" | "paper-f2" the fields above
//         | number "*" preset | preset "*" number   a scaled preset, e.g. "0.5*paper-f1"
//         | expression              anything else: a muparser expression in x, y and z
//                                   (spacing3d_expression.hpp)
// Errors: empty spec or expression syntax error -> Error(kUsage); a constant or factor that is
// not a positive finite number -> Error(kInvalidSpacing).
SizingPtr3 make_spacing3(const std::string& spec);

}  // namespace fdr::sizing
