// The allocator's policy per phase of a run (memory_policy.hpp).
#include "pipeline/memory_policy.hpp"

namespace fdr::pipeline {

MemoryPolicy policy_for(MemoryPhase phase, bool gis) {
  MemoryPolicy p;
  switch (phase) {
    case MemoryPhase::kGisInput:
      // GEOS's small objects, the spacing grids and the cleaned PSLG are written once in scattered
      // order, where a huge page saves hundreds of small page faults.
      p.huge_pages = true;
      break;
    case MemoryPhase::kGisRead:
      // GEOS allocates and frees millions of small objects: pages given back would be faulted in
      // again at once.
      p.keep_freed = true;
      break;
    case MemoryPhase::kMesh:
      if (gis) {
        // The filter's removed-water listing runs beside the CDT and the refinement, and every page
        // given back interrupts that thread too; kept pages also serve the report's and the
        // writers' temporary arrays.
        p.keep_freed = true;
      }
      // A .poly run keeps the allocator's defaults: giving freed pages back at once neither sped
      // it up nor lowered its peak.
      break;
  }
  return p;
}

PhaseMemory::PhaseMemory(MemoryPhase phase, bool gis) {
  const MemoryPolicy p = policy_for(phase, gis);
  if (p.huge_pages) huge_.emplace();
  if (p.keep_freed) keep_.emplace();
}

void stage_ended() {
  // One stage's garbage does not stay resident beside the next stage's data.
  release_free_memory();
}

}  // namespace fdr::pipeline
