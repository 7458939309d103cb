// PostgreSQL sources: connection strings, their labels without passwords, opening for reading.
#include "gis/pg_source.hpp"

#include <cctype>

#include <cpl_error.h>
#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include "base/error.hpp"
#include "base/redact.hpp"
#include "gis/pg_open.hpp"

namespace fdr::gis {

bool is_pg_connection(std::string_view path) {
  return path.size() >= 3 && std::toupper(static_cast<unsigned char>(path[0])) == 'P' &&
         std::toupper(static_cast<unsigned char>(path[1])) == 'G' && path[2] == ':';
}

std::string source_label(const std::string& path) { return is_pg_connection(path) ? redact_passwords(path) : path; }

std::string pg_reason(std::string_view gdal_message) {
  std::string m(gdal_message);
  const std::string noise = "PQconnectdb failed.";
  if (m.rfind(noise, 0) == 0) m.erase(0, noise.size());
  std::string one;
  for (char c : m) {
    if (c == '\n' || c == '\r' || c == '\t') c = ' ';
    if (c == ' ' && (one.empty() || one.back() == ' ')) continue;
    one.push_back(c);
  }
  while (!one.empty() && one.back() == ' ') one.pop_back();
  return redact_passwords(one);
}

DatasetPtr open_pg_vector(const std::string& conn) {
  ensure_gdal_registered();
  GdalQuiet quiet;
  CPLErrorReset();
  const char* const drivers[] = {"PostgreSQL", nullptr};
  DatasetPtr ds(GDALDataset::Open(conn.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, drivers));
  if (!ds) {
    const std::string why = pg_reason(CPLGetLastErrorMsg());
    throw Error(ExitCode::kInputUnreadable,
                source_label(conn) + ": cannot connect" + (why.empty() ? std::string() : ": " + why));
  }
  return ds;
}

void check_pg_layer(OGRLayer& layer, const std::string& conn) {
  if (layer.GetLayerDefn()->GetGeomFieldCount() == 0)
    throw Error(ExitCode::kInputUnreadable, source_label(conn) + ": table '" + layer.GetName() +
                                                "' has no geometry column (give a table or view with one)");
}

}  // namespace fdr::gis
