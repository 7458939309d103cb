// Oracle of the fuzz_pslg_mesh target (shared with its regression test): PSLG -> pslg::resolve -> cdt::build_cdt -> FDR refinement, with the mesh
// checkers (mesh::check_all) as the oracle and a small Steiner cap.
//
// Input: either Triangle .poly text, or (first byte 'B') a compact binary PSLG on an integer
// lattice, which makes collinear overlaps, vertices on segments, stars and crossings common:
//   'B', flags, n, n x (x, y) as int8 (or int16 with flag bit 6), m, m x (a, b) vertex bytes
//   (high bit of a: breakline marker 4), holes h, h x (x, y) int8 (+0.5), spacing byte.
//   flags bit 0: --convex-hull; bit 7: parity regions (GIS path); bits 1-3: scale 10^{-6,-3,0,0,3,6,-12,1}; bits 4-5: offset
//   {0, 1e7, -3.5e5, 12345.678} (applied to x and y).
// Oracle: no sanitizer report; no kInternal error; after refinement (finished or stopped by the
// cap) check_all holds; a finished refinement leaves no triangle with R/f(c) > B.
#include <unistd.h>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include "base/error.hpp"
#include "cdt/cdt.hpp"
#include "mesh/check.hpp"
#include "pslg/poly_io.hpp"
#include "pslg/resolve.hpp"
#include "refine/refine.hpp"
#include "sizing/make_spacing.hpp"

namespace fdr_fuzz {

using fdr::Point2;
using fdr::pslg::Pslg;

struct Reader {
  const std::uint8_t* d;
  std::size_t n, i = 0;
  int u8() { return i < n ? d[i++] : 0; }
  int s8() { return static_cast<std::int8_t>(u8()); }
  int s16() { return static_cast<std::int16_t>(static_cast<std::uint16_t>(u8() | (u8() << 8))); }
};

inline bool decode_binary(const std::uint8_t* data, std::size_t size, Pslg* g, bool* hull, bool* parity, int* fine) {
  Reader r{data, size, 1};
  const int flags = r.u8();
  *hull = flags & 1;
  *parity = flags & 128;
  static const double scales[8] = {1e-6, 1e-3, 1, 1, 1e3, 1e6, 1e-12, 10};
  static const double offsets[4] = {0, 1e7, -3.5e5, 12345.678};
  const double sc = scales[(flags >> 1) & 7], off = offsets[(flags >> 4) & 3];
  const bool wide = flags & 64;
  const int n = r.u8() % 48;
  for (int k = 0; k < n; ++k) {
    const double x = wide ? r.s16() : r.s8(), y = wide ? r.s16() : r.s8();
    g->points.push_back({off + x * sc, off + y * sc});
  }
  if (n == 0) return false;
  const int m = r.u8() % 64;
  for (int k = 0; k < m; ++k) {
    const int a = r.u8(), b = r.u8();
    g->segments.push_back({static_cast<fdr::Index>((a & 127) % n), static_cast<fdr::Index>(b % n), (a & 128) ? 4 : 1, -1});
  }
  const int h = r.u8() % 3;
  for (int k = 0; k < h; ++k) {
    const double x = r.s8() + 0.5, y = r.s8() + 0.5;
    g->holes.push_back({off + x * sc, off + y * sc});
  }
  *fine = 3 + r.u8() % 12;
  return true;
}

inline bool decode_text(const std::uint8_t* data, std::size_t size, Pslg* g) {
  static const std::string path = "/tmp/fdr_fuzz_mesh_" + std::to_string(getpid()) + ".poly";
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return false;
  std::fwrite(data, 1, size, f);
  std::fclose(f);
  try {
    *g = fdr::pslg::read_poly(path);
  } catch (const fdr::Error&) {
    return false;
  }
  return g->points.size() <= 200 && g->segments.size() <= 400;
}


// Runs one case; returns "" when every check holds, else what failed.
inline std::string pslg_mesh_case(const std::uint8_t* data, std::size_t size) {
  if (size == 0 || size > 4096) return "";
  Pslg g;
  bool hull = false, parity = false;
  int fine = 6;
  if (data[0] == 'B') {
    if (!decode_binary(data, size, &g, &hull, &parity, &fine)) return "";
  } else if (!decode_text(data, size, &g)) {
    return "";
  }
  Pslg res;
  try {
    res = fdr::pslg::resolve(g, {}, nullptr);
  } catch (const fdr::Error& e) {
    if (e.code() == fdr::ExitCode::kInternal) return std::string("resolve: ") + e.what();
    return "";  // non-finite input, cascade cap
  }
  fdr::mesh::Triangulation tri;
  fdr::cdt::CdtOptions co;
  co.regions = hull ? fdr::cdt::CdtOptions::Regions::kHull
               : parity ? fdr::cdt::CdtOptions::Regions::kAuto  // the GIS path
               : res.segments.empty() ? fdr::cdt::CdtOptions::Regions::kNone
                                      : fdr::cdt::CdtOptions::Regions::kSeeds;  // as the .poly path
  co.source = "fuzz";
  try {
    tri = fdr::cdt::build_cdt(res, co);
  } catch (const fdr::Error& e) {
    if (e.code() == fdr::ExitCode::kInternal) return std::string("cdt: ") + e.what();
    return "";  // fewer than 3 vertices, hole seed errors
  }
  {
    const fdr::mesh::CheckResult cr = fdr::mesh::check_all(tri);
    if (!cr.ok()) return "CDT check: " + cr.problems.front();
  }
  if (tri.num_live_triangles() == 0) return "";
  const fdr::Box2 b = res.bbox();
  const double h = std::hypot(b.width(), b.height()) / fine;
  if (!(h > 0) || !std::isfinite(h)) return "";
  char spec[64];
  std::snprintf(spec, sizeof spec, "%.17g", h);
  fdr::sizing::SizingPtr f;
  try {
    f = fdr::sizing::make_spacing(spec);
  } catch (const fdr::Error&) {
    return "";
  }
  fdr::refine::RefineOptions ro;
  ro.max_steiner = 3000;
  bool finished = false;
  try {
    fdr::refine::Refiner refiner(tri, *f, ro);
    refiner.init();
    refiner.run();
    finished = true;
    if (refiner.leftovers().r_over_f_bad) return "refinement finished with R/f(c) > B triangles";
  } catch (const fdr::Error& e) {
    if (e.code() != fdr::ExitCode::kWorkLimit) return std::string("refine: ") + e.what();
  }
  const fdr::mesh::CheckResult cr = fdr::mesh::check_all(tri);
  if (!cr.ok()) return std::string(finished ? "mesh" : "capped mesh") + " check: " + cr.problems.front();
  return "";
}

}  // namespace fdr_fuzz
