// GDAL helpers shared by the gis readers and writers (private to fdr_gis).
#pragma once
#include <memory>
#include <string>

#include <cpl_error.h>
#include <gdal_priv.h>

namespace fdr::gis {

// Registers all GDAL/OGR drivers once (thread-safe).
void ensure_gdal_registered();

// Silences GDAL's stderr messages while alive; failures surface as fdr::Error with
// CPLGetLastErrorMsg() in the message instead.
class GdalQuiet {
 public:
  GdalQuiet() { CPLPushErrorHandler(CPLQuietErrorHandler); }
  ~GdalQuiet() { CPLPopErrorHandler(); }
  GdalQuiet(const GdalQuiet&) = delete;
  GdalQuiet& operator=(const GdalQuiet&) = delete;
};

struct DatasetCloser {
  void operator()(GDALDataset* d) const { if (d) GDALClose(GDALDataset::ToHandle(d)); }
};
using DatasetPtr = std::unique_ptr<GDALDataset, DatasetCloser>;

// Opens a vector / raster dataset read-only; kInputUnreadable "<file>: cannot open" on failure.
DatasetPtr open_vector(const std::string& path);
DatasetPtr open_raster(const std::string& path);

// The layer `layer` (the first when empty) of the vector source `path`, a file or a "PG:"
// connection, with its dataset and the source's name for messages (never a password);
// kInputUnreadable naming the source and its layers when there is no such layer.
struct OpenedLayer {
  DatasetPtr ds;
  OGRLayer* layer = nullptr;
  std::string source;
};
OpenedLayer open_layer(const std::string& path, const std::string& layer);

}  // namespace fdr::gis
