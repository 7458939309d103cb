#include "adcirc_grid.hpp"

#include <algorithm>
#include <charconv>
#include <climits>
#include <cstdio>
#include <fstream>
#include <string_view>
#include <unordered_map>

namespace fdr_mdal {

namespace {

std::string lower(std::string s) {
  for (char& c : s)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return s;
}

std::string file_name(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return lower(slash == std::string::npos ? path : path.substr(slash + 1));
}

std::string extension(const std::string& path) {
  const std::string name = file_name(path);
  const std::size_t dot = name.find_last_of('.');
  return dot == std::string::npos ? std::string() : name.substr(dot);
}

// Thrown inside the reader only; read_grid turns it into its message.
struct Bad {
  std::string why;
};

// Whitespace/comma separated tokens of the lines of a text held in memory (ADCIRC tools write
// either separator).
class Lines {
 public:
  explicit Lines(std::string_view text) : text_(text) {}

  // The next line, whatever it holds; false at the end of the text.
  bool next() {
    if (pos_ >= text_.size()) return false;
    std::size_t end = text_.find('\n', pos_);
    if (end == std::string_view::npos) end = text_.size();
    std::string_view line = text_.substr(pos_, end - pos_);
    pos_ = end + 1;
    ++lineno_;
    tokens_.clear();
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && blank(line[i])) ++i;
      std::size_t j = i;
      while (j < line.size() && !blank(line[j])) ++j;
      if (j > i) tokens_.push_back(line.substr(i, j - i));
      i = j;
    }
    return true;
  }
  // The next line holding a token; false at the end of the text.
  bool next_data() {
    while (next())
      if (!tokens_.empty()) return true;
    return false;
  }
  void require(const char* what) {
    if (!next_data()) fail(std::string("the file ends where ") + what + " was expected");
  }
  [[noreturn]] void fail(const std::string& why) const { throw Bad{std::to_string(lineno_) + ": " + why}; }

  std::size_t size() const { return tokens_.size(); }
  std::string_view tok(std::size_t i) const {
    if (i >= tokens_.size()) fail("expected at least " + std::to_string(i + 1) + " values");
    return tokens_[i];
  }
  long long integer(std::size_t i) const {
    long long v = 0;
    if (!parse_integer(tok(i), v)) fail(quoted(tok(i)) + " is not an integer");
    return v;
  }
  double real(std::size_t i) const {
    double v = 0;
    if (!parse_real(tok(i), v)) fail(quoted(tok(i)) + " is not a number");
    return v;
  }
  static std::string quoted(std::string_view t) {
    std::string s;
    s.reserve(t.size() + 2);
    s.push_back('\'');
    s.append(t);
    s.push_back('\'');
    return s;
  }

  static bool parse_integer(std::string_view t, long long& v) {
    if (!t.empty() && t[0] == '+') t.remove_prefix(1);
    auto r = std::from_chars(t.data(), t.data() + t.size(), v);
    return r.ec == std::errc() && r.ptr == t.data() + t.size();
  }
  static bool parse_real(std::string_view t, double& v) {
    if (!t.empty() && t[0] == '+') t.remove_prefix(1);
    auto r = std::from_chars(t.data(), t.data() + t.size(), v);
    if (r.ec == std::errc() && r.ptr == t.data() + t.size()) return true;
    // Fortran writes exponents as 1.5D+02.
    std::string s(t);
    for (char& c : s)
      if (c == 'D' || c == 'd') c = 'e';
    r = std::from_chars(s.data(), s.data() + s.size(), v);
    return r.ec == std::errc() && r.ptr == s.data() + s.size();
  }

 private:
  static bool blank(char c) { return c == ' ' || c == '\t' || c == ',' || c == '\r'; }
  std::string_view text_;
  std::size_t pos_ = 0;
  std::size_t lineno_ = 0;
  std::vector<std::string_view> tokens_;
};

// File node ids to vertex indices: the identity shift when the file numbers nodes 1..NP in order,
// a hash map otherwise.
class NodeIds {
 public:
  void add(const Lines& in, long long id, int index) {
    if (sequential_ && id == index + 1) return;
    if (sequential_) {
      sequential_ = false;
      for (int i = 0; i < index; ++i) map_.emplace(i + 1, i);
    }
    if (!map_.emplace(id, index).second) in.fail("node id " + std::to_string(id) + " defined twice");
  }
  void set_count(int n) { count_ = n; }
  int at(const Lines& in, long long id) const {
    if (sequential_) {
      if (id >= 1 && id <= count_) return static_cast<int>(id - 1);
    } else if (auto it = map_.find(id); it != map_.end()) {
      return it->second;
    }
    in.fail("node id " + std::to_string(id) + " is not defined");
  }

 private:
  bool sequential_ = true;
  int count_ = 0;
  std::unordered_map<long long, int> map_;
};

int count_of(const Lines& in, long long v, const char* what) {
  if (v < 0 || v > INT_MAX) in.fail(std::string(what) + " " + std::to_string(v) + " is out of range");
  return static_cast<int>(v);
}

void read_nodes(Lines& in, int np, NodeIds& ids, Grid& g) {
  for (int i = 0; i < np; ++i) {
    in.require("a node line 'JN X Y DP'");
    ids.add(in, in.integer(0), i);
    const double x = in.real(1), y = in.real(2), dp = in.real(3);
    g.xyz.insert(g.xyz.end(), {x, y, dp == 0 ? 0.0 : -dp});
    g.depth.push_back(dp);
    if (i == 0) {
      g.xmin = g.xmax = x;
      g.ymin = g.ymax = y;
    }
    g.xmin = std::min(g.xmin, x);
    g.xmax = std::max(g.xmax, x);
    g.ymin = std::min(g.ymin, y);
    g.ymax = std::max(g.ymax, y);
  }
  ids.set_count(np);
}

void read_elements(Lines& in, int ne, const NodeIds& ids, Grid& g) {
  for (int i = 0; i < ne; ++i) {
    in.require("an element line 'JE NV N1 .. NNV'");
    const long long nv = in.integer(1);
    if (nv != 3 && nv != 4) in.fail("element with " + std::to_string(nv) + " nodes; triangles (3) and quads (4) are valid");
    for (int k = 0; k < nv; ++k) g.face_nodes.push_back(ids.at(in, in.integer(2 + static_cast<std::size_t>(k))));
    if (g.face_nodes.size() > static_cast<std::size_t>(INT_MAX)) in.fail("too many element nodes");
    g.face_end.push_back(static_cast<int>(g.face_nodes.size()));
  }
}

// One list of boundaries, its count line being the current line: the total line, then per
// boundary its node count (first value) and one node per line (the node id first). The total must
// equal the sum of the counts, except with weirs or barriers (IBTYPE x4, x5), whose pairs ADCIRC
// counts its own way.
void read_boundary_list(Lines& in, const NodeIds& ids, const char* kind) {
  const int n = count_of(in, in.integer(0), kind);
  in.require("the total number of boundary nodes");
  const long long total = in.integer(0);
  long long sum = 0;
  bool barriers = false;
  for (int b = 0; b < n; ++b) {
    in.require("a boundary's node count");
    const long long k = count_of(in, in.integer(0), "boundary node count");
    long long type = 0;
    if (in.size() > 1 && Lines::parse_integer(in.tok(1), type) && (type % 10 == 4 || type % 10 == 5)) barriers = true;
    sum += k;
    for (long long j = 0; j < k; ++j) {
      in.require("a boundary node id");
      ids.at(in, in.integer(0));
    }
  }
  if (!barriers && sum != total)
    in.fail(std::string("the ") + kind + " hold " + std::to_string(sum) + " nodes, the file's total says " +
            std::to_string(total));
}

void read_boundaries(Lines& in, const NodeIds& ids) {
  if (!in.next_data()) return;  // a grid without boundaries (any gr3 but hgrid)
  read_boundary_list(in, ids, "open boundaries");
  if (in.next_data()) read_boundary_list(in, ids, "land boundaries");
}

std::string read_text(const std::string& path, std::string& text) {
  std::ifstream f(path, std::ios::binary | std::ios::ate);
  if (!f) return "cannot open";
  const std::streamoff size = f.tellg();
  if (size < 0) return "cannot tell its size";
  text.resize(static_cast<std::size_t>(size));
  f.seekg(0);
  if (!f.read(text.data(), size)) return "read error";
  return {};
}

}  // namespace

bool has_grid_name(const std::string& path) {
  const std::string ext = extension(path);
  return file_name(path) == "fort.14" || ext == ".14" || ext == ".grd" || ext == ".gr3" || ext == ".ll";
}

bool looks_like_grid(const std::string& path) {
  if (!has_grid_name(path)) return false;
  std::ifstream f(path, std::ios::binary);
  if (!f) return false;
  std::string head(1 << 16, '\0');
  f.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(f.gcount()));
  if (head.find('\0') != std::string::npos) return false;  // binary
  Lines in(head);
  long long ne = 0, np = 0, id = 0;
  double v = 0;
  if (!in.next() || !in.next_data() || in.size() < 2) return false;
  if (!Lines::parse_integer(in.tok(0), ne) || !Lines::parse_integer(in.tok(1), np) || ne < 0 || np < 0) return false;
  if (np == 0) return true;
  if (!in.next_data() || in.size() < 4 || !Lines::parse_integer(in.tok(0), id)) return false;
  for (std::size_t i = 1; i < 4; ++i)
    if (!Lines::parse_real(in.tok(i), v)) return false;
  return true;
}

std::string read_grid(const std::string& path, Grid& g) {
  g = Grid{};
  std::string text;
  if (std::string why = read_text(path, text); !why.empty()) return path + ": " + why;
  Lines in(text);
  try {
    if (!in.next()) in.fail("empty file, expected the grid title line");
    in.require("'NE NP'");
    const int ne = count_of(in, in.integer(0), "element count");
    const int np = count_of(in, in.integer(1), "node count");
    // Reserve no more than the text can hold: a wrong count must not exhaust memory.
    const std::size_t lines = static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')) + 1;
    g.xyz.reserve(3 * std::min<std::size_t>(static_cast<std::size_t>(np), lines));
    g.depth.reserve(std::min<std::size_t>(static_cast<std::size_t>(np), lines));
    g.face_end.reserve(std::min<std::size_t>(static_cast<std::size_t>(ne), lines));
    g.face_nodes.reserve(3 * std::min<std::size_t>(static_cast<std::size_t>(ne), lines));
    NodeIds ids;
    read_nodes(in, np, ids, g);
    read_elements(in, ne, ids, g);
    read_boundaries(in, ids);
  } catch (const Bad& b) {
    return path + ":" + b.why;
  }
  g.crs = grid_crs(path, g);
  return {};
}

std::string grid_crs(const std::string& path, const Grid& g) {
  if (extension(path) == ".ll") return "EPSG:4326";
  if (g.depth.empty()) return {};
  const bool lonlat = g.xmin >= -180 && g.xmax <= 360 && g.ymin >= -90 && g.ymax <= 90;
  return lonlat ? "EPSG:4326" : std::string();
}

}  // namespace fdr_mdal
