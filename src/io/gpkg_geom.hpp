// GeoPackage geometry blobs (GeoPackage binary header + little-endian WKB) built by hand, and the
// extent of what was written, for the GeoPackage writer.
#pragma once
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>

namespace fdr::io::detail {

// GeoPackage geometry blob: "GP", version 0, flags (little endian; envelope [minx,maxx,miny,maxy]
// except for points; empty bit), srs_id, envelope, then little-endian WKB.
class GeomBlob {
 public:
  explicit GeomBlob(std::int32_t srs) : srs_(srs) {}
  const std::string& point(double x, double y) {
    const bool empty = !(std::isfinite(x) && std::isfinite(y));
    header(empty ? 0x11 : 0x01);
    wkb_head(1);
    if (empty) x = y = std::numeric_limits<double>::quiet_NaN();
    put(x);
    put(y);
    return b_;
  }
  // Polygon with one ring or linestring; `closed` repeats the first point (the ring always is).
  // The polygon's bytes are written in place into a buffer sized once (one per triangle row).
  template <class Pt>
  const std::string& polygon(const Pt* p, std::uint32_t n) {
    header(0x03);
    envelope(p, n);
    const std::size_t at = b_.size();
    b_.resize(at + 1 + 4 + 4 + 4 + 16 * (static_cast<std::size_t>(n) + 1));
    char* o = b_.data() + at;
    *o++ = 1;  // little endian
    const std::uint32_t head[3] = {3, 1, n + 1};  // polygon, one ring, its points
    std::memcpy(o, head, 12);
    o += 12;
    for (std::uint32_t i = 0; i <= n; ++i, o += 16) {
      const double xy[2] = {p[i % n].x, p[i % n].y};
      std::memcpy(o, xy, 16);
    }
    return b_;
  }
  template <class Pt>
  const std::string& linestring(const Pt* p, std::uint32_t n, bool closed) {
    header(0x03);
    envelope(p, n);
    wkb_head(2);
    put32(n + (closed ? 1 : 0));
    for (std::uint32_t i = 0; i < n; ++i) put(p[i].x), put(p[i].y);
    if (closed) put(p[0].x), put(p[0].y);
    return b_;
  }
  double minx = 0, maxx = 0, miny = 0, maxy = 0;  // envelope of the last polygon/linestring

 private:
  void header(std::uint8_t flags) {
    b_.resize(8);
    b_[0] = 'G';
    b_[1] = 'P';
    b_[2] = 0;
    b_[3] = static_cast<char>(flags);
    const auto srs = static_cast<std::uint32_t>(srs_);
    std::memcpy(&b_[4], &srs, 4);
  }
  template <class Pt>
  void envelope(const Pt* p, std::uint32_t n) {
    minx = maxx = p[0].x;
    miny = maxy = p[0].y;
    for (std::uint32_t i = 1; i < n; ++i) {
      minx = std::min(minx, p[i].x), maxx = std::max(maxx, p[i].x);
      miny = std::min(miny, p[i].y), maxy = std::max(maxy, p[i].y);
    }
    const double e[4] = {minx, maxx, miny, maxy};
    b_.append(reinterpret_cast<const char*>(e), 32);
  }
  void wkb_head(std::uint32_t type) {
    b_.push_back(1);
    put32(type);
  }
  void put32(std::uint32_t v) {
    char c[4];
    std::memcpy(c, &v, 4);  // little-endian host (checked below)
    b_.append(c, 4);
  }
  void put(double v) {
    char c[8];
    std::memcpy(c, &v, 8);
    b_.append(c, 8);
  }
  std::int32_t srs_;
  std::string b_;
};
static_assert(std::endian::native == std::endian::little, "GeomBlob writes the host byte order as little endian");

struct Extent {
  double minx = std::numeric_limits<double>::infinity(), maxx = -minx, miny = minx, maxy = -minx;
  void add(double x0, double x1, double y0, double y1) {
    minx = std::min(minx, x0), maxx = std::max(maxx, x1), miny = std::min(miny, y0), maxy = std::max(maxy, y1);
  }
  bool empty() const { return !(minx <= maxx); }
};

}  // namespace fdr::io::detail
