// Bulk-loaded GeoPackage R-tree spatial index (gpkg_rtree_index extension), packed with Sort-Tile-Recursive.
#pragma once
#include <gdal_priv.h>

#include <cstdint>
#include <string>
#include <vector>

#include "io/gdal_util.hpp"

namespace fdr::io::detail {

struct RtreeEntry {
  std::int64_t id;                  // feature id (FID) of the row
  double minx, maxx, miny, maxy;    // geometry envelope
};

// Creates the spatial index of `layer_name` (created with SPATIAL_INDEX=NO and already filled)
// inside the current transaction: the rtree virtual table, its node/parent/rowid tables written
// directly from an STR-packed tree (SQLite inserts row by row with forced reinsertion, which is
// what made 1M-triangle GeoPackages take tens of seconds), the six maintenance triggers of the
// GeoPackage 1.2 rtree extension, and its gpkg_extensions row. Throws kOutputError naming `path`.
void build_gpkg_rtree(GDALDataset& ds, const std::string& layer_name, std::vector<RtreeEntry> entries,
                      const std::string& path, GdalErrors& errs);

}  // namespace fdr::io::detail
