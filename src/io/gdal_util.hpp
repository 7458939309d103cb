// GDAL helpers for the io module: one-time driver registration and a scoped error collector.
#pragma once
#include <cpl_error.h>
#include <gdal_priv.h>

#include <memory>
#include <string>

namespace fdr::io::detail {

void gdal_register_once();

// Silences GDAL's stderr output while alive and remembers the last failure message
// (warnings such as the GeoPackage extension notice for temp names are dropped).
class GdalErrors {
 public:
  GdalErrors() { CPLPushErrorHandlerEx(&GdalErrors::handler, this); }
  ~GdalErrors() { CPLPopErrorHandler(); }
  GdalErrors(const GdalErrors&) = delete;
  GdalErrors& operator=(const GdalErrors&) = delete;
  const std::string& last() const { return last_; }
  bool any() const { return !last_.empty(); }
  void clear() { last_.clear(); }
  // "<fallback>: <GDAL message>" or just the fallback.
  std::string reason(const std::string& fallback) const { return last_.empty() ? fallback : fallback + ": " + last_; }

 private:
  static void CPL_STDCALL handler(CPLErr cls, CPLErrorNum, const char* msg) {
    auto* self = static_cast<GdalErrors*>(CPLGetErrorHandlerUserData());
    if (self && cls >= CE_Failure) self->last_ = msg ? msg : "unknown GDAL error";
  }
  std::string last_;
};

struct GdalCloser {
  void operator()(GDALDataset* ds) const { if (ds) GDALClose(ds); }
};
using DatasetPtr = std::unique_ptr<GDALDataset, GdalCloser>;

}  // namespace fdr::io::detail
