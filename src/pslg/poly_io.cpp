// Triangle .poly/.node reader and writer: strict field counts, line-numbered errors.
#include "pslg/poly_io.hpp"
#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string_view>
#include <vector>
#include "base/error.hpp"

namespace fdr::pslg {
namespace {

constexpr std::string_view kOriginTag = "# fdrmesh-origin";

// Walks a file record by record: one record = the whitespace-separated fields of a line
// with its '#' comment removed; blank lines are skipped.
class Reader {
 public:
  explicit Reader(std::string path) : path_(std::move(path)) {
    std::error_code ec;
    if (std::filesystem::is_directory(path_, ec))
      throw Error(ExitCode::kInputUnreadable, path_ + ": is a directory, not a file");
    errno = 0;
    std::ifstream in(path_, std::ios::binary);
    if (!in) throw Error(ExitCode::kInputUnreadable, path_ + ": cannot open file: " + std::strerror(errno));
    // Read straight into a buffer of the file's size (a copy through a string stream grows it
    // step by step and copies it once more); then whatever a stream without a size still has.
    in.seekg(0, std::ios::end);
    const std::streamoff size = in ? static_cast<std::streamoff>(in.tellg()) : -1;
    in.clear();
    in.seekg(0);
    if (size > 0) {
      text_.resize(static_cast<std::size_t>(size));
      in.read(text_.data(), size);
      text_.resize(static_cast<std::size_t>(in.gcount()));
    }
    char chunk[1 << 16];
    while (in.read(chunk, sizeof chunk) || in.gcount() > 0) text_.append(chunk, static_cast<std::size_t>(in.gcount()));
    if (in.bad()) throw Error(ExitCode::kInputUnreadable, path_ + ": read error");
  }

  // Upper bound on the records left (a record line has at least 5 bytes plus a newline): caps
  // reservations, so a header claiming billions of entries cannot allocate gigabytes (fuzz_poly_reader_1).
  std::size_t max_records_left() const { return (text_.size() - std::min(pos_, text_.size())) / 5 + 1; }

  // Advances to the next record; false at end of file.
  bool next() {
    while (pos_ < text_.size()) {
      std::size_t end = text_.find('\n', pos_);
      if (end == std::string::npos) end = text_.size();
      std::string_view line(text_.data() + pos_, end - pos_);
      pos_ = end + 1;
      ++line_;
      if (line.substr(0, kOriginTag.size()) == kOriginTag) parse_origin(line.substr(kOriginTag.size()));
      if (auto h = line.find('#'); h != std::string_view::npos) line = line.substr(0, h);
      fields_.clear();
      std::size_t i = 0;
      while (i < line.size()) {
        while (i < line.size() && is_space(line[i])) ++i;
        std::size_t j = i;
        while (j < line.size() && !is_space(line[j])) ++j;
        if (j > i) fields_.push_back(line.substr(i, j - i));
        i = j;
      }
      if (!fields_.empty()) return true;
    }
    fields_.clear();
    return false;
  }

  // Next record, which must exist.
  void need(const std::string& what) {
    if (!next()) fail("file ends early: expected " + what);
  }

  std::size_t size() const { return fields_.size(); }
  int line() const { return line_; }
  const std::string& path() const { return path_; }
  bool has_origin() const { return has_origin_; }
  Point2 origin() const { return origin_; }

  [[noreturn]] void fail(const std::string& what) const {
    throw Error(ExitCode::kInputMalformed, path_ + ":" + std::to_string(line_) + ": " + what);
  }

  void expect_fields(std::size_t lo, std::size_t hi, const std::string& what) const {
    if (fields_.size() < lo || fields_.size() > hi) {
      const std::string want = lo == hi ? std::to_string(lo) : std::to_string(lo) + " to " + std::to_string(hi);
      fail(std::string(fields_.size() > hi ? "too many" : "too few") + " fields in " + what + ": expected " +
           want + ", found " + std::to_string(fields_.size()));
    }
  }

  double number(std::size_t k, const char* what) const {
    std::string_view f = fields_[k];
    if (!f.empty() && f.front() == '+') f.remove_prefix(1);
    double v = 0;
    auto [p, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
    if (ec == std::errc::result_out_of_range) fail(std::string(what) + " '" + std::string(fields_[k]) + "' is out of range");
    if (ec != std::errc() || p != f.data() + f.size())
      fail(std::string(what) + " '" + std::string(fields_[k]) + "' is not a number");
    if (!std::isfinite(v)) fail(std::string(what) + " '" + std::string(fields_[k]) + "' is not finite");
    return v;
  }

  long long integer(std::size_t k, const char* what) const {
    std::string_view f = fields_[k];
    if (!f.empty() && f.front() == '+') f.remove_prefix(1);
    long long v = 0;
    auto [p, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
    if (ec != std::errc() || p != f.data() + f.size())
      fail(std::string(what) + " '" + std::string(fields_[k]) + "' is not an integer");
    return v;
  }

  long long count(std::size_t k, const char* what, long long max) const {
    const long long v = integer(k, what);
    if (v < 0 || v > max) fail(std::string(what) + " " + std::to_string(v) + " is out of range 0.." + std::to_string(max));
    return v;
  }

 private:
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

  void parse_origin(std::string_view rest) {
    double v[2];
    int k = 0;
    std::size_t i = 0;
    while (k < 2 && i < rest.size()) {
      while (i < rest.size() && is_space(rest[i])) ++i;
      std::size_t j = i;
      while (j < rest.size() && !is_space(rest[j])) ++j;
      if (j == i) break;
      auto [p, ec] = std::from_chars(rest.data() + i, rest.data() + j, v[k]);
      if (ec != std::errc() || p != rest.data() + j || !std::isfinite(v[k]))
        fail("bad fdrmesh-origin comment: '" + std::string(rest) + "'");
      ++k;
      i = j;
    }
    if (k != 2) fail("bad fdrmesh-origin comment: '" + std::string(rest) + "'");
    origin_ = {v[0], v[1]};
    has_origin_ = true;
  }

  std::string path_, text_;
  std::size_t pos_ = 0;
  int line_ = 0;
  std::vector<std::string_view> fields_;
  bool has_origin_ = false;
  Point2 origin_{0, 0};
};

constexpr long long kMaxCount = static_cast<long long>(std::numeric_limits<Index>::max() - 1);

// Reads the node section (header already current) into g; returns the first index (0 or 1).
int read_nodes(Reader& r, long long n, Pslg* g) {
  long long dim = 2, nattr = 0, nmark = 0;
  if (r.size() >= 2) dim = r.integer(1, "dimension");
  if (dim != 2) r.fail("dimension must be 2, found " + std::to_string(dim));
  if (r.size() >= 3) nattr = r.count(2, "number of vertex attributes", 1000000);
  if (r.size() >= 4) nmark = r.count(3, "number of vertex boundary markers", 1);
  const std::size_t want = 3 + static_cast<std::size_t>(nattr + nmark);
  int base = 0;
  const std::size_t cap = std::min(static_cast<std::size_t>(n), r.max_records_left());
  g->points.reserve(cap);
  if (nmark) g->point_markers.reserve(cap);
  for (long long i = 0; i < n; ++i) {
    r.need(std::to_string(n) + " vertices, found " + std::to_string(i));
    r.expect_fields(want, want, "vertex line (id x y" + std::string(nattr ? " attributes" : "") +
                                    std::string(nmark ? " marker" : "") + ")");
    const long long id = r.integer(0, "vertex id");
    if (i == 0) {
      if (id != 0 && id != 1) r.fail("first vertex id must be 0 or 1, found " + std::to_string(id));
      base = static_cast<int>(id);
    } else if (id != base + i) {
      r.fail("vertex ids must be consecutive: expected " + std::to_string(base + i) + ", found " + std::to_string(id));
    }
    const double x = r.number(1, "x coordinate"), y = r.number(2, "y coordinate");
    for (long long a = 0; a < nattr; ++a) r.number(3 + static_cast<std::size_t>(a), "vertex attribute");
    g->points.push_back({x, y});
    if (nmark) {
      const long long m = r.integer(want - 1, "vertex marker");
      if (m < std::numeric_limits<std::int32_t>::min() || m > std::numeric_limits<std::int32_t>::max())
        r.fail("vertex marker " + std::to_string(m) + " does not fit in 32 bits");
      g->point_markers.push_back(static_cast<std::int32_t>(m));
    }
  }
  return base;
}

void apply_origin(const Reader& r, Pslg* g) {
  if (r.has_origin()) g->origin = r.origin();
}

std::string sibling_node(const std::string& poly) {
  const auto dot = poly.find_last_of('.');
  const auto slash = poly.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return poly + ".node";
  return poly.substr(0, dot) + ".node";
}

// Reads a whole .node file into g; returns its first index (0 or 1).
int read_node_into(const std::string& path, Pslg* g) {
  Reader r(path);
  r.need("the node header '<#vertices> <dimension> <#attributes> <#boundary markers>'");
  r.expect_fields(1, 4, "node header");
  const long long n = r.count(0, "number of vertices", kMaxCount);
  const int base = read_nodes(r, n, g);
  if (r.next()) r.fail("unexpected content after " + std::to_string(n) + " vertices");
  apply_origin(r, g);
  return base;
}

}  // namespace

Pslg read_node(const std::string& path) {
  Pslg g;
  read_node_into(path, &g);
  return g;
}

Pslg read_poly(const std::string& path) {
  Reader r(path);
  Pslg g;
  r.need("the vertex header '<#vertices> <dimension> <#attributes> <#boundary markers>'");
  r.expect_fields(1, 4, "vertex header");
  const long long nv = r.count(0, "number of vertices", kMaxCount);
  int base = 0;
  if (nv > 0) {
    base = read_nodes(r, nv, &g);
  } else {
    // Triangle convention: a .poly with no vertices takes them from the .node file of the same name.
    if (r.size() >= 2 && r.integer(1, "dimension") != 2) r.fail("dimension must be 2");
    base = read_node_into(sibling_node(path), &g);
  }
  const long long n = static_cast<long long>(g.points.size());

  r.need("the segment header '<#segments> <#boundary markers>'");
  r.expect_fields(1, 2, "segment header");
  const long long ns = r.count(0, "number of segments", kMaxCount);
  long long smark = 0;
  if (r.size() >= 2) smark = r.count(1, "number of segment boundary markers", 1);
  g.segments.reserve(std::min(static_cast<std::size_t>(ns), r.max_records_left()));
  for (long long i = 0; i < ns; ++i) {
    r.need(std::to_string(ns) + " segments, found " + std::to_string(i));
    const std::size_t want = 3 + static_cast<std::size_t>(smark);
    r.expect_fields(want, want, smark ? "segment line (id a b marker)" : "segment line (id a b)");
    r.integer(0, "segment id");
    Segment s;
    for (int e = 0; e < 2; ++e) {
      const long long v = r.integer(1 + static_cast<std::size_t>(e), "segment endpoint");
      if (v < base || v >= base + n)
        r.fail("segment endpoint " + std::to_string(v) + " is out of range " + std::to_string(base) + ".." +
               std::to_string(base + n - 1));
      (e == 0 ? s.a : s.b) = static_cast<Index>(v - base);
    }
    if (smark) {
      const long long m = r.integer(3, "segment marker");
      if (m < std::numeric_limits<std::int32_t>::min() || m > std::numeric_limits<std::int32_t>::max())
        r.fail("segment marker " + std::to_string(m) + " does not fit in 32 bits");
      s.marker = static_cast<std::int32_t>(m);
    }
    g.segments.push_back(s);
  }

  r.need("the hole header '<#holes>'");
  r.expect_fields(1, 1, "hole header");
  const long long nh = r.count(0, "number of holes", kMaxCount);
  for (long long i = 0; i < nh; ++i) {
    r.need(std::to_string(nh) + " holes, found " + std::to_string(i));
    r.expect_fields(3, 3, "hole line (id x y)");
    r.integer(0, "hole id");
    g.holes.push_back({r.number(1, "hole x"), r.number(2, "hole y")});
  }

  if (r.next()) {  // the regions section is optional
    r.expect_fields(1, 1, "region header");
    const long long nr = r.count(0, "number of regions", kMaxCount);
    for (long long i = 0; i < nr; ++i) {
      r.need(std::to_string(nr) + " regions, found " + std::to_string(i));
      r.expect_fields(5, 5, "region line (id x y attribute maxarea)");
      r.integer(0, "region id");
      Region reg;
      reg.seed = {r.number(1, "region x"), r.number(2, "region y")};
      reg.attribute = r.number(3, "region attribute");
      reg.max_area = r.number(4, "region maximum area");
      g.regions.push_back(reg);
    }
    if (r.next()) r.fail("unexpected content after the regions section");
  }
  apply_origin(r, &g);
  return g;
}

void write_poly(const Pslg& g, const std::string& path) {
  const std::string tmp = path + ".tmp";
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) throw Error(ExitCode::kOutputError, path + ": cannot create '" + tmp + "': " + std::strerror(errno));
  const bool pm = !g.point_markers.empty() && g.point_markers.size() == g.points.size();
  std::fprintf(f, "# fdrmesh PSLG (Triangle .poly, 0-based)\n");
  if (g.origin.x != 0 || g.origin.y != 0)
    std::fprintf(f, "%s %.17g %.17g\n", kOriginTag.data(), g.origin.x, g.origin.y);
  std::fprintf(f, "%zu 2 0 %d\n", g.points.size(), pm ? 1 : 0);
  for (std::size_t i = 0; i < g.points.size(); ++i) {
    std::fprintf(f, "%zu %.17g %.17g", i, g.points[i].x, g.points[i].y);
    if (pm) std::fprintf(f, " %d", static_cast<int>(g.point_markers[i]));
    std::fputc('\n', f);
  }
  std::fprintf(f, "%zu 1\n", g.segments.size());
  for (std::size_t i = 0; i < g.segments.size(); ++i)
    std::fprintf(f, "%zu %llu %llu %d\n", i, static_cast<unsigned long long>(g.segments[i].a),
                 static_cast<unsigned long long>(g.segments[i].b), static_cast<int>(g.segments[i].marker));
  std::fprintf(f, "%zu\n", g.holes.size());
  for (std::size_t i = 0; i < g.holes.size(); ++i)
    std::fprintf(f, "%zu %.17g %.17g\n", i, g.holes[i].x, g.holes[i].y);
  if (!g.regions.empty()) {
    std::fprintf(f, "%zu\n", g.regions.size());
    for (std::size_t i = 0; i < g.regions.size(); ++i)
      std::fprintf(f, "%zu %.17g %.17g %.17g %.17g\n", i, g.regions[i].seed.x, g.regions[i].seed.y,
                   g.regions[i].attribute, g.regions[i].max_area);
  }
  const bool write_ok = !std::ferror(f);
  const bool close_ok = std::fclose(f) == 0;
  if (!write_ok || !close_ok) {
    std::remove(tmp.c_str());
    throw Error(ExitCode::kOutputError, path + ": write error on '" + tmp + "'");
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    std::remove(tmp.c_str());
    throw Error(ExitCode::kOutputError, path + ": cannot rename '" + tmp + "': " + why);
  }
}

}  // namespace fdr::pslg
