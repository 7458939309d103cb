// Bulk-loaded GeoPackage R-tree spatial index (gpkg_rtree_index extension), packed with Sort-Tile-Recursive.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "io/sqlite_db.hpp"

namespace fdr::io::detail {

// One indexed row: its feature id (FID, >= 1) and its envelope rounded outwards to float (the
// R-tree's storage precision), so the index never loses a candidate.
struct RtreeEntry {
  std::int64_t id;
  float box[4];  // minx maxx miny maxy
  static RtreeEntry of(std::int64_t id, double minx, double maxx, double miny, double maxy);
};

// Creates the spatial index of `table`.`geom_col` (already filled) inside the current transaction:
// the rtree virtual table, its node/parent/rowid tables written directly from an STR-packed tree
// (SQLite inserts row by row with forced reinsertion, which is what made 1M-triangle GeoPackages
// take tens of seconds), the six maintenance triggers of the GeoPackage 1.2 rtree extension, and
// its gpkg_extensions row (the gpkg_extensions table must exist). Throws kOutputError.
void build_gpkg_rtree(SqliteDb& db, const std::string& table, const std::string& geom_col, const std::string& fid_col,
                      std::vector<RtreeEntry> entries);

}  // namespace fdr::io::detail
