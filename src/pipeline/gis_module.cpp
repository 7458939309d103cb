// fdrmesh_gis.so: the GIS side of the pipeline (gis_backend.hpp) as a module for dlopen. Its only
// exported symbol is fdr_gis_module_backend (the static libraries inside are linked with
// --exclude-libs,ALL, so the module never interposes on the program's own copies).
#include "pipeline/gis_backend.hpp"

extern "C" __attribute__((visibility("default"))) const fdr::pipeline::GisBackend* fdr_gis_module_backend() {
  return fdr_builtin_gis_backend();
}
