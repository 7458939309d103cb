// GeoPackage spatial index (the gpkg_rtree_index extension) made through SQL: SQLite's rtree
// virtual table filled with INSERTs, the extension's six maintenance triggers and its
// gpkg_extensions row.
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "io/sqlite_db.hpp"

namespace fdr::io::detail {

// Position of the cell (x, y) of a 2^16 x 2^16 grid along a Hilbert curve that starts at (0, 0):
// consecutive positions are neighbouring cells, so boxes taken in this order are near each other.
std::uint32_t hilbert_key(std::uint32_t x, std::uint32_t y);

struct IndexBox {
  double minx, maxx, miny, maxy;
};
// box(i, out) gives the envelope of row i (feature id i + 1), or false when the row has none.
using BoxOf = std::function<bool(std::size_t, IndexBox&)>;

// The rows of [0, n) that have a box, ordered along the Hilbert curve over their box centres
// (ties by row): SQLite's R-tree then inserts each box next to the previous ones, into nodes it
// has just read.
std::vector<std::uint32_t> rtree_insert_order(std::size_t n, const BoxOf& box);

// Creates rtree_<table>_<geom_col> inside the current transaction (the gpkg_extensions table
// must exist), inserts the boxes of rows [0, n) in rtree_insert_order, then adds the triggers
// (made last: they call functions only GeoPackage readers define) and the extension row.
void build_gpkg_rtree(SqliteDb& db, const std::string& table, const std::string& geom_col, std::size_t n,
                      const BoxOf& box);

}  // namespace fdr::io::detail
