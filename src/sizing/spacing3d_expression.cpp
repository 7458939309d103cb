// ExpressionField3: muparser evaluators in x, y, z, pooled so that threads never share one.
#include "sizing/spacing3d_expression.hpp"

#include <muParser.h>

#include <cctype>

#include "base/error.hpp"
#include "sizing/fields.hpp"

namespace fdr::sizing {

struct ExpressionField3::Evaluator {
  mu::Parser parser;
  double x = 0, y = 0, z = 0;
};

namespace {

// muparser messages may end in " at position N" (0-based); the message names our own 1-based one.
std::string strip_position(std::string msg) {
  const std::size_t p = msg.rfind(" at position ");
  if (p == std::string::npos) return msg;
  msg.erase(p);
  const std::string found = " found";
  if (msg.size() >= found.size() && msg.compare(msg.size() - found.size(), found.size(), found) == 0)
    msg.erase(msg.size() - found.size());
  return msg;
}

[[noreturn]] void throw_parse_error(const std::string& expr, const std::string& msg, std::size_t pos0) {
  throw Error(ExitCode::kUsage, "spacing expression '" + expr + "': " + msg + " at position " +
                                    std::to_string(std::min(pos0, expr.size()) + 1));
}

std::unique_ptr<ExpressionField3::Evaluator> parse(const std::string& expr) {
  auto e = std::make_unique<ExpressionField3::Evaluator>();
  try {
    e->parser.DefineVar("x", &e->x);
    e->parser.DefineVar("y", &e->y);
    e->parser.DefineVar("z", &e->z);
    e->parser.SetExpr(expr);
    e->parser.Eval();  // muparser parses lazily: force syntax errors out at construction
  } catch (const mu::Parser::exception_type& ex) {
    throw_parse_error(expr, strip_position(ex.GetMsg()), static_cast<std::size_t>(ex.GetPos()));
  }
  if (e->parser.GetNumResults() != 1) {
    int depth = 0;
    std::size_t at = 0;
    for (std::size_t k = 0; k < expr.size(); ++k) {
      if (expr[k] == '(') ++depth;
      if (expr[k] == ')') --depth;
      if (expr[k] == ',' && depth == 0) {
        at = k;
        break;
      }
    }
    throw_parse_error(expr, "several comma-separated results, expected one", at);
  }
  return e;
}

}  // namespace

ExpressionField3::ExpressionField3(const std::string& expr) : expr_(expr) { idle_.push_back(parse(expr_)); }

ExpressionField3::~ExpressionField3() = default;

double ExpressionField3::operator()(Point3 p) const {
  std::unique_ptr<Evaluator> e;
  {
    std::lock_guard<std::mutex> lock(pool_mutex_);
    if (!idle_.empty()) {
      e = std::move(idle_.back());
      idle_.pop_back();
    }
  }
  if (!e) e = parse(expr_);
  e->x = p.x;
  e->y = p.y;
  e->z = p.z;
  double v;
  try {
    v = e->parser.Eval();
  } catch (const mu::Parser::exception_type& ex) {
    throw Error(ExitCode::kInvalidSpacing, "spacing expression '" + expr_ + "' at (" + format_number(p.x) + ", " +
                                               format_number(p.y) + ", " + format_number(p.z) + "): " + ex.GetMsg());
  }
  std::lock_guard<std::mutex> lock(pool_mutex_);
  idle_.push_back(std::move(e));
  return v;
}

}  // namespace fdr::sizing
