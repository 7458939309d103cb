// ExpressionField: muparser-backed spacing expression with native paper-f1/paper-f2 operands.
#include "sizing/expression_field.hpp"

#include <muParser.h>

#include <cctype>
#include <limits>

#include "base/error.hpp"
#include "sizing/fields.hpp"

namespace fdr::sizing {

namespace {

bool is_ident_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// Replaces the preset names "paper-f1"/"paper-f2" (hyphenated, so not muparser identifiers)
// by the same-length variable names "paper_f1"/"paper_f2": error positions stay valid.
std::string substitute_presets(std::string s) {
  for (const char* name : {"paper-f1", "paper-f2"}) {
    const std::string n(name);
    for (std::size_t pos = s.find(n); pos != std::string::npos; pos = s.find(n, pos + 1)) {
      const bool left_ok = pos == 0 || !is_ident_char(s[pos - 1]);
      const bool right_ok = pos + n.size() >= s.size() || !is_ident_char(s[pos + n.size()]);
      if (left_ok && right_ok) s[pos + 5] = '_';
    }
  }
  return s;
}

// muparser messages sometimes end in " found at position N." / " at position N"; we append
// our own 1-based position, so strip theirs.
std::string strip_position(std::string msg) {
  const std::string tag = " at position ";
  const std::size_t p = msg.rfind(tag);
  if (p == std::string::npos) return msg;
  std::size_t q = p + tag.size();
  if (q >= msg.size() || !std::isdigit(static_cast<unsigned char>(msg[q]))) return msg;
  while (q < msg.size() && std::isdigit(static_cast<unsigned char>(msg[q]))) ++q;
  if (q < msg.size() && msg[q] == '.') ++q;
  if (q != msg.size()) return msg;
  std::size_t cut = p;
  const std::string found = " found";
  if (cut >= found.size() && msg.compare(cut - found.size(), found.size(), found) == 0) cut -= found.size();
  return msg.substr(0, cut);
}

[[noreturn]] void throw_parse_error(const std::string& expr, const std::string& msg, std::size_t pos0) {
  const std::size_t pos1 = std::min(pos0, expr.size()) + 1;
  throw Error(ExitCode::kUsage,
              "spacing expression '" + expr + "': " + msg + " at position " + std::to_string(pos1));
}

}  // namespace

struct ExpressionField::Impl {
  mu::Parser parser;
  double x = 0, y = 0, f1 = 0, f2 = 0;
  bool use_f1 = false, use_f2 = false;
  PaperF1Field paper_f1;
  PaperF2Field paper_f2;
};

ExpressionField::ExpressionField(const std::string& expr) : expr_(expr), impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  const std::string text = substitute_presets(expr);
  try {
    m.parser.DefineVar("x", &m.x);
    m.parser.DefineVar("y", &m.y);
    m.parser.DefineVar("paper_f1", &m.f1);
    m.parser.DefineVar("paper_f2", &m.f2);
    m.parser.SetExpr(text);
    m.parser.Eval();  // muparser parses lazily: force syntax errors out now
  } catch (const mu::Parser::exception_type& e) {
    throw_parse_error(expr, strip_position(e.GetMsg()), static_cast<std::size_t>(e.GetPos()));
  }
  if (m.parser.GetNumResults() != 1) {
    // Report the first comma outside parentheses.
    int depth = 0;
    std::size_t at = 0;
    for (std::size_t k = 0; k < text.size(); ++k) {
      if (text[k] == '(') ++depth;
      if (text[k] == ')') --depth;
      if (text[k] == ',' && depth == 0) { at = k; break; }
    }
    throw_parse_error(expr, "several comma-separated results, expected one", at);
  }
  const auto& used = m.parser.GetUsedVar();
  m.use_f1 = used.count("paper_f1") != 0;
  m.use_f2 = used.count("paper_f2") != 0;
}

ExpressionField::~ExpressionField() = default;

double ExpressionField::operator()(Point2 p) const {
  Impl& m = *impl_;
  m.x = p.x;
  m.y = p.y;
  if (m.use_f1) m.f1 = m.paper_f1(p);
  if (m.use_f2) m.f2 = m.paper_f2(p);
  try {
    return m.parser.Eval();
  } catch (const mu::Parser::exception_type& e) {
    throw Error(ExitCode::kInvalidSpacing, "spacing expression '" + expr_ + "' at (" + format_number(p.x) + ", " +
                                               format_number(p.y) + "): " + e.GetMsg());
  }
}

}  // namespace fdr::sizing
