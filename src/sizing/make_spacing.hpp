// make_spacing: builds a SizingField from a command-line spacing specification.
#pragma once
#include <string>
#include "sizing/sizing_field.hpp"

namespace fdr::sizing {

// Spacing specification grammar (surrounding blanks ignored everywhere):
//
//   spec     := number                  constant field, e.g. "250" or "1.5e3"
//             | preset                  "paper-f1" | "paper-f2" (FDR paper, Figure 2)
//             | number "*" preset       native scaled preset, e.g. "0.025*paper-f1"
//             | preset "*" number       same, e.g. "paper-f2 * 2"
//             | expression              anything else: a muparser expression in x and y
//                                       (see expression_field.hpp), in which preset names
//                                       may appear as operands, e.g. "min(paper-f1, 0.3)"
//   number   := decimal floating-point literal (from_chars syntax, e.g. 0.5, 2e-3), finite
//   preset   := "paper-f1"   f = (|x-5| + |y-5|)*0.1 + 0.1,         Lipschitz 0.1*sqrt(2)
//             | "paper-f2"   f = (|sin(x+y)| + |cos(x+y)|)*0.1,     Lipschitz 0.1*sqrt(2)
//
// Errors: empty spec or expression syntax error -> Error(kUsage, ...) (with the 1-based
// position for expressions); a constant or preset factor that is not a positive finite
// number -> Error(kInvalidSpacing, ...). Expressions are not checked for positivity here:
// use check_positive() over the domain.
SizingPtr make_spacing(const std::string& spec);

}  // namespace fdr::sizing
