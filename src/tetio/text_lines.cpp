// Reading the 3D input formats: file bytes, tokenised data lines, strict numbers.
#include "tetio/text_lines.hpp"

#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

namespace fdr::tetio {

std::string read_file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    int e = errno;
    throw Error(ExitCode::kInputUnreadable, path + ": cannot open: " + std::strerror(e));
  }
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw Error(ExitCode::kInputUnreadable, path + ": read failed");
  return std::move(ss).str();
}

void fail_malformed(const std::string& path, std::size_t line, const std::string& what) {
  std::string msg = path;
  if (line > 0) msg += ":" + std::to_string(line);
  throw Error(ExitCode::kInputMalformed, msg + ": " + what);
}

TextLines::TextLines(std::string path, std::string text) : path_(std::move(path)), text_(std::move(text)) {}

bool TextLines::next() {
  tokens_.clear();
  while (pos_ < text_.size()) {
    line_ = next_line_++;
    std::size_t end = text_.find('\n', pos_);
    if (end == std::string::npos) end = text_.size();
    std::string_view row(text_.data() + pos_, end - pos_);
    pos_ = end + 1;
    if (auto hash = row.find('#'); hash != std::string_view::npos) row = row.substr(0, hash);
    std::size_t i = 0;
    while (i < row.size()) {
      while (i < row.size() && (std::isspace(static_cast<unsigned char>(row[i])) || row[i] == ',')) ++i;
      std::size_t j = i;
      while (j < row.size() && !std::isspace(static_cast<unsigned char>(row[j])) && row[j] != ',') ++j;
      if (j > i) tokens_.push_back(row.substr(i, j - i));
      i = j;
    }
    if (!tokens_.empty()) return true;
  }
  pos_ = text_.size();
  return false;
}

void TextLines::expect(const std::string& what) {
  if (!next()) fail_malformed(path_, line_, "unexpected end of file, expected " + what);
}

std::string_view TextLines::token(std::size_t i) const {
  if (i >= tokens_.size()) fail("missing field " + std::to_string(i + 1) + " on this line");
  return tokens_[i];
}

void TextLines::need(std::size_t n, const std::string& what) const {
  if (tokens_.size() < n) {
    fail("expected " + what + " (" + std::to_string(n) + " fields), found " + std::to_string(tokens_.size()));
  }
}

std::int64_t TextLines::integer(std::size_t i) const {
  std::int64_t v = 0;
  if (!parse_integer(token(i), v)) fail("field " + std::to_string(i + 1) + " '" + shown(token(i)) + "' is not an integer");
  return v;
}

double TextLines::real(std::size_t i) const {
  double v = 0;
  if (!parse_real(token(i), v)) {
    fail("field " + std::to_string(i + 1) + " '" + shown(token(i)) + "' is not a finite number");
  }
  return v;
}

std::string shown(std::string_view token) {
  std::string out;
  for (std::size_t i = 0; i < token.size() && i < 40; ++i) {
    const auto c = static_cast<unsigned char>(token[i]);
    if (c >= 0x20 && c < 0x7f) {
      out.push_back(static_cast<char>(c));
    } else {
      static constexpr char kHex[] = "0123456789abcdef";
      out += "\\x";
      out.push_back(kHex[c >> 4]);
      out.push_back(kHex[c & 15]);
    }
  }
  if (token.size() > 40) out += "...";
  return out;
}

bool parse_integer(std::string_view s, std::int64_t& out) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  auto r = std::from_chars(s.data(), s.data() + s.size(), out);
  return r.ec == std::errc() && r.ptr == s.data() + s.size() && !s.empty();
}

bool parse_real(std::string_view s, double& out) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  auto r = std::from_chars(s.data(), s.data() + s.size(), out);
  return r.ec == std::errc() && r.ptr == s.data() + s.size() && !s.empty() && std::isfinite(out);
}

}  // namespace fdr::tetio
