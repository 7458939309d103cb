// Binary COPY rows and EWKB geometries (see pg_copy.hpp).
#include "io/pg_copy.hpp"

#include <bit>
#include <cmath>

namespace fdr::io::pg {

namespace {
// The binary COPY signature, flags and header extension length.
constexpr char kHeader[] = {'P', 'G', 'C', 'O', 'P', 'Y', '\n', '\377', '\r', '\n', '\0', 0, 0, 0, 0, 0, 0, 0, 0};
constexpr std::uint32_t kWkbPoint = 1, kWkbLineString = 2, kWkbPolygon = 3;
constexpr std::uint32_t kEwkbSrid = 0x20000000;
}  // namespace

CopyBuffer::CopyBuffer(Sink sink, std::size_t chunk) : sink_(std::move(sink)), chunk_(chunk) {
  buf_.reserve(chunk_ + 4096);
  buf_.append(kHeader, sizeof kHeader);
}

void CopyBuffer::flush_if_full() {
  if (buf_.size() < chunk_) return;
  sink_(buf_.data(), buf_.size());
  buf_.clear();
}

void CopyBuffer::be16(std::uint16_t v) {
  const char b[2] = {static_cast<char>(v >> 8), static_cast<char>(v)};
  buf_.append(b, 2);
}

void CopyBuffer::be32(std::uint32_t v) {
  const char b[4] = {static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8),
                     static_cast<char>(v)};
  buf_.append(b, 4);
}

void CopyBuffer::be64(std::uint64_t v) {
  be32(static_cast<std::uint32_t>(v >> 32));
  be32(static_cast<std::uint32_t>(v));
}

void CopyBuffer::le32(std::uint32_t v) {
  const char b[4] = {static_cast<char>(v), static_cast<char>(v >> 8), static_cast<char>(v >> 16),
                     static_cast<char>(v >> 24)};
  buf_.append(b, 4);
}

void CopyBuffer::le64(std::uint64_t v) {
  le32(static_cast<std::uint32_t>(v));
  le32(static_cast<std::uint32_t>(v >> 32));
}

void CopyBuffer::row(std::int16_t fields) {
  flush_if_full();
  be16(static_cast<std::uint16_t>(fields));
}

void CopyBuffer::null() { be32(0xFFFFFFFFu); }

void CopyBuffer::i32(std::int32_t v) {
  be32(4);
  be32(static_cast<std::uint32_t>(v));
}

void CopyBuffer::i64(std::int64_t v) {
  be32(8);
  be64(static_cast<std::uint64_t>(v));
}

void CopyBuffer::f8(double v) {
  if (!std::isfinite(v)) return null();
  be32(8);
  be64(std::bit_cast<std::uint64_t>(v));
}

void CopyBuffer::boolean(bool v) {
  be32(1);
  buf_.push_back(v ? '\1' : '\0');
}

void CopyBuffer::text(std::string_view v) {
  be32(static_cast<std::uint32_t>(v.size()));
  buf_.append(v.data(), v.size());
}

// Field length, byte order mark (1: little-endian), type with the SRID flag, SRID.
void CopyBuffer::ewkb_head(std::uint32_t type, std::int32_t srid, std::uint32_t length) {
  const bool has_srid = srid != 0;
  be32(length + 5 + (has_srid ? 4 : 0));
  buf_.push_back('\1');
  le32(type | (has_srid ? kEwkbSrid : 0));
  if (has_srid) le32(static_cast<std::uint32_t>(srid));
}

void CopyBuffer::point(std::int32_t srid, double x, double y) {
  ewkb_head(kWkbPoint, srid, 16);
  le64(std::bit_cast<std::uint64_t>(x));
  le64(std::bit_cast<std::uint64_t>(y));
}

void CopyBuffer::linestring(std::int32_t srid, const std::vector<double>& xy) {
  const auto n = static_cast<std::uint32_t>(xy.size() / 2);
  ewkb_head(kWkbLineString, srid, 4 + 16 * n);
  le32(n);
  for (double c : xy) le64(std::bit_cast<std::uint64_t>(c));
}

void CopyBuffer::polygon(std::int32_t srid, const double* ring_xy, std::uint32_t points) {
  ewkb_head(kWkbPolygon, srid, 8 + 16 * points);
  le32(1);
  le32(points);
  for (std::uint32_t i = 0; i < 2 * points; ++i) le64(std::bit_cast<std::uint64_t>(ring_xy[i]));
}

void CopyBuffer::finish() {
  be16(0xFFFFu);
  sink_(buf_.data(), buf_.size());
  buf_.clear();
}

}  // namespace fdr::io::pg
