// Validity checkers for a Triangulation (library code, used by tests and `--check`).
#pragma once
#include <functional>
#include <string>
#include <vector>
#include "mesh/triangulation.hpp"

namespace fdr::mesh {

struct CheckResult {
  std::vector<std::string> problems;  // empty when every invariant holds (at most max_report kept)
  std::size_t count = 0;              // total number of violations found
  bool ok() const { return count == 0; }
  void add(std::string s, std::size_t max_report = 20) {
    ++count;
    if (problems.size() < max_report) problems.push_back(std::move(s));
  }
};

// Twin symmetry, matching endpoints, symmetric constraint bits, valid vertex ids,
// strictly positive orientation of every live triangle (exact predicate).
CheckResult check_topology(const Triangulation& tri);
// Constrained Delaunay: every unconstrained interior edge is locally Delaunay (exact incircle).
CheckResult check_delaunay(const Triangulation& tri);
// Every input segment whose endpoints are in the mesh is a chain of constrained edges
// belonging to it, from one endpoint to the other.
CheckResult check_segments(const Triangulation& tri);
// All three.
CheckResult check_all(const Triangulation& tri);
// FDR's guarantee: R/f(c) <= bound for every live triangle (R circumradius, c circumcenter), for a
// spacing f given as a function (the mesh does not know sizing::SizingField).
CheckResult check_spacing(const Triangulation& tri, const std::function<double(Point2)>& f, double bound);

}  // namespace fdr::mesh
