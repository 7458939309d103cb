// The registry of developer aids (debug.hpp): the only place that reads the environment.
#include "base/debug.hpp"
#include <array>
#include <cstdlib>

namespace fdr::debug {
namespace {

constexpr std::array<AidInfo, static_cast<unsigned>(Aid::kCount)> kAids{{
    {Aid::kStages, "FDR_DEBUG_STAGES", "every pipeline stage's wall time and page faults on stderr"},
    {Aid::kReport, "FDR_DEBUG_REPORT", "the quality report's steps on stderr"},
    {Aid::kFilter, "FDR_DEBUG_FILTER", "the coast generalisation's steps on stderr"},
    {Aid::kClean, "FDR_DEBUG_CLEAN", "PSLG cleaning and boundary resampling steps on stderr"},
    {Aid::kSizing, "FDR_DEBUG_SIZING", "the spacing rules' steps on stderr"},
    {Aid::kSmooth, "FDR_DEBUG_SMOOTH", "the smoothing sweeps on stderr"},
    {Aid::kGpkg, "FDR_DEBUG_GPKG", "the GeoPackage writer's steps on stderr"},
    {Aid::kPslg, "FDR_DEBUG_PSLG", "PREFIX: a GIS run's PSLG before and after cleaning, PREFIX.before.poly and .after.poly"},
    {Aid::kFilterWkt, "FDR_DEBUG_FILTER_WKT", "PATH: the coast generalisation's result as WKT, one polygon a line"},
    {Aid::kThreads, "FDR_THREADS", "N: at most N threads (1 to 64); results do not depend on it"},
    {Aid::kTet, "FDR_DEBUG_TET",
     "the 3D refinement checks after every boundary episode that each subsegment is a mesh edge and each subfacet "
     "a mesh face, and names the first that is not on stderr"},
    {Aid::kGisModule, "FDRMESH_GIS_MODULE", "PATH: the GIS module (fdrmesh_gis.so) to load instead of the installed one"},
}};

}  // namespace

std::span<const AidInfo> registry() { return kAids; }

const char* value(Aid aid) {
  // Read at each call, not cached: tests change FDR_THREADS between runs in one process.
  return std::getenv(kAids[static_cast<unsigned>(aid)].variable);
}

}  // namespace fdr::debug
