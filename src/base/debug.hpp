// Developer aids: the one registry of the environment variables fdrmesh reads. None of them
// changes a mesh, a report or a written file; each only prints timings or dumps intermediate
// data, caps the thread count (results never depend on it), or points at the GIS module to load. docs/debug.md lists them.
#pragma once
#include <span>

namespace fdr::debug {

enum class Aid : unsigned {
  kStages,   // FDR_DEBUG_STAGES: every pipeline stage's time on stderr
  kReport,   // FDR_DEBUG_REPORT: the quality report's steps
  kFilter,   // FDR_DEBUG_FILTER: the coast generalisation's steps
  kClean,    // FDR_DEBUG_CLEAN: PSLG cleaning and resampling steps
  kSizing,   // FDR_DEBUG_SIZING: spacing rules' steps
  kSmooth,   // FDR_DEBUG_SMOOTH: smoothing sweeps
  kGpkg,     // FDR_DEBUG_GPKG: GeoPackage writer's steps
  kPslg,     // FDR_DEBUG_PSLG=PREFIX: the GIS run's PSLG before and after cleaning as .poly files
  kFilterWkt,  // FDR_DEBUG_FILTER_WKT=PATH: the coast generalisation's result as WKT, one polygon a line
  kThreads,  // FDR_THREADS=N: at most N threads (1..64)
  kTet,      // FDR_DEBUG_TET: the 3D refinement's boundary invariant checked after every episode
  kGisModule,  // FDRMESH_GIS_MODULE=PATH: the GIS module to load instead of the installed one
  kCount
};

struct AidInfo {
  Aid aid;
  const char* variable;
  const char* what;
};

// Every aid, in the order of Aid.
std::span<const AidInfo> registry();

// The variable's text when it is set (read once per process), else nullptr.
const char* value(Aid aid);

inline bool on(Aid aid) { return value(aid) != nullptr; }

}  // namespace fdr::debug
