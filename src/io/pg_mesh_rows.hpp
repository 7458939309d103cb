// The five PostGIS tables of a mesh (the GeoPackage's layers and columns): their columns, and
// their rows as binary COPY data.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "io/pg_copy.hpp"
#include "io/writer.hpp"

namespace fdr::io::detail {

struct PgTable {
  const char* name;          // without the prefix: nodes, triangles, boundaries, repairs, metadata
  bool spatial;              // has a geometry column `geom` (GiST-indexed)
  std::string columns;       // the columns after `fid bigserial`, for CREATE TABLE
  std::string copy_columns;  // the columns COPY fills, fid first
};

// The tables in their fixed order; geometries carry `srid` (0: none).
std::vector<PgTable> pg_tables(std::int32_t srid);

// Sends the rows of table `i` (the index in pg_tables) to `b`, fids 1, 2, ... as the GeoPackage's,
// and returns how many there are. Reads only `m` and `o` (several tables may be sent at once).
std::int64_t pg_rows(std::size_t i, pg::CopyBuffer& b, const mesh::MeshView& m, const WriteOptions& o,
                     std::int32_t srid);

}  // namespace fdr::io::detail
