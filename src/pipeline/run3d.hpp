// The 3D run of `fdrmesh mesh`: read the PLC, make f, tetrahedralize (FDR), measure, check, write.
#pragma once
#include <ostream>
#include <string>
#include <vector>
#include "base/progress.hpp"
#include "pipeline/options.hpp"
#include "pipeline/stage_time.hpp"
#include "quality/report3d.hpp"
#include "tet/tet_mesh.hpp"

namespace fdr::pipeline {

struct Result3 {
  tet::TetMesh mesh;
  quality::Report3 report;
  bool measured = false;              // false: -q without --report or VTU output (counts only)
  std::vector<std::string> written;   // output paths
  std::vector<StageTime> stages;
};

// Whether the run's input is a 3D one (api: a .poly or .node whose dimension line says 3, .smesh,
// .off, .stl, .ply).
bool is_3d_run(const Options& opt);

// Every usage error of a 3D run, before any I/O: 2D-only options given (named), outputs that are
// not 3D formats, a bound that is not positive. Throws Error(kUsage).
void check_3d_options(const Options& opt);

// Runs one 3D meshing job; the same all-or-nothing writing as pipeline::run. Throws fdr::Error.
Result3 run3d(const Options& opt, const ProgressFn& progress, const LogFn& log);

// What the command line prints after a 3D run: the text report, stages, written files.
void write_summary3(const Result3& r, std::ostream& out);

}  // namespace fdr::pipeline
