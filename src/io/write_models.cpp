// Coastal-model writers sharing one boundary extraction: ADCIRC fort.14, SCHISM hgrid.gr3 /
// hgrid.ll, and the Telemac Selafin geometry with its .cli boundary conditions file.
#include <climits>
#include <cmath>
#include <cstring>

#include "base/error.hpp"
#include "gis/lonlat.hpp"
#include "io/boundaries.hpp"
#include "io/detail.hpp"

namespace fdr::io::detail {

namespace {

std::string one_line(const std::string& s) {
  std::string r = s;
  for (char& c : r)
    if (c == '\n' || c == '\r') c = ' ';
  return r;
}

// Splits a closed run of k >= 3 nodes into nodes[0..h] and nodes[h..k-1] + nodes[0], h = k / 2.
void split_closed(const BoundaryRun& r, std::vector<BoundaryList>& out) {
  const std::size_t k = r.nodes.size(), h = k / 2;
  BoundaryList a{r.kind, std::vector<Index>(r.nodes.begin(), r.nodes.begin() + static_cast<std::ptrdiff_t>(h) + 1)};
  BoundaryList b{r.kind, std::vector<Index>(r.nodes.begin() + static_cast<std::ptrdiff_t>(h), r.nodes.end())};
  b.nodes.push_back(r.nodes.front());
  out.push_back(std::move(a));
  out.push_back(std::move(b));
}

}  // namespace

BoundaryLists model_boundary_lists(const mesh::MeshView& m, const std::string& path, BoundaryFlavor flavor,
                                   BoundaryCache* cache) {
  Boundaries own;
  const Boundaries& b = boundaries_for(m, path, cache, own);
  BoundaryLists out;
  for (const BoundaryRun& r : b.runs) {
    auto& dst = r.kind == BoundaryKind::kOpen ? out.open : out.walls;
    if (!r.closed) {
      dst.push_back({r.kind, r.nodes});
      continue;
    }
    switch (flavor) {
      case BoundaryFlavor::kFort14: {
        BoundaryList l{r.kind, r.nodes};
        l.nodes.push_back(r.nodes.front());
        dst.push_back(std::move(l));
        break;
      }
      case BoundaryFlavor::kGr3:
      case BoundaryFlavor::kLl:
        if (r.kind == BoundaryKind::kIsland) dst.push_back({r.kind, r.nodes});
        else split_closed(r, dst);
        break;
      case BoundaryFlavor::k2dm:
        split_closed(r, dst);
        break;
    }
  }
  return out;
}

// ------------------------------------------------------------------ ADCIRC fort.14, SCHISM gr3/ll
// AGRID / NE NP / "JN X Y DP" (DP depth positive down) / "JE 3 N1 N2 N3" / NOPE, NETA, per open
// boundary its node count (fort.14 adds IBTYPEE 0: elevation specified) and nodes / NBOU, NVEL,
// per land boundary "NVELL IBTYPE" (0 mainland, 1 island) and nodes. See model_boundary_lists.
void write_adcirc(const mesh::MeshView& m, const std::string& path, const WriteOptions& o, BoundaryFlavor flavor) {
  const BoundaryLists bl = model_boundary_lists(m, path, flavor, o.boundary_cache);
  std::vector<LonLat> ll;
  if (flavor == BoundaryFlavor::kLl && !m.vertices.empty()) ll = gis::points_to_lonlat(m.vertices, m.origin, m.crs_wkt);
  const bool down = flavor != BoundaryFlavor::kFort14 || o.fort14_depth_positive_down;
  auto count = [](const std::vector<BoundaryList>& v) {
    std::uint64_t n = 0;
    for (const auto& l : v) n += l.nodes.size();
    return n;
  };
  TempFile tf(path);
  TextOut out(tf.stream(), path);
  out.str(one_line(o.title.empty() ? "fdrmesh" : o.title)).nl();
  out.num(static_cast<std::uint64_t>(m.triangles.size())).sp().num(static_cast<std::uint64_t>(m.vertices.size()))
      .str(" ! NE NP").nl();
  for (std::size_t v = 0; v < m.vertices.size(); ++v) {
    double x, y;
    if (flavor == BoundaryFlavor::kLl) {
      x = ll[v].lon_deg;
      y = ll[v].lat_deg;
    } else {
      const Point2 w = m.world(static_cast<Index>(v));
      x = w.x;
      y = w.y;
    }
    const double z = m.z.empty() ? 0.0 : m.z[v];
    double dp = down ? -z : z;
    if (dp == 0) dp = 0;  // no "-0" in the file
    out.num(static_cast<std::uint64_t>(v + 1)).sp().num(x).sp().num(y).sp().num(dp).nl();
  }
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    out.num(static_cast<std::uint64_t>(t + 1)).str(" 3");
    for (Index v : m.triangles[t]) out.sp().num(static_cast<std::uint64_t>(v) + 1);
    out.nl();
  }
  out.num(static_cast<std::uint64_t>(bl.open.size())).str(" = Number of open boundaries").nl();
  out.num(count(bl.open)).str(" = Total number of open boundary nodes").nl();
  for (std::size_t i = 0; i < bl.open.size(); ++i) {
    out.num(static_cast<std::uint64_t>(bl.open[i].nodes.size()));
    if (flavor == BoundaryFlavor::kFort14) out.str(" 0");
    out.str(" = Number of nodes for open boundary ").num(static_cast<std::uint64_t>(i + 1)).nl();
    for (Index v : bl.open[i].nodes) out.num(static_cast<std::uint64_t>(v) + 1).nl();
  }
  out.num(static_cast<std::uint64_t>(bl.walls.size())).str(" = Number of land boundaries").nl();
  out.num(count(bl.walls)).str(" = Total number of land boundary nodes").nl();
  for (std::size_t i = 0; i < bl.walls.size(); ++i) {
    const int type = bl.walls[i].kind == BoundaryKind::kIsland ? 1 : 0;
    out.num(static_cast<std::uint64_t>(bl.walls[i].nodes.size())).sp().num(type)
        .str(" = Number of nodes for land boundary ").num(static_cast<std::uint64_t>(i + 1)).nl();
    for (Index v : bl.walls[i].nodes) out.num(static_cast<std::uint64_t>(v) + 1).nl();
  }
  out.flush();
  tf.commit();
}

// ------------------------------------------------------------------ Telemac Selafin + .cli
namespace {

// Big-endian Fortran sequential records: [int32 length] payload [int32 length].
class FortranOut {
 public:
  FortranOut(std::FILE* f, const std::string& target) : f_(f), target_(target) { buf_.reserve(kFlush + 64); }
  void begin(std::size_t bytes) {
    if (bytes > static_cast<std::size_t>(INT32_MAX))
      fail_output(target_, "a Selafin record would hold " + std::to_string(bytes) +
                               " bytes, more than the format's 2^31-1 (mesh too large for Selafin)");
    len_ = bytes;
    i32(static_cast<std::int32_t>(bytes));
  }
  void end() { i32(static_cast<std::int32_t>(len_)); }
  void i32(std::int32_t v) {
    std::uint32_t u;
    std::memcpy(&u, &v, 4);
    put_be(u, 4);
  }
  void f32(float v) {
    std::uint32_t u;
    std::memcpy(&u, &v, 4);
    put_be(u, 4);
  }
  void f64(double v) {
    std::uint64_t u;
    std::memcpy(&u, &v, 8);
    put_be(u, 8);
  }
  void chars(const std::string& s, std::size_t width) {
    for (std::size_t i = 0; i < width; ++i) buf_.push_back(i < s.size() ? s[i] : ' ');
  }
  void flush() {
    if (!buf_.empty() && std::fwrite(buf_.data(), 1, buf_.size(), f_) != buf_.size()) {
      int e = errno;
      fail_output(target_, std::string("write failed: ") + std::strerror(e));
    }
    buf_.clear();
  }

 private:
  static constexpr std::size_t kFlush = 1 << 20;
  template <class U>
  void put_be(U u, int n) {
    for (int i = n - 1; i >= 0; --i) buf_.push_back(static_cast<char>((u >> (8 * i)) & 0xff));
    if (buf_.size() >= kFlush) flush();
  }
  std::FILE* f_;
  const std::string& target_;
  std::string buf_;
  std::size_t len_ = 0;
};

}  // namespace

// Selafin (SERAFIN/SERAFIND) geometry, one record after the other:
//   title (72 chars) + "SERAFIN " | "SERAFIND";  NBV1 NBV2 = 1 0;  "BOTTOM" + "M" (16 + 16 chars);
//   IPARAM(10) = 1 0 I_ORIG J_ORIG 0 0 0 0 0 0;  NELEM NPOIN 3 1;  IKLE (1-based, counter-
//   clockwise, element by element);  IPOBO (0 interior, else the node's rank in the .cli);
//   X - I_ORIG;  Y - J_ORIG;  one time step: T = 0, BOTTOM = bed elevation z (positive up).
// Single precision stores X/Y relative to the integer offset (I_ORIG, J_ORIG) = the rounded
// centre of the bounding box, so 32-bit floats keep millimetres; SERAFIND writes offset 0.
// The .cli: one line per boundary node in IPOBO order,
//   LIHBOR LIUBOR LIVBOR HBOR UBOR VBOR AUBOR LITBOR TBOR ATBOR BTBOR N K
// walls "2 2 2 0.0 0.0 0.0 0.0 2 0.0 0.0 0.0", open nodes "<codes> 0.0 0.0 0.0 0.0 4 0.0 0.0 0.0".
void write_selafin(const mesh::MeshView& m, const std::string& path, const WriteOptions& o) {
  const std::size_t nv = m.vertices.size(), nt = m.triangles.size();
  if (nv > static_cast<std::size_t>(INT32_MAX) || 3 * nt > static_cast<std::size_t>(INT32_MAX))
    fail_output(path, "mesh too large for Selafin (32-bit counts)");
  Boundaries own;
  const Boundaries& b = boundaries_for(m, path, o.boundary_cache, own);
  if (const Index p = pinch_node(b, nv); p != kNoId) {
    const Point2 w = m.world(p);
    fail_output(path, "node " + std::to_string(p + 1) + " at (" + std::to_string(w.x) + ", " + std::to_string(w.y) +
                          ") lies twice on the boundary (two boundary loops touch there); Telemac needs every "
                          "boundary node once: separate the features in the input");
  }
  const std::vector<Index> order = b.ordered_nodes();
  const std::vector<char> open = b.open_nodes(nv);

  std::int32_t i_orig = 0, j_orig = 0;
  if (!o.slf_double && nv) {
    Box2 box;
    for (std::size_t v = 0; v < nv; ++v) box.add(m.world(static_cast<Index>(v)));
    const Point2 c = box.center();
    if (std::fabs(c.x) < 2e9 && std::fabs(c.y) < 2e9) {
      i_orig = static_cast<std::int32_t>(std::lround(c.x));
      j_orig = static_cast<std::int32_t>(std::lround(c.y));
    }
  }

  std::string base = path;
  if (lower_extension(path) == ".slf") base = path.substr(0, path.size() - 4);
  TempFile slf_tf(path);
  TempFile cli_tf(base + ".cli");
  {
    FortranOut out(slf_tf.stream(), path);
    std::string title = one_line(o.title.empty() ? "fdrmesh" : o.title);
    out.begin(80);
    out.chars(title, 72);
    out.chars(o.slf_double ? "SERAFIND" : "SERAFIN ", 8);
    out.end();
    out.begin(8);
    out.i32(1);
    out.i32(0);
    out.end();
    out.begin(32);
    out.chars("BOTTOM", 16);
    out.chars("M", 16);
    out.end();
    out.begin(40);
    const std::int32_t iparam[10] = {1, 0, i_orig, j_orig, 0, 0, 0, 0, 0, 0};
    for (std::int32_t v : iparam) out.i32(v);
    out.end();
    out.begin(16);
    out.i32(static_cast<std::int32_t>(nt));
    out.i32(static_cast<std::int32_t>(nv));
    out.i32(3);
    out.i32(1);
    out.end();
    out.begin(12 * nt);
    for (const auto& tr : m.triangles)
      for (Index v : tr) out.i32(static_cast<std::int32_t>(v + 1));
    out.end();
    std::vector<std::int32_t> ipobo(nv, 0);
    for (std::size_t k = 0; k < order.size(); ++k) ipobo[order[k]] = static_cast<std::int32_t>(k + 1);
    out.begin(4 * nv);
    for (std::int32_t v : ipobo) out.i32(v);
    out.end();
    const std::size_t rs = o.slf_double ? 8 : 4;
    auto real = [&](double v) { o.slf_double ? out.f64(v) : out.f32(static_cast<float>(v)); };
    for (int axis = 0; axis < 2; ++axis) {
      out.begin(rs * nv);
      for (std::size_t v = 0; v < nv; ++v) {
        const Point2 w = m.world(static_cast<Index>(v));
        real(axis == 0 ? w.x - i_orig : w.y - j_orig);
      }
      out.end();
    }
    out.begin(rs);
    real(0.0);
    out.end();
    out.begin(rs * nv);
    for (std::size_t v = 0; v < nv; ++v) real(m.z.empty() ? 0.0 : m.z[v]);
    out.end();
    out.flush();
    slf_tf.close_stream();
  }
  {
    TextOut out(cli_tf.stream(), cli_tf.target());
    const auto& c = o.telemac_open_codes;
    for (std::size_t k = 0; k < order.size(); ++k) {
      const Index v = order[k];
      if (open[v]) {
        out.num(c[0]).sp().num(c[1]).sp().num(c[2]).str(" 0.0 0.0 0.0 0.0 4 0.0 0.0 0.0 ");
      } else {
        out.str("2 2 2 0.0 0.0 0.0 0.0 2 0.0 0.0 0.0 ");
      }
      out.num(static_cast<std::uint64_t>(v) + 1).sp().num(static_cast<std::uint64_t>(k + 1)).nl();
    }
    out.flush();
    cli_tf.close_stream();
  }
  commit_all({&slf_tf, &cli_tf});
}

}  // namespace fdr::io::detail
