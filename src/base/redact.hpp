// Passwords out of messages: database connection strings name their server in errors, logs and
// metadata, but never with the password a user typed into them.
#pragma once
#include <cctype>
#include <string>
#include <string_view>

namespace fdr {

namespace redact_detail {
inline bool iequal_at(std::string_view s, std::size_t at, std::string_view word) {
  if (at + word.size() > s.size()) return false;
  for (std::size_t k = 0; k < word.size(); ++k)
    if (std::tolower(static_cast<unsigned char>(s[at + k])) != word[k]) return false;
  return true;
}
inline bool is_space(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }
}  // namespace redact_detail

// `text` with every libpq password removed: the `password=VALUE` keyword (VALUE bare, or quoted
// in '...' with \' escapes, as libpq reads it; also as a URI query parameter) and the password
// of a "postgres[ql]://user:password@host" URI. Text without a password comes back unchanged.
inline std::string redact_passwords(std::string_view text) {
  using redact_detail::iequal_at;
  using redact_detail::is_space;
  std::string out;
  out.reserve(text.size());
  std::size_t i = 0;
  while (i < text.size()) {
    // A keyword starts a word (or follows '?' / '&' in a URI).
    const bool word_start = i == 0 || is_space(text[i - 1]) || text[i - 1] == '?' || text[i - 1] == '&' ||
                            text[i - 1] == ':' || text[i - 1] == '"' || text[i - 1] == '\'';
    if (word_start && iequal_at(text, i, "password")) {
      std::size_t j = i + 8;
      while (j < text.size() && is_space(text[j])) ++j;
      if (j < text.size() && text[j] == '=') {
        ++j;
        while (j < text.size() && is_space(text[j])) ++j;
        if (j < text.size() && text[j] == '\'') {
          for (++j; j < text.size() && text[j] != '\''; ++j)
            if (text[j] == '\\') ++j;
          if (j < text.size()) ++j;
        } else {
          while (j < text.size() && !is_space(text[j]) && text[j] != '&' && text[j] != '"') ++j;
        }
        // Drop the keyword and one blank beside it, so "a=1 password=x b=2" reads "a=1 b=2".
        if (j < text.size() && (text[j] == ' ' || text[j] == '&')) ++j;
        else if (!out.empty() && (out.back() == ' ' || out.back() == '&' || out.back() == '?')) out.pop_back();
        i = j;
        continue;
      }
    }
    // "postgresql://user:secret@host": the part between ':' and '@' of the authority.
    if (iequal_at(text, i, "postgres") && text.substr(i).find("://") <= 10) {
      const std::size_t auth = text.find("://", i) + 3;
      std::size_t end = auth;
      while (end < text.size() && !is_space(text[end]) && text[end] != '/' && text[end] != '?') ++end;
      const std::size_t at = text.substr(auth, end - auth).rfind('@');
      out.append(text.substr(i, auth - i));
      if (at != std::string_view::npos) {
        const std::string_view user_info = text.substr(auth, at);
        const std::size_t colon = user_info.find(':');
        out.append(user_info.substr(0, colon));
        i = auth + at;  // from the '@'
      } else {
        i = auth;
      }
      continue;
    }
    out.push_back(text[i++]);
  }
  return out;
}

}  // namespace fdr
