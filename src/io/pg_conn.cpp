// One libpq connection of the PostGIS writer (see pg_conn.hpp).
#include "io/pg_conn.hpp"

#include <libpq-fe.h>

#include <cctype>
#include <memory>

#include "base/error.hpp"
#include "gis/pg_source.hpp"

namespace fdr::io::pg {

namespace {

bool starts_with_ci(std::string_view s, std::string_view p) {
  if (s.size() < p.size()) return false;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(s[i])) != p[i]) return false;
  return true;
}

bool is_gdal_keyword(const std::string& k) {
  return k == "schemas" || k == "tables" || k == "active_schema" || k == "list_all_tables";
}

// A value as libpq reads it: '...' with \' and \\ inside, or up to the next blank with \ escapes.
std::string read_value(std::string_view s, std::size_t& i, bool& open_quote) {
  std::string v;
  open_quote = false;
  if (i < s.size() && s[i] == '\'') {
    ++i;
    while (i < s.size() && s[i] != '\'') {
      if (s[i] == '\\' && i + 1 < s.size()) ++i;
      v += s[i++];
    }
    if (i >= s.size()) open_quote = true;
    else ++i;
    return v;
  }
  while (i < s.size() && !std::isspace(static_cast<unsigned char>(s[i]))) {
    if (s[i] == '\\' && i + 1 < s.size()) ++i;
    v += s[i++];
  }
  return v;
}

std::string quote_value(const std::string& v) {
  std::string r = "'";
  for (char c : v) {
    if (c == '\'' || c == '\\') r += '\\';
    r += c;
  }
  return r + "'";
}

struct ResultFree {
  void operator()(PGresult* r) const { PQclear(r); }
};
using Result = std::unique_ptr<PGresult, ResultFree>;

}  // namespace

ConnInfo parse_connection(std::string_view s, const std::string& label) {
  if (starts_with_ci(s, "pg:")) s.remove_prefix(3);
  ConnInfo out;
  if (starts_with_ci(s, "postgresql://") || starts_with_ci(s, "postgres://")) {
    out.libpq = std::string(s);
    return out;
  }
  std::size_t i = 0;
  while (true) {
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    if (i >= s.size()) break;
    std::string key;
    while (i < s.size() && s[i] != '=' && !std::isspace(static_cast<unsigned char>(s[i]))) key += s[i++];
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    std::string value;
    if (i < s.size() && s[i] == '=') {
      ++i;
      while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
      bool open_quote = false;
      value = read_value(s, i, open_quote);
      if (open_quote) throw Error(ExitCode::kUsage, label + ": a quoted value of '" + key + "' is not closed");
    }
    std::string lower;
    for (char c : key) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (is_gdal_keyword(lower)) {
      if (lower == "schemas" && out.first_schema.empty()) out.first_schema = value.substr(0, value.find(','));
      continue;
    }
    if (!out.libpq.empty()) out.libpq += ' ';
    out.libpq += key + "=" + quote_value(value);
  }
  return out;
}

std::string quote_ident(std::string_view s) {
  std::string r = "\"";
  for (char c : s) {
    if (c == '"') r += '"';
    r += c;
  }
  return r + "\"";
}

std::string quote_literal(std::string_view s) {
  std::string r = "'";
  for (char c : s) {
    if (c == '\'') r += '\'';
    r += c;
  }
  return r + "'";
}

Connection::Connection(const std::string& conninfo, const std::string& label) : label_(label) {
  c_ = PQconnectdb(conninfo.c_str());
  if (!c_ || PQstatus(c_) != CONNECTION_OK) {
    const std::string why = c_ ? gis::pg_reason(PQerrorMessage(c_)) : std::string("out of memory");
    if (c_) PQfinish(c_);
    c_ = nullptr;
    throw Error(ExitCode::kOutputError, label_ + ": cannot connect" + (why.empty() ? "" : ": " + why));
  }
  if (PQsetClientEncoding(c_, "UTF8") != 0) fail("cannot set the client encoding to UTF8");
  // The server's notices ("drop cascades to ...") are not the user's business; errors are.
  PQsetNoticeProcessor(c_, [](void*, const char*) {}, nullptr);
}

Connection::~Connection() {
  if (c_) PQfinish(c_);
}

void Connection::fail(const std::string& what) const {
  std::string why = c_ ? gis::pg_reason(PQerrorMessage(c_)) : std::string();
  throw Error(ExitCode::kOutputError, label_ + ": " + what + (why.empty() ? "" : ": " + why));
}

void Connection::exec(const std::string& sql, const std::string& what) {
  std::string state;
  if (!try_exec(sql, state)) fail(what);
}

bool Connection::try_exec(const std::string& sql, std::string& state) {
  Result r(PQexec(c_, sql.c_str()));
  const ExecStatusType st = r ? PQresultStatus(r.get()) : PGRES_FATAL_ERROR;
  if (st == PGRES_COMMAND_OK || st == PGRES_TUPLES_OK) return true;
  const char* code = r ? PQresultErrorField(r.get(), PG_DIAG_SQLSTATE) : nullptr;
  state = code ? code : "";
  return false;
}

std::vector<std::string> Connection::column(const std::string& sql, const std::string& what) {
  Result r(PQexec(c_, sql.c_str()));
  if (!r || PQresultStatus(r.get()) != PGRES_TUPLES_OK) fail(what);
  std::vector<std::string> out;
  for (int i = 0; i < PQntuples(r.get()); ++i) out.emplace_back(PQgetisnull(r.get(), i, 0) ? "" : PQgetvalue(r.get(), i, 0));
  return out;
}

void Connection::copy_begin(const std::string& sql, const std::string& what) {
  copy_what_ = what;
  Result r(PQexec(c_, sql.c_str()));
  if (!r || PQresultStatus(r.get()) != PGRES_COPY_IN) fail(what);
}

void Connection::copy_put(const char* data, std::size_t n) {
  // libpq takes at most INT_MAX bytes at a time; the writer sends far smaller pieces.
  if (PQputCopyData(c_, data, static_cast<int>(n)) != 1) fail(copy_what_);
}

void Connection::copy_end() {
  if (PQputCopyEnd(c_, nullptr) != 1) fail(copy_what_);
  bool ok = true;
  while (Result r{PQgetResult(c_)}) ok = ok && PQresultStatus(r.get()) == PGRES_COMMAND_OK;
  if (!ok) fail(copy_what_);
}

bool Connection::alive() const { return c_ && PQstatus(c_) == CONNECTION_OK; }

}  // namespace fdr::io::pg
