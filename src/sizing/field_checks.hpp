// Domain checks on a spacing field: sampled Lipschitz estimate, positivity, expected work.
#pragma once
#include <functional>
#include "sizing/sizing_field.hpp"

namespace fdr::sizing {

// Samples f on an n x n lattice spanning the box (corners included; n < 2 is taken as 2) and
// returns the largest |f(p)-f(q)| / |p-q| over horizontal, vertical and diagonal lattice
// neighbours. A lower bound of the true constant that converges as n grows. Pairs with a
// non-finite value are skipped. Returns 0 for a constant field or an empty box.
double estimate_lipschitz(const SizingField& f, Box2 box, int n = 64);

// Evaluates f on the same n x n lattice, row by row from the lowest y, at the samples where
// inside(p) is true, and throws Error(kInvalidSpacing,
//   "spacing f(x,y) = <value> at (<x>, <y>) is not a positive finite number")
// at the first sample whose value is <= 0, NaN or infinite. An empty `inside` means the whole box.
void check_positive(const SizingField& f, Box2 box, int n, const std::function<bool(Point2)>& inside);

// Expected number of triangles of a mesh following f: the midpoint-rule value of
//   integral over {inside} of c / f(p)^2 dA,   c = 4 / (3 sqrt 3) ~= 0.7698,
// on n x n cells over the box, i.e. the count of equilateral triangles whose circumradius
// equals f (area 3 sqrt(3)/4 f^2). FDR outputs triangles with R <= B f(c), so real counts
// differ by a roughly constant factor that the caller calibrates. Throws like check_positive
// at a cell centre whose value is not a positive finite number. Empty `inside`: whole box.
inline constexpr double kTrianglesPerCircumradiusSquared = 0.76980035891950105;  // 4/(3*sqrt(3))
double expected_triangles(const SizingField& f, Box2 box, const std::function<bool(Point2)>& inside, int n = 256);

}  // namespace fdr::sizing
