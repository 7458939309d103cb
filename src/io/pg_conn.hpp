// One libpq connection of the PostGIS writer: GDAL's "PG:" connection string turned into libpq's,
// statements, and COPY streams; every failure an output error naming the connection without its
// password.
#pragma once
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

struct pg_conn;

namespace fdr::io::pg {

// A GDAL PostgreSQL connection string split into what libpq takes and what only GDAL knows.
struct ConnInfo {
  std::string libpq;         // libpq's keywords (or a postgresql:// URI) as given
  std::string first_schema;  // the first name of GDAL's `schemas=a,b`, or ""
};

// Parses "PG:key=value key='quoted \' value' ..." (the "PG:" optional) with libpq's quoting,
// dropping GDAL's own keywords (schemas, tables, active_schema, list_all_tables); a
// "postgresql://" URI passes through. kUsage naming `label` when a quote is left open.
ConnInfo parse_connection(std::string_view gdal_conn, const std::string& label);

std::string quote_ident(std::string_view s);
std::string quote_literal(std::string_view s);

// SQLSTATE of a refused privilege (the writer then loads without a staging schema).
inline constexpr const char* kInsufficientPrivilege = "42501";

class Connection {
 public:
  // Connects (client encoding UTF8); kOutputError "<label>: cannot connect: <server's reason>".
  Connection(const std::string& libpq_conninfo, const std::string& label);
  ~Connection();
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;

  const std::string& label() const { return label_; }
  // Runs one or more statements; kOutputError "<label>: <what>: <server's reason>" on failure.
  void exec(const std::string& sql, const std::string& what);
  // As exec, but returns false with the SQLSTATE in `state` instead of throwing.
  bool try_exec(const std::string& sql, std::string& state);
  // The first column of every row of a query.
  std::vector<std::string> column(const std::string& sql, const std::string& what);
  // COPY ... FROM STDIN: begin, send bytes, end (the server's verdict comes with end).
  void copy_begin(const std::string& sql, const std::string& what);
  void copy_put(const char* data, std::size_t n);
  void copy_end();
  // False once the server or the socket is gone.
  bool alive() const;
  [[noreturn]] void fail(const std::string& what) const;

 private:
  pg_conn* c_ = nullptr;
  std::string label_;
  std::string copy_what_;
};

}  // namespace fdr::io::pg
