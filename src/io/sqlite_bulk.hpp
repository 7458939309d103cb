// Rowid tables filled by writing their B-tree pages straight into a closed SQLite database file,
// as SQLite's file format documents them (https://www.sqlite.org/fileformat2.html): for the
// GeoPackage writer's big tables, whose rows SQLite itself inserts at about 1 M rows/s on one
// thread. The tables are created (empty) by SQLite; this only adds their rows.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace fdr::io::detail {

// One row in SQLite's record format (a header of serial types, then the values) and its rowid.
// The add_* calls take the columns in order, as BatchInsert's do (a row builder can be written
// once for both). Integers take SQLite's smallest serial type; reals are stored as 8-byte
// floats (SQLite may store an integral real as an integer: the value read back is the same).
class Record {
 public:
  static constexpr int kMaxColumns = 32;
  void clear(std::int64_t rowid) {
    rowid_ = rowid;
    ntypes_ = 0;
    type_bytes_ = 0;
    body_.clear();
  }
  Record& add_int(std::int64_t v);
  Record& add_real(double v);
  Record& add_real_or_null(double v);  // NULL for NaN/inf (as BatchInsert)
  Record& add_null() { return type(0); }
  Record& add_blob(const void* data, std::size_t n);
  Record& add_text(std::string_view s);
  void end_row() {}

  std::int64_t rowid() const { return rowid_; }
  std::size_t payload_size() const;
  // The table-leaf cell: varint(payload size), varint(rowid), payload.
  std::size_t cell_size() const;
  char* write_cell(char* out) const;  // returns the end

 private:
  Record& type(std::uint64_t t);
  std::size_t header_size() const;
  std::int64_t rowid_ = 0;
  int ntypes_ = 0;
  std::size_t type_bytes_ = 0;  // the serial types' varints
  std::uint64_t types_[kMaxColumns];
  std::string body_;
};

// A table to fill: `row(i, r)` builds row i of `rows` into r (r.clear(rowid) first); rowids
// must ascend. Rows are built on two threads at once unless a table says it cannot be.
struct BulkTable {
  std::string name;        // for messages
  std::int64_t root = 0;   // root page (an empty table leaf, as CREATE TABLE leaves it)
  std::size_t rows = 0;
  bool thread_safe = true;  // false: every row built on one thread (then every table's are)
  std::function<void(std::size_t, Record&)> row;
};

// Appends the tables' pages to the database file `file` (closed, not in WAL mode, no
// auto-vacuum, every table's root an empty leaf) and makes each root the top of its table's
// B-tree; the header's page count and change counter are updated. `pending_byte` is SQLite's
// lock-byte offset (its page is never used). Throws kOutputError naming `path_for_errors`.
void write_bulk_tables(const std::string& file, const std::string& path_for_errors, const std::vector<BulkTable>& tables,
                       std::uint64_t pending_byte = 0x40000000);

}  // namespace fdr::io::detail
