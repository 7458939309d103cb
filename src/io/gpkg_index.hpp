// GeoPackage spatial index (the gpkg_rtree_index extension) made through SQL: SQLite's rtree
// virtual table, its tables filled with INSERTs from a tree packed here, the extension's six
// maintenance triggers and its gpkg_extensions row.
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
// (ties by row), so that consecutive rows are near each other.
std::vector<std::uint32_t> rtree_insert_order(std::size_t n, const BoxOf& box);

// A cell of an R-tree node: a feature id (leaves) or a node number (above), and its box rounded
// outwards to float as SQLite's rtree stores it.
struct RtreeCell {
  std::uint32_t id;
  float box[4];  // minx maxx miny maxy
};
// An R-tree packed bottom-up: the boxes in rtree_insert_order cut into nodes of `cap` cells,
// those nodes' boxes cut the same way one level up, until a level fits in the root. levels[0]
// holds the leaves' cells, the last level the root's; node j of level l holds cells
// [j cap, (j + 1) cap) of levels[l]. Node numbers: the root 1, the others 2, 3, ... level by
// level from the leaves (the ids of the cells one level up).
struct PackedRtree {
  std::size_t cap = 0;
  std::vector<std::vector<RtreeCell>> levels;  // empty when no row has a box
};
PackedRtree pack_rtree(std::size_t n, const BoxOf& box, std::size_t cap);

// Creates rtree_<table>_<geom_col> inside the current transaction (the gpkg_extensions table
// must exist) and fills its tables with the packed tree of the boxes of rows [0, n) by SQL
// INSERTs (SQLite's own insertion, with its forced reinsertions, is dozens of times slower than
// plain row inserts); then adds the triggers (made last: they call functions only GeoPackage
// readers define) and the extension row.
void build_gpkg_rtree(SqliteDb& db, const std::string& table, const std::string& geom_col, std::size_t n,
                      const BoxOf& box);

}  // namespace fdr::io::detail
