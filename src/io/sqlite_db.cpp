// Thin SQLite helpers for the GeoPackage writer (see sqlite_db.hpp).
#include "io/sqlite_db.hpp"

#include <algorithm>
#include <cmath>

#include "io/detail.hpp"

namespace fdr::io::detail {

SqliteDb::SqliteDb(const std::string& file, const std::string& path_for_errors) : path_(path_for_errors) {
  const int rc = sqlite3_open_v2(file.c_str(), &db_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE | SQLITE_OPEN_NOMUTEX,
                                 nullptr);
  if (rc != SQLITE_OK) {
    std::string msg = db_ ? sqlite3_errmsg(db_) : sqlite3_errstr(rc);
    sqlite3_close(db_);
    db_ = nullptr;
    fail_output(path_, "cannot create the GeoPackage: " + msg);
  }
}

SqliteDb::~SqliteDb() {
  if (db_) sqlite3_close_v2(db_);
}

void SqliteDb::fail(const std::string& what) const {
  fail_output(path_, what + ": " + (db_ ? sqlite3_errmsg(db_) : "database closed"));
}

void SqliteDb::exec(const std::string& sql) {
  char* err = nullptr;
  if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &err) != SQLITE_OK) {
    std::string msg = err ? err : sqlite3_errmsg(db_);
    sqlite3_free(err);
    const std::string head = sql.substr(0, 60);
    fail_output(path_, "SQLite failed on '" + head + (sql.size() > 60 ? "...'" : "'") + ": " + msg);
  }
}

std::int64_t SqliteDb::query_int(const std::string& sql) {
  SqliteStmt st(*this, sql);
  std::int64_t v = 0;
  const int rc = sqlite3_step(st.get());
  if (rc == SQLITE_ROW) v = sqlite3_column_int64(st.get(), 0);
  else if (rc != SQLITE_DONE) fail("query failed");
  return v;
}

void SqliteDb::close() {
  if (!db_) return;
  const int rc = sqlite3_close(db_);
  if (rc != SQLITE_OK) fail("closing the GeoPackage failed");
  db_ = nullptr;
}

SqliteStmt::SqliteStmt(SqliteDb& db, const std::string& sql) : db_(db) {
  if (sqlite3_prepare_v2(db.get(), sql.c_str(), static_cast<int>(sql.size()), &st_, nullptr) != SQLITE_OK)
    db.fail("cannot prepare '" + sql.substr(0, 60) + "'");
}
SqliteStmt::~SqliteStmt() { sqlite3_finalize(st_); }

void SqliteStmt::step_done(const char* what) {
  if (sqlite3_step(st_) != SQLITE_DONE) db_.fail(what);
  sqlite3_reset(st_);
  sqlite3_clear_bindings(st_);
}

BatchInsert::BatchInsert(SqliteDb& db, std::string table, std::vector<std::string> cols, std::size_t rows_per_stmt)
    : db_(db), table_(std::move(table)), cols_(std::move(cols)), per_stmt_(rows_per_stmt ? rows_per_stmt : 1) {
  // Stay within this SQLite build's limit on bound parameters per statement (999 in old builds).
  const int max_vars = sqlite3_limit(db.get(), SQLITE_LIMIT_VARIABLE_NUMBER, -1);
  if (!cols_.empty() && max_vars > 0)
    per_stmt_ = std::max<std::size_t>(1, std::min(per_stmt_, static_cast<std::size_t>(max_vars) / cols_.size()));
  cur_.vals.reserve(per_stmt_ * cols_.size());
}

BatchInsert::~BatchInsert() { sqlite3_finalize(full_); }

BatchInsert& BatchInsert::add_real_or_null(double v) {
  return std::isfinite(v) ? add_real(v) : add_null();
}

BatchInsert& BatchInsert::add_blob(const void* data, std::size_t n) {
  cur_.vals.push_back({kBlob, static_cast<std::uint32_t>(n), {.off = cur_.bytes.size()}});
  cur_.bytes.append(static_cast<const char*>(data), n);
  return *this;
}

BatchInsert& BatchInsert::add_text(std::string_view s) {
  cur_.vals.push_back({kText, static_cast<std::uint32_t>(s.size()), {.off = cur_.bytes.size()}});
  cur_.bytes.append(s);
  return *this;
}

sqlite3_stmt* BatchInsert::prepare(std::size_t rows) {
  std::string sql = "INSERT INTO \"" + table_ + "\" (";
  for (std::size_t c = 0; c < cols_.size(); ++c) sql += (c ? ",\"" : "\"") + cols_[c] + "\"";
  sql += ") VALUES ";
  std::string one = "(";
  for (std::size_t c = 0; c < cols_.size(); ++c) one += c ? ",?" : "?";
  one += ")";
  for (std::size_t r = 0; r < rows; ++r) {
    if (r) sql += ',';
    sql += one;
  }
  sqlite3_stmt* st = nullptr;
  if (sqlite3_prepare_v3(db_.get(), sql.c_str(), static_cast<int>(sql.size()), SQLITE_PREPARE_PERSISTENT, &st, nullptr) !=
      SQLITE_OK)
    db_.fail("cannot prepare the insert into '" + table_ + "'");
  return st;
}

void BatchInsert::write(Batch& b) {
  if (b.vals.size() != b.rows * cols_.size())
    fail_output(db_.path(), "internal: wrong number of values for table '" + table_ + "'");
  sqlite3_stmt* st;
  sqlite3_stmt* partial = nullptr;
  if (b.rows == per_stmt_) {
    if (!full_) full_ = prepare(per_stmt_);
    st = full_;
  } else {
    st = partial = prepare(b.rows);
  }
  int rc = SQLITE_OK;
  for (std::size_t i = 0; i < b.vals.size() && rc == SQLITE_OK; ++i) {
    const Val& v = b.vals[i];
    const int k = static_cast<int>(i + 1);
    switch (v.type) {
      case kNull: rc = sqlite3_bind_null(st, k); break;
      case kInt: rc = sqlite3_bind_int64(st, k, v.i); break;
      case kReal: rc = sqlite3_bind_double(st, k, v.d); break;
      case kBlob: rc = sqlite3_bind_blob64(st, k, b.bytes.data() + v.off, v.len, SQLITE_STATIC); break;
      case kText: rc = sqlite3_bind_text64(st, k, b.bytes.data() + v.off, v.len, SQLITE_STATIC, SQLITE_UTF8); break;
    }
  }
  if (rc == SQLITE_OK) rc = sqlite3_step(st);
  const bool ok = rc == SQLITE_DONE;
  std::string msg = ok ? "" : sqlite3_errmsg(db_.get());
  sqlite3_reset(st);
  sqlite3_finalize(partial);
  if (!ok) fail_output(db_.path(), "cannot write rows of table '" + table_ + "': " + msg);
  b.vals.clear();
  b.bytes.clear();
  b.rows = 0;
}

void BatchInsert::flush() {
  if (cur_.rows > 0) write(cur_);
}

void BatchInsert::finish() { flush(); }

}  // namespace fdr::io::detail
