// PostgreSQL/PostGIS sources and targets named by GDAL connection strings ("PG:dbname=... ").
#pragma once
#include <string>
#include <string_view>

namespace fdr::gis {

// True for a GDAL PostgreSQL connection string: "PG:" in any case, then libpq's keywords.
bool is_pg_connection(std::string_view path);

// How messages name a source or target: the connection string without its password (any
// other path unchanged).
std::string source_label(const std::string& path);

// A GDAL/libpq failure message as one line without passwords ("PQconnectdb failed." and the
// line breaks libpq puts between its parts dropped).
std::string pg_reason(std::string_view gdal_message);

}  // namespace fdr::gis
