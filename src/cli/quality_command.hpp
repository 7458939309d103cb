// `fdrmesh quality MESH`: the mesh report for an existing mesh against a spacing function.
#pragma once
#include <string>

namespace fdr::cli {

struct QualityArgs {
  std::string mesh, spacing, raster, report_json;
  double bound = 1.0;
  bool quiet = false;
};

int run_quality(const QualityArgs& args);

}  // namespace fdr::cli
