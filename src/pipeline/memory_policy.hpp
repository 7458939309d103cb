// How the allocator treats freed memory in each phase of a run: chosen here, in one place, from
// the mechanisms of base/memory.hpp.
#pragma once
#include <optional>
#include "base/memory.hpp"

namespace fdr::pipeline {

enum class MemoryPhase {
  kGisInput,  // a GIS run's read, spacing and clean stages (prepare_gis_input)
  kGisRead,   // a GIS run's read and resolution filter (inside kGisInput)
  kMesh,      // CDT, refinement, report and write
};

// What the allocator does while a phase runs.
struct MemoryPolicy {
  bool keep_freed = false;       // freed pages stay with the allocator for reuse
  bool huge_pages = false;       // the allocator's new mappings are backed by huge pages
};

// The policy of `phase` in a GIS run (`gis`) or a .poly run.
MemoryPolicy policy_for(MemoryPhase phase, bool gis);

// Holds policy_for(phase, gis) while it lives; the previous settings come back when it ends (and
// with keep_freed, the pages kept go back to the system).
class PhaseMemory {
 public:
  PhaseMemory(MemoryPhase phase, bool gis);
  PhaseMemory(const PhaseMemory&) = delete;
  PhaseMemory& operator=(const PhaseMemory&) = delete;

 private:
  // Declared in this order so that the huge-page hooks are in place before the decay changes and
  // removed after them.
  std::optional<HugePageArenas> huge_;
  std::optional<KeepFreedPages> keep_;
};

// Called at the end of every stage (StageClock::lap).
void stage_ended();

}  // namespace fdr::pipeline
