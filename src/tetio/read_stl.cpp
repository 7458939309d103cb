// STL: ASCII ("solid", "facet normal", "outer loop", three "vertex x y z", "endloop", "endfacet")
// or binary (80-byte header, a 32-bit little-endian count, 50 bytes per triangle). The file size
// tells them apart: some binary files also begin with "solid".
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include "tetio/surface.hpp"
#include "tetio/text_lines.hpp"

namespace fdr::tetio {
namespace {

template <class T>
T load_le(const char* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  if constexpr (std::endian::native == std::endian::big) {
    auto u = std::bit_cast<std::array<unsigned char, sizeof(T)>>(v);
    std::reverse(u.begin(), u.end());
    v = std::bit_cast<T>(u);
  }
  return v;
}

bool is_binary(const std::string& bytes) {
  if (bytes.size() < 84) return false;
  const std::uint64_t n = load_le<std::uint32_t>(bytes.data() + 80);
  return 84 + 50 * n == bytes.size();
}

Surface read_binary(const std::string& path, const std::string& bytes) {
  const std::uint32_t n = load_le<std::uint32_t>(bytes.data() + 80);
  Surface s;
  s.points.reserve(3 * static_cast<std::size_t>(n));
  s.faces.reserve(n);
  for (std::uint32_t t = 0; t < n; ++t) {
    const char* rec = bytes.data() + 84 + 50 * static_cast<std::size_t>(t);
    std::vector<VertexId> face;
    for (int k = 0; k < 3; ++k) {
      Point3 p;
      p.x = load_le<float>(rec + 12 + 12 * k);
      p.y = load_le<float>(rec + 16 + 12 * k);
      p.z = load_le<float>(rec + 20 + 12 * k);
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
        fail_malformed(path, 0, "triangle " + std::to_string(t) + ", corner " + std::to_string(k) + ": a coordinate is not finite");
      }
      face.push_back(static_cast<VertexId>(s.points.size()));
      s.points.push_back(p);
    }
    s.faces.push_back(std::move(face));
  }
  return s;
}

void expect_word(TextLines& in, std::string_view word, const std::string& what) {
  in.expect(what);
  if (in.token(0) != word) in.fail("expected '" + std::string(word) + "', found '" + shown(in.token(0)) + "'");
}

Surface read_ascii(const std::string& path, std::string bytes) {
  TextLines in(path, std::move(bytes));
  Surface s;
  in.expect("'solid'");
  if (in.token(0) != "solid") in.fail("not an STL file: no 'solid' at the start and not the size of a binary STL");
  while (in.next()) {
    if (in.token(0) == "endsolid") continue;
    if (in.token(0) == "solid") continue;
    if (in.token(0) != "facet") in.fail("expected 'facet', found '" + shown(in.token(0)) + "'");
    expect_word(in, "outer", "'outer loop'");
    std::vector<VertexId> face;
    for (int k = 0; k < 3; ++k) {
      expect_word(in, "vertex", "a 'vertex x y z' line");
      in.need(4, "vertex x y z");
      face.push_back(static_cast<VertexId>(s.points.size()));
      s.points.push_back({in.real(1), in.real(2), in.real(3)});
    }
    expect_word(in, "endloop", "'endloop' (STL facets are triangles)");
    expect_word(in, "endfacet", "'endfacet'");
    s.faces.push_back(std::move(face));
  }
  return s;
}

}  // namespace

plc::Plc read_stl(const std::string& path) {
  std::string bytes = read_file_bytes(path);
  Surface s = is_binary(bytes) ? read_binary(path, bytes) : read_ascii(path, std::move(bytes));
  return surface_to_plc(std::move(s), path);
}

}  // namespace fdr::tetio
