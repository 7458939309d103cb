// VTU writer: XML UnstructuredGrid with raw appended or inline base64 arrays, streamed in chunks so
// that no array is copied whole.
#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <functional>
#include <string>
#include <vector>
#include "tetio/write_parts.hpp"

namespace fdr::tetio {
namespace {

static_assert(std::endian::native == std::endian::little, "the VTU writer emits the host's bytes as LittleEndian");

constexpr std::size_t kChunk = 1 << 14;  // values converted per write

// Bytes to the file, either as they are or base64-encoded (three bytes to four characters, the
// remainder carried to the next call so that one array is one continuous base64 stream).
class Sink {
 public:
  Sink(OutFile& out, bool base64) : out_(out), base64_(base64) {}
  void put(const void* data, std::size_t n) {
    if (!base64_) return out_.write_raw(data, n);
    const auto* p = static_cast<const unsigned char*>(data);
    std::string text;
    text.reserve((n + carry_len_) / 3 * 4 + 4);
    std::size_t i = 0;
    while (carry_len_ > 0 && carry_len_ < 3 && i < n) carry_[carry_len_++] = p[i++];
    if (carry_len_ == 3) {
      encode3(carry_.data(), text);
      carry_len_ = 0;
    }
    for (; i + 3 <= n; i += 3) encode3(p + i, text);
    for (; i < n; ++i) carry_[carry_len_++] = p[i];
    out_.write(text);
  }
  // Ends a base64 stream with its padding.
  void finish() {
    if (!base64_ || carry_len_ == 0) return;
    static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    const unsigned v = (carry_[0] << 16) | (carry_len_ > 1 ? carry_[1] << 8 : 0);
    char q[4] = {kAlphabet[(v >> 18) & 63], kAlphabet[(v >> 12) & 63], carry_len_ > 1 ? kAlphabet[(v >> 6) & 63] : '=', '='};
    out_.write(std::string_view(q, 4));
    carry_len_ = 0;
  }

 private:
  static void encode3(const unsigned char* b, std::string& text) {
    static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    const unsigned v = (b[0] << 16) | (b[1] << 8) | b[2];
    text.push_back(kAlphabet[(v >> 18) & 63]);
    text.push_back(kAlphabet[(v >> 12) & 63]);
    text.push_back(kAlphabet[(v >> 6) & 63]);
    text.push_back(kAlphabet[v & 63]);
  }
  OutFile& out_;
  bool base64_;
  std::array<unsigned char, 3> carry_{};
  std::size_t carry_len_ = 0;
};

// One DataArray: its XML attributes, its size in bytes, and how to produce its values.
struct Array {
  std::string attrs;
  std::uint64_t bytes = 0;
  std::function<void(Sink&)> emit;
};

// n values of type T, value i from get(i), in chunks.
template <class T, class Get>
Array make_array(std::string attrs, std::size_t n, Get get) {
  Array a;
  a.attrs = std::move(attrs);
  a.bytes = n * sizeof(T);
  a.emit = [n, get](Sink& sink) {
    std::vector<T> buf;
    buf.reserve(std::min(n, kChunk));
    for (std::size_t i = 0; i < n;) {
      buf.clear();
      for (std::size_t j = 0; j < kChunk && i < n; ++j, ++i) buf.push_back(get(i));
      sink.put(buf.data(), buf.size() * sizeof(T));
    }
  };
  return a;
}

std::string xml_escape(const std::string& s) {
  std::string r;
  for (char c : s) {
    switch (c) {
      case '&': r += "&amp;"; break;
      case '<': r += "&lt;"; break;
      case '>': r += "&gt;"; break;
      case '"': r += "&quot;"; break;
      default: r += c;
    }
  }
  return r;
}

// The UInt64 byte count that precedes each array's data, then the data.
void emit_with_header(const Array& a, Sink& sink) {
  const std::uint64_t header = a.bytes;
  sink.put(&header, sizeof header);
  a.emit(sink);
  sink.finish();
}

struct Layout {
  std::vector<Array> points, cells, cell_data;
};

Layout layout(const tet::TetMesh& m) {
  Layout l;
  const auto& pts = m.points;
  l.points.push_back(make_array<double>(R"(type="Float64" Name="Points" NumberOfComponents="3")", 3 * pts.size(),
                                        [&pts](std::size_t i) {
                                          const Point3& p = pts[i / 3];
                                          return i % 3 == 0 ? p.x : i % 3 == 1 ? p.y : p.z;
                                        }));
  const auto& tets = m.tets;
  l.cells.push_back(make_array<std::int64_t>(R"(type="Int64" Name="connectivity")", 4 * tets.size(),
                                             [&tets](std::size_t i) { return static_cast<std::int64_t>(tets[i / 4][i % 4]); }));
  l.cells.push_back(make_array<std::int64_t>(R"(type="Int64" Name="offsets")", tets.size(),
                                             [](std::size_t i) { return static_cast<std::int64_t>(4 * (i + 1)); }));
  l.cells.push_back(make_array<std::uint8_t>(R"(type="UInt8" Name="types")", tets.size(), [](std::size_t) { return std::uint8_t{10}; }));
  const auto& mat = m.tet_material;
  l.cell_data.push_back(make_array<std::int32_t>(R"(type="Int32" Name="material")", mat.size(), [&mat](std::size_t i) { return mat[i]; }));
  for (const auto& [name, values] : m.cell_fields) {
    const auto& v = values;
    l.cell_data.push_back(make_array<double>(R"(type="Float64" Name=")" + xml_escape(name) + "\"", v.size(),
                                             [&v](std::size_t i) { return v[i]; }));
  }
  return l;
}

// The DataArray elements of one section: self-closing with an offset (appended) or holding base64.
void write_section(OutFile& out, Sink& sink, const std::vector<Array>& arrays, bool appended, std::uint64_t& offset,
                   const char* indent) {
  for (const Array& a : arrays) {
    out.str(indent).str("<DataArray ").str(a.attrs);
    if (appended) {
      out.str(R"( format="appended" offset=")").num(static_cast<std::int64_t>(offset)).str("\"/>\n");
      offset += sizeof(std::uint64_t) + a.bytes;
    } else {
      out.str(R"( format="binary">)");
      emit_with_header(a, sink);
      out.str("</DataArray>\n");
    }
  }
}

}  // namespace

Written prepare_vtu(const std::string& path, const tet::TetMesh& mesh, VtuEncoding encoding) {
  check_mesh_arrays(mesh);
  const bool appended = encoding == VtuEncoding::kAppendedRaw;
  const Layout l = layout(mesh);
  Written parts;
  OutFile& out = *parts.emplace_back(std::make_unique<OutFile>(path));
  Sink sink(out, !appended);
  std::uint64_t offset = 0;
  out.str("<?xml version=\"1.0\"?>\n");
  out.str(R"(<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt64">)").nl();
  out.str("  <UnstructuredGrid>\n    <Piece NumberOfPoints=\"").num(static_cast<std::int64_t>(mesh.points.size()));
  out.str("\" NumberOfCells=\"").num(static_cast<std::int64_t>(mesh.tets.size())).str("\">\n");
  out.str("      <Points>\n");
  write_section(out, sink, l.points, appended, offset, "        ");
  out.str("      </Points>\n      <Cells>\n");
  write_section(out, sink, l.cells, appended, offset, "        ");
  out.str("      </Cells>\n      <CellData Scalars=\"material\">\n");
  write_section(out, sink, l.cell_data, appended, offset, "        ");
  out.str("      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n");
  if (appended) {
    out.str("  <AppendedData encoding=\"raw\">\n   _");
    for (const auto* section : {&l.points, &l.cells, &l.cell_data}) {
      for (const Array& a : *section) emit_with_header(a, sink);
    }
    out.str("\n  </AppendedData>\n");
  }
  out.str("</VTKFile>\n");
  return parts;
}

void write_vtu(const std::string& path, const tet::TetMesh& mesh, VtuEncoding encoding) {
  Written parts = prepare_vtu(path, mesh, encoding);
  commit_written(parts);
}

}  // namespace fdr::tetio
