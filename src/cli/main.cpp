// fdrmesh: Functional Delaunay Refinement mesher for coastlines and terrain.
#include "base/memory.hpp"
#include "cli/cli.hpp"

int main(int argc, char** argv) {
  fdr::set_process_allocator_policy();  // the program's, not the libraries': set before any work
  return fdr::cli::run(argc, argv);
}
