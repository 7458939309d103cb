// libFuzzer target: OGR vector path (GeoJSON bytes in /vsimem/ -> gis::read_domain with
// cleaning). Oracle: no sanitizer report; only fdr::Error (not kInternal) may escape.
#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_vsi.h>
#include <gdal.h>
#include <ogr_api.h>
#include <cstdint>
#include <cstdio>
#include <string>
#include "base/error.hpp"
#include "gis/vector_input.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  GDALAllRegister();
  CPLSetConfigOption("CPL_LOG", "/dev/null");
  CPLPushErrorHandler(CPLQuietErrorHandler);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > 16384) return 0;
  const char* path = "/vsimem/fuzz.geojson";
  VSILFILE* fp = VSIFileFromMemBuffer(path, const_cast<GByte*>(data), size, FALSE);
  if (!fp) return 0;
  VSIFCloseL(fp);
  try {
    fdr::gis::DomainOptions o;
    o.domain.path = path;
    o.s_srs = "EPSG:4326";
    (void)fdr::gis::read_domain(o);
  } catch (const fdr::Error& e) {
    if (e.code() == fdr::ExitCode::kInternal) {
      std::fprintf(stderr, "internal error: %s\n", e.what());
      VSIUnlink(path);
      __builtin_trap();
    }
  }
  VSIUnlink(path);
  return 0;
}
