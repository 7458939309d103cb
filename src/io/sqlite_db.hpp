// Thin SQLite helpers for the GeoPackage writer: an owned connection, prepared statements, and a
// batched multi-row INSERT (one statement binds many rows, so per-statement costs are paid rarely).
#pragma once
#include <sqlite3.h>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace fdr::io::detail {

// An open database; every failure throws kOutputError "<path>: <what>: <sqlite message>".
class SqliteDb {
 public:
  SqliteDb(const std::string& file, const std::string& path_for_errors);
  ~SqliteDb();
  SqliteDb(const SqliteDb&) = delete;
  SqliteDb& operator=(const SqliteDb&) = delete;

  sqlite3* get() const { return db_; }
  const std::string& path() const { return path_; }
  void exec(const std::string& sql);                       // one or more statements, no results
  std::int64_t query_int(const std::string& sql);          // first column of the first row (0 if none)
  [[noreturn]] void fail(const std::string& what) const;  // adds sqlite3_errmsg
  void close();                                            // throws if closing fails

 private:
  sqlite3* db_ = nullptr;
  std::string path_;
};

class SqliteStmt {
 public:
  SqliteStmt(SqliteDb& db, const std::string& sql);
  ~SqliteStmt();
  SqliteStmt(const SqliteStmt&) = delete;
  SqliteStmt& operator=(const SqliteStmt&) = delete;
  sqlite3_stmt* get() const { return st_; }
  void step_done(const char* what);  // step (expects SQLITE_DONE), then reset and clear bindings

 private:
  SqliteDb& db_;
  sqlite3_stmt* st_ = nullptr;
};

// INSERT INTO <table>(<cols>) VALUES (...),(...),... with `rows_per_stmt` rows a statement.
// Values of a row are appended with the add_* calls (in column order), end_row() closes it; the
// last partial batch is written by finish() through a statement of its own size. Blob and text
// bytes are copied into the batch, so callers may reuse their buffers.
class BatchInsert {
 public:
  BatchInsert(SqliteDb& db, std::string table, std::vector<std::string> cols, std::size_t rows_per_stmt = 128);
  ~BatchInsert();
  BatchInsert(const BatchInsert&) = delete;
  BatchInsert& operator=(const BatchInsert&) = delete;
  BatchInsert& add_int(std::int64_t v) { cur_.vals.push_back({kInt, 0, {.i = v}}); return *this; }
  BatchInsert& add_real(double v) { cur_.vals.push_back({kReal, 0, {.d = v}}); return *this; }
  BatchInsert& add_real_or_null(double v);  // NULL for NaN/inf
  BatchInsert& add_null() { cur_.vals.push_back({kNull, 0, {.i = 0}}); return *this; }
  BatchInsert& add_blob(const void* data, std::size_t n);
  BatchInsert& add_text(std::string_view s);
  void end_row() {
    if (++cur_.rows == per_stmt_) flush();
  }
  void finish();  // writes the remaining rows

 private:
  enum Type : std::uint8_t { kNull, kInt, kReal, kBlob, kText };
  struct Val {
    Type type;
    std::uint32_t len;  // blob/text bytes
    union {
      std::int64_t i;
      double d;
      std::uint64_t off;  // into the batch's bytes (blob/text)
    };
  };
  struct Batch {
    std::vector<Val> vals;
    std::string bytes;
    std::size_t rows = 0;
  };
  void flush();
  void write(Batch& b);  // binds and steps one batch
  sqlite3_stmt* prepare(std::size_t rows);
  SqliteDb& db_;
  std::string table_;
  std::vector<std::string> cols_;
  std::size_t per_stmt_;
  sqlite3_stmt* full_ = nullptr;
  Batch cur_;
};

}  // namespace fdr::io::detail
