// Bulk-loaded GeoPackage R-tree spatial index (gpkg_rtree_index extension), packed with Sort-Tile-Recursive.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "io/sqlite_bulk.hpp"
#include "io/sqlite_db.hpp"

namespace fdr::io::detail {

// One indexed row: its feature id (FID, >= 1) and its envelope rounded outwards to float (the
// R-tree's storage precision), so the index never loses a candidate.
// 20 bytes (a 32-bit id: 1.6 M entries of a 1 M-triangle mesh take 6 MB less while the writers
// run); of() refuses ids beyond 32 bits.
struct RtreeEntry {
  std::uint32_t id;
  float box[4];  // minx maxx miny maxy
  static RtreeEntry of(std::int64_t id, double minx, double maxx, double miny, double maxy);
};
static_assert(sizeof(RtreeEntry) == 20, "RtreeEntry is packed in 20 bytes");

// An STR-packed tree computed without the database (so on another thread while the rows are
// inserted): the cells of each level in packed order (level 0: the entries; above: one cell per
// node of the level below, its id that node's number) and the node sizes per level. Node
// numbers as build_gpkg_rtree writes them: 2, 3, ... level by level, the root 1.
struct RtreePlan {
  std::size_t cap = 0;  // cells per node the plan was made for
  std::vector<std::vector<RtreeEntry>> levels;
  std::vector<std::vector<std::size_t>> sizes;
};
RtreePlan plan_gpkg_rtree(std::vector<RtreeEntry> entries, std::size_t cap);
// Cells per node of a 2D rtree virtual table made in a database of this page size (SQLite's
// rule: node size page - 64 bytes, at most 51 cells); build_gpkg_rtree checks it against the
// table it creates.
std::size_t gpkg_rtree_cap(std::int64_t page_size);

// Creates the spatial index of `table`.`geom_col` (already filled) inside the current transaction:
// the rtree virtual table, its node/parent/rowid tables written directly from an STR-packed tree
// (SQLite inserts row by row with forced reinsertion, which is what made 1M-triangle GeoPackages
// take tens of seconds), the six maintenance triggers of the GeoPackage 1.2 rtree extension, and
// its gpkg_extensions row (the gpkg_extensions table must exist). Throws kOutputError.
void build_gpkg_rtree(SqliteDb& db, const std::string& table, const std::string& geom_col, const std::string& fid_col,
                      std::vector<RtreeEntry> entries);
// The same from a plan (made again here if its cap differs from the table's).
void build_gpkg_rtree(SqliteDb& db, const std::string& table, const std::string& geom_col, const std::string& fid_col,
                      RtreePlan plan);

// An R-tree whose shadow tables are filled by write_bulk_tables (sqlite_bulk.hpp) instead of
// SQL inserts: create_gpkg_rtree makes it with empty shadow tables (the virtual table, the
// triggers, the gpkg_extensions row) inside the current transaction; set_plan then takes the
// packed tree, whose ids must be 1..n (every row of the table indexed); add_tables describes
// the rows of _node, _parent and _rowid, as SQL inserts would have written them.
struct RtreeRows {
  std::string name;  // rtree_<table>_<geom>
  std::size_t node_size = 0;
  std::int64_t root_node = 0, root_parent = 0, root_rowid = 0;  // root pages of the shadow tables
  RtreePlan plan;
  struct NodeRef {
    std::uint32_t depth;       // level in the plan
    std::size_t first, count;  // its cells in plan.levels[depth]
  };
  std::vector<NodeRef> nodes;           // by node number - 1
  std::vector<std::int64_t> parent_of;  // by node number (0: the root)
  std::vector<std::uint32_t> leaf_of;   // by row id

  void set_plan(RtreePlan plan, const std::string& path_for_errors);  // re-packed if made for another cap
  void add_tables(std::vector<BulkTable>& out) const;                 // *this must outlive their use
};
// `filled`: the table has rows (set_plan will be called with their boxes); else the R-tree keeps
// the empty root node SQLite made.
RtreeRows create_gpkg_rtree(SqliteDb& db, const std::string& table, const std::string& geom_col, const std::string& fid_col,
                            bool filled);

}  // namespace fdr::io::detail
