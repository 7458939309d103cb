// PLY (ascii, binary_little_endian, binary_big_endian): the "vertex" element's x, y, z and the
// "face" element's vertex_indices (or vertex_index) list; an integer face property "marker" is
// taken as the facet's boundary marker. Other elements and properties are read past.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <optional>
#include "tetio/surface.hpp"
#include "tetio/text_lines.hpp"

namespace fdr::tetio {
namespace {

enum class Type { kI8, kU8, kI16, kU16, kI32, kU32, kF32, kF64 };

std::optional<Type> type_from(std::string_view s) {
  if (s == "char" || s == "int8") return Type::kI8;
  if (s == "uchar" || s == "uint8") return Type::kU8;
  if (s == "short" || s == "int16") return Type::kI16;
  if (s == "ushort" || s == "uint16") return Type::kU16;
  if (s == "int" || s == "int32") return Type::kI32;
  if (s == "uint" || s == "uint32") return Type::kU32;
  if (s == "float" || s == "float32") return Type::kF32;
  if (s == "double" || s == "float64") return Type::kF64;
  return std::nullopt;
}
std::size_t type_size(Type t) {
  switch (t) {
    case Type::kI8: case Type::kU8: return 1;
    case Type::kI16: case Type::kU16: return 2;
    case Type::kI32: case Type::kU32: case Type::kF32: return 4;
    case Type::kF64: return 8;
  }
  return 1;
}

struct Property {
  std::string name;
  Type type = Type::kF32;
  bool list = false;
  Type count_type = Type::kU8;
};
struct Element {
  std::string name;
  std::int64_t count = 0;
  std::vector<Property> props;
};
enum class Format { kAscii, kLittle, kBig };
struct Header {
  Format format = Format::kAscii;
  std::vector<Element> elements;
  std::size_t body = 0;  // byte offset of the data
  std::size_t lines = 0;  // header lines (ASCII data line numbers follow)
};

Header parse_header(const std::string& path, const std::string& bytes) {
  Header h;
  std::size_t pos = 0;
  bool format_seen = false;
  for (;;) {
    const std::size_t end = bytes.find('\n', pos);
    if (end == std::string::npos) fail_malformed(path, h.lines + 1, "the header has no end_header line");
    TextLines row(path, bytes.substr(pos, end - pos));
    pos = end + 1;
    ++h.lines;
    if (!row.next()) continue;
    const std::string_view w = row.token(0);
    auto fail = [&](const std::string& what) { fail_malformed(path, h.lines, what); };
    if (h.lines == 1) {
      if (w != "ply") fail("not a PLY file: it does not begin with 'ply'");
    } else if (w == "format") {
      const std::string_view f = row.size() > 1 ? row.token(1) : "";
      if (f == "ascii") h.format = Format::kAscii;
      else if (f == "binary_little_endian") h.format = Format::kLittle;
      else if (f == "binary_big_endian") h.format = Format::kBig;
      else fail("unknown PLY format '" + shown(f) + "'");
      format_seen = true;
    } else if (w == "element") {
      if (row.size() < 3) fail("expected 'element NAME COUNT'");
      std::int64_t n = 0;
      if (!parse_integer(row.token(2), n) || n < 0) fail("bad element count '" + shown(row.token(2)) + "'");
      h.elements.push_back({std::string(row.token(1)), n, {}});
    } else if (w == "property") {
      if (h.elements.empty()) fail("a property before any element");
      Property p;
      if (row.size() >= 5 && row.token(1) == "list") {
        auto c = type_from(row.token(2)), t = type_from(row.token(3));
        if (!c || !t) fail("unknown list property type");
        p = {std::string(row.token(4)), *t, true, *c};
      } else if (row.size() >= 3) {
        auto t = type_from(row.token(1));
        if (!t) fail("unknown property type '" + shown(row.token(1)) + "'");
        p = {std::string(row.token(2)), *t, false, Type::kU8};
      } else {
        fail("expected 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME'");
      }
      h.elements.back().props.push_back(p);
    } else if (w == "end_header") {
      if (!format_seen) fail("the header has no format line");
      h.body = pos;
      return h;
    } else if (w != "comment" && w != "obj_info") {
      fail("unknown header line '" + shown(w) + "'");
    }
  }
}

// The data of the file, value by value: ASCII tokens or binary numbers of either byte order.
class Values {
 public:
  Values(const std::string& path, const std::string& bytes, const Header& h)
      : path_(path), p_(bytes.data() + h.body), end_(bytes.data() + bytes.size()), format_(h.format),
        line_(h.lines + 1) {}

  double next(Type t) {
    if (format_ == Format::kAscii) return next_text();
    const std::size_t n = type_size(t);
    if (static_cast<std::size_t>(end_ - p_) < n) fail_malformed(path_, 0, "the binary data ends early");
    std::array<unsigned char, 8> b{};
    std::memcpy(b.data(), p_, n);
    p_ += n;
    if ((format_ == Format::kBig) != (std::endian::native == std::endian::big)) std::reverse(b.begin(), b.begin() + n);
    return decode(t, b);
  }
  std::int64_t next_integer(Type t, const std::string& what) {
    const double v = next(t);
    if (v != std::floor(v) || std::abs(v) > 9.0e15) fail(what + " is not an integer");
    return static_cast<std::int64_t>(v);
  }
  [[noreturn]] void fail(const std::string& what) const {
    fail_malformed(path_, format_ == Format::kAscii ? line_ : 0, what);
  }
  // Binary data cannot hold fewer bytes than the elements' fixed-size properties need.
  std::size_t remaining() const { return static_cast<std::size_t>(end_ - p_); }
  bool binary() const { return format_ != Format::kAscii; }

 private:
  static double decode(Type t, const std::array<unsigned char, 8>& b) {
    switch (t) {
      case Type::kI8: return static_cast<std::int8_t>(b[0]);
      case Type::kU8: return b[0];
      case Type::kI16: return as<std::int16_t>(b);
      case Type::kU16: return as<std::uint16_t>(b);
      case Type::kI32: return as<std::int32_t>(b);
      case Type::kU32: return as<std::uint32_t>(b);
      case Type::kF32: return as<float>(b);
      case Type::kF64: return as<double>(b);
    }
    return 0;
  }
  template <class T>
  static T as(const std::array<unsigned char, 8>& b) {
    T v;
    std::memcpy(&v, b.data(), sizeof v);
    return v;
  }
  double next_text() {
    while (p_ < end_ && (*p_ == ' ' || *p_ == '\t' || *p_ == '\r' || *p_ == '\n')) {
      if (*p_ == '\n') ++line_;
      ++p_;
    }
    const char* s = p_;
    while (p_ < end_ && !(*p_ == ' ' || *p_ == '\t' || *p_ == '\r' || *p_ == '\n')) ++p_;
    if (s == p_) fail_malformed(path_, line_, "unexpected end of file in the data");
    double v = 0;
    if (!parse_real(std::string_view(s, static_cast<std::size_t>(p_ - s)), v)) {
      fail("'" + shown(std::string_view(s, static_cast<std::size_t>(p_ - s))) + "' is not a finite number");
    }
    return v;
  }
  const std::string& path_;
  const char* p_;
  const char* end_;
  Format format_;
  std::size_t line_;
};

std::size_t min_row_bytes(const Element& e) {
  std::size_t n = 0;
  for (const auto& p : e.props) n += type_size(p.list ? p.count_type : p.type);
  return n;
}

void read_element(Values& in, const Element& e, Surface& s) {
  const bool vertex = e.name == "vertex", face = e.name == "face";
  if (in.binary() && e.count > 0 && static_cast<std::size_t>(e.count) > in.remaining() / std::max<std::size_t>(1, min_row_bytes(e))) {
    in.fail("the binary data is too short for " + std::to_string(e.count) + " " + e.name + " elements");
  }
  for (std::int64_t i = 0; i < e.count; ++i) {
    Point3 p;
    std::vector<VertexId> corners;
    std::int32_t marker = 0;
    for (const auto& prop : e.props) {
      if (prop.list) {
        const std::int64_t k = in.next_integer(prop.count_type, "a list length");
        if (k < 0) in.fail("negative list length");
        const bool is_corners = face && (prop.name == "vertex_indices" || prop.name == "vertex_index");
        for (std::int64_t c = 0; c < k; ++c) {
          if (!is_corners) {
            in.next(prop.type);
            continue;
          }
          const std::int64_t v = in.next_integer(prop.type, "a vertex index");
          if (v < 0 || v >= static_cast<std::int64_t>(s.points.size())) {
            in.fail("face " + std::to_string(i) + ": vertex " + std::to_string(v) + " out of range (0.." +
                    std::to_string(static_cast<std::int64_t>(s.points.size()) - 1) + ")");
          }
          corners.push_back(static_cast<VertexId>(v));
        }
        continue;
      }
      const double v = in.next(prop.type);
      if (vertex && (prop.name == "x" || prop.name == "y" || prop.name == "z")) {
        if (!std::isfinite(v)) in.fail("vertex " + std::to_string(i) + ": coordinate " + prop.name + " is not finite");
        (prop.name == "x" ? p.x : prop.name == "y" ? p.y : p.z) = v;
      } else if (face && prop.name == "marker") {
        marker = static_cast<std::int32_t>(v);
      }
    }
    if (vertex) s.points.push_back(p);
    if (face) {
      if (corners.size() < 3) in.fail("face " + std::to_string(i) + " has " + std::to_string(corners.size()) + " corners (at least 3)");
      s.faces.push_back(std::move(corners));
      s.face_marker.push_back(marker);
    }
  }
}

}  // namespace

plc::Plc read_ply(const std::string& path) {
  const std::string bytes = read_file_bytes(path);
  const Header h = parse_header(path, bytes);
  bool has_xyz = false, has_faces = false;
  for (const auto& e : h.elements) {
    if (e.name == "vertex") {
      int n = 0;
      for (const auto& p : e.props) n += !p.list && (p.name == "x" || p.name == "y" || p.name == "z");
      has_xyz = n == 3;
    }
    if (e.name == "face") {
      for (const auto& p : e.props) has_faces |= p.list && (p.name == "vertex_indices" || p.name == "vertex_index");
    }
  }
  if (!has_xyz) fail_malformed(path, 0, "no 'vertex' element with x, y, z properties");
  if (!has_faces) fail_malformed(path, 0, "no 'face' element with a vertex_indices list");
  Values in(path, bytes, h);
  Surface s;
  for (const auto& e : h.elements) read_element(in, e, s);
  return surface_to_plc(std::move(s), path);
}

}  // namespace fdr::tetio
