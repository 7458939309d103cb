// The chain benchmark: degenerate inputs (collinear square, lattice, cocircular rings, collinear
// breaklines) beside random points of the same size, through fdrmesh's CDT, the fdrmesh command
// line and CGAL's constrained Delaunay triangulation.
#pragma once
#include <cstddef>
#include <string>

// Runs every case with about n vertices; fdr_binary empty: no command-line rows. Returns 0, or
// the first failing child's exit code.
int run_chains(std::size_t n, const std::string& fdr_binary, bool cgal);
