// Reading the 3D input formats: a whole file in memory, its lines as tokens (TetGen's '#'
// comments and blank lines skipped), numbers parsed strictly, and errors that name file and line.
#pragma once
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>
#include "base/error.hpp"

namespace fdr::tetio {

// The bytes of `path`; a missing or unreadable file is Error(kInputUnreadable).
std::string read_file_bytes(const std::string& path);

// "<path>:<line>: <what>" as Error(kInputMalformed) (line 0: no line).
[[noreturn]] void fail_malformed(const std::string& path, std::size_t line, const std::string& what);

// The data lines of a text file: each a list of whitespace-separated tokens, with everything from
// '#' to the end of the line dropped and empty lines skipped.
class TextLines {
 public:
  TextLines(std::string path, std::string text);
  // Advances to the next data line; false at the end of the file.
  bool next();
  // Advances to the next data line or fails with "unexpected end of file, expected <what>".
  void expect(const std::string& what);
  std::size_t line() const { return line_; }
  std::size_t size() const { return tokens_.size(); }
  std::string_view token(std::size_t i) const;  // fails when the line has fewer tokens
  // The i-th token as a number: an integer, or a finite double (NaN/inf are rejected).
  std::int64_t integer(std::size_t i) const;
  double real(std::size_t i) const;
  // Requires at least n tokens on the line, naming what they are.
  void need(std::size_t n, const std::string& what) const;
  [[noreturn]] void fail(const std::string& what) const { fail_malformed(path_, line_, what); }
  const std::string& path() const { return path_; }

 private:
  std::string path_, text_;
  std::size_t pos_ = 0, line_ = 0, next_line_ = 1;
  std::vector<std::string_view> tokens_;
};

// A token as an error message shows it: at most 40 characters, bytes outside printable ASCII as
// \xNN (a damaged file must not put raw bytes into messages and logs).
std::string shown(std::string_view token);

// Strict number parsing of one token (whole token, no trailing characters).
bool parse_integer(std::string_view s, std::int64_t& out);
bool parse_real(std::string_view s, double& out);  // false for non-numbers and for NaN/inf

}  // namespace fdr::tetio
