// PostGIS output: the GeoPackage's layers as tables of a PostgreSQL database, loaded with binary
// COPY over libpq, all or nothing.
#pragma once
#include <string>

#include "io/writer.hpp"

namespace fdr::io::detail {

// Writes <prefix>nodes, <prefix>triangles, <prefix>boundaries, <prefix>repairs (with GiST
// indexes on geom) and <prefix>metadata into the database of `conn` ("PG:dbname=... ", the
// prefix optional): filled in a staging schema, then moved into place in one transaction; on
// any failure the staging schema is dropped and the database is as it was. An existing table of
// the same names is refused unless o.postgis.overwrite.
// Errors are kOutputError "<conn without password>: <reason>" (kUsage for a bad prefix).
void write_postgis(const mesh::MeshView& m, const std::string& conn, const WriteOptions& o);

}  // namespace fdr::io::detail
