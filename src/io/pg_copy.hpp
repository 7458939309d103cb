// Rows in PostgreSQL's binary COPY format, geometries as PostGIS EWKB (little-endian, with the
// SRID), so the server neither parses text numbers nor hex: fields in network byte order, each
// with its length, NULL as length -1.
#pragma once
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace fdr::io::pg {

class CopyBuffer {
 public:
  // Bytes go to `sink` in pieces of about `chunk` bytes (the last with finish()).
  using Sink = std::function<void(const char*, std::size_t)>;
  explicit CopyBuffer(Sink sink, std::size_t chunk = std::size_t{1} << 20);

  void row(std::int16_t fields) {  // starts a row of that many fields
    flush_if_full();
    be16(static_cast<std::uint16_t>(fields));
  }
  void null() { be32(0xFFFFFFFFu); }
  void i32(std::int32_t v) {
    be32(4);
    be32(static_cast<std::uint32_t>(v));
  }
  void i64(std::int64_t v) {
    be32(8);
    be64(static_cast<std::uint64_t>(v));
  }
  void f8(double v) {  // NULL when not finite (as the GeoPackage writer)
    if (!std::isfinite(v)) return null();
    be32(8);
    be64(std::bit_cast<std::uint64_t>(v));
  }
  void boolean(bool v);
  void text(std::string_view v);  // UTF-8
  // EWKB geometries with SRID `srid` (0: none), x y pairs.
  void point(std::int32_t srid, double x, double y);
  void linestring(std::int32_t srid, const std::vector<double>& xy);
  void polygon(std::int32_t srid, const double* ring_xy, std::uint32_t points);  // one ring
  // Ends the stream (trailer) and hands the rest to the sink.
  void finish();

 private:
  // Fixed-size fields, called several times a row: defined here so that they inline.
  template <class U>
  void put(U v, bool big_endian) {
    if ((std::endian::native == std::endian::big) != big_endian) v = byteswap(v);
    char b[sizeof(U)];
    std::memcpy(b, &v, sizeof(U));
    buf_.append(b, sizeof(U));
  }
  template <class U>
  static U byteswap(U v) {
    U r = 0;
    for (std::size_t i = 0; i < sizeof(U); ++i) r = static_cast<U>((r << 8) | ((v >> (8 * i)) & 0xFF));
    return r;
  }
  void be16(std::uint16_t v) { put(v, true); }
  void be32(std::uint32_t v) { put(v, true); }
  void be64(std::uint64_t v) { put(v, true); }
  void le32(std::uint32_t v) { put(v, false); }
  void le64(std::uint64_t v) { put(v, false); }
  void ewkb_head(std::uint32_t type, std::int32_t srid, std::uint32_t length);
  void flush_if_full();

  Sink sink_;
  std::size_t chunk_;
  std::string buf_;
};

}  // namespace fdr::io::pg
