// Helpers shared by the netCDF writers (UGRID, Delft3D FM net file): checked calls, attributes,
// the CRS of a mesh in the forms CF and Deltares tools read.
#pragma once
#include <netcdf.h>

#include <mutex>
#include <string>

#include "io/detail.hpp"

namespace fdr::io::detail {

// libnetcdf keeps global state without locks (as Debian builds it), and the writers of one run may
// go in parallel: each netCDF writer holds this for its whole file, from create to close or abort.
inline std::mutex& nc_mutex() {
  static std::mutex m;
  return m;
}

// Owns an open netCDF id; aborts (discarding changes) unless closed explicitly.
struct NcFile {
  int id = -1;
  NcFile() = default;
  NcFile(const NcFile&) = delete;
  NcFile& operator=(const NcFile&) = delete;
  ~NcFile() { if (id >= 0) nc_abort(id); }
};

// Checked netCDF calls that fail with Error(kOutputError, "<path>: netCDF <what>: <reason>").
struct Nc {
  const std::string& path;
  void check(int status, const char* what) const {
    if (status != NC_NOERR) fail_output(path, std::string("netCDF ") + what + ": " + nc_strerror(status));
  }
  void text(int nc, int var, const char* name, const std::string& v) const {
    check(nc_put_att_text(nc, var, name, v.size(), v.c_str()), name);
  }
  void integer(int nc, int var, const char* name, int v) const {
    check(nc_put_att_int(nc, var, name, NC_INT, 1, &v), name);
  }
  void real(int nc, int var, const char* name, double v) const {
    check(nc_put_att_double(nc, var, name, NC_DOUBLE, 1, &v), name);
  }
};

// A mesh CRS described for netCDF attributes; empty wkt1 when the mesh has none.
struct NcCrs {
  bool geographic = false;
  std::string wkt1, wkt2;  // WKT1 (GDAL) and WKT2_2019
  int epsg = 0;            // 0 when no EPSG code is known
  double semi_major = 0, semi_minor = 0, inverse_flattening = 0;
  std::string name;        // CRS name
};
// Parses m.crs_wkt (fails with kOutputError naming `path` if it cannot be parsed).
NcCrs nc_crs(const std::string& crs_wkt, const std::string& path);

}  // namespace fdr::io::detail
