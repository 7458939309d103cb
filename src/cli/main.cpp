// fdrmesh: Functional Delaunay Refinement mesher for coastlines and terrain.
#include "cli/cli.hpp"

int main(int argc, char** argv) { return fdr::cli::run(argc, argv); }
