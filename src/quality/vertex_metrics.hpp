// The report's vertex metrics: nearest-neighbour distances nn(p) and the conformity figures
// nn(p)/f(p) (FDR paper, Definition 2.1 and Theorem 4.4).
#pragma once
#include <vector>
#include "base/types.hpp"
#include "quality/report.hpp"
#include "sizing/sizing_field.hpp"

namespace fdr::quality {

// nn(p) of every vertex from the mesh walk's squared distances `walk_sq` when there are any, else
// by a k-d tree search bounded by `edge_sq`, the squared shortest mesh edge of each vertex
// (exact either way).
std::vector<double> nearest_from(std::vector<double>&& walk_sq, std::vector<double>&& edge_sq,
                                 const std::vector<Point2>& vertices);

// Fills r's conformity figures (min, mean, p05, histogram), nn/f min and the invalid spacing
// count from nn and f at the vertices: `fv` when not null, else f at each vertex.
void conformity_figures(QualityReport& r, const std::vector<double>& nn, const double* fv,
                        const sizing::SizingField* f, const std::vector<Point2>& vertices);

}  // namespace fdr::quality
