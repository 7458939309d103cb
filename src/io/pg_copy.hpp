// Rows in PostgreSQL's binary COPY format, geometries as PostGIS EWKB (little-endian, with the
// SRID), so the server neither parses text numbers nor hex: fields in network byte order, each
// with its length, NULL as length -1.
#pragma once
#include <cstddef>
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

  void row(std::int16_t fields);  // starts a row of that many fields
  void null();
  void i32(std::int32_t v);
  void i64(std::int64_t v);
  void f8(double v);  // NULL when not finite (as the GeoPackage writer)
  void boolean(bool v);
  void text(std::string_view v);  // UTF-8
  // EWKB geometries with SRID `srid` (0: none), x y pairs.
  void point(std::int32_t srid, double x, double y);
  void linestring(std::int32_t srid, const std::vector<double>& xy);
  void polygon(std::int32_t srid, const double* ring_xy, std::uint32_t points);  // one ring
  // Ends the stream (trailer) and hands the rest to the sink.
  void finish();

 private:
  void be16(std::uint16_t v);
  void be32(std::uint32_t v);
  void be64(std::uint64_t v);
  void le32(std::uint32_t v);
  void le64(std::uint64_t v);
  void ewkb_head(std::uint32_t type, std::int32_t srid, std::uint32_t length);
  void flush_if_full();

  Sink sink_;
  std::size_t chunk_;
  std::string buf_;
};

}  // namespace fdr::io::pg
