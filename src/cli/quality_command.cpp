// `fdrmesh quality`: reads a mesh (2DM, fort.14, msh, node/ele, fdrmesh GPKG), evaluates f,
// prints and writes the same report as `fdrmesh mesh --report` (pipeline::run_quality).
#include "cli/quality_command.hpp"
#include <iostream>
#include "pipeline/quality_run.hpp"

namespace fdr::cli {
int run_quality(const QualityArgs& a) {
  pipeline::QualityOptions o;
  o.mesh = a.mesh;
  o.spacing = a.spacing;
  o.raster = a.raster;
  o.report_json = a.report_json;
  o.bound = a.bound;
  pipeline::run_quality(o, a.quiet ? nullptr : &std::cout);
  return 0;
}

}  // namespace fdr::cli
