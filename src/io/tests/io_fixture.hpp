// Shared by the io tests: a small mesh with every boundary kind, write options, a temporary folder
// that removes itself, and the round-trip fixture.
#pragma once

#include <gtest/gtest.h>
#include <netcdf.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include <sqlite3.h>

#include "base/error.hpp"
#include "base/tests/scoped_env.hpp"
#include "io/detail.hpp"
#include "io/reader.hpp"
#include "io/gpkg_index.hpp"
#include "io/sqlite_db.hpp"
#include "io/write_many.hpp"
#include "io/writer.hpp"
#include "io/tests/tmp_dir.hpp"

namespace fs = std::filesystem;

namespace fdr::io_testing {

using fdr::io::Format;
using mesh::EdgeKind;

// A spacing of one value everywhere.
class ConstantF : public sizing::SizingField {
 public:
  explicit ConstantF(double v) : v_(v) {}
  double operator()(Point2) const override { return v_; }
  std::string describe() const override { return "constant"; }

 private:
  double v_;
};

inline std::int32_t mk(EdgeKind k) { return static_cast<std::int32_t>(k); }

// A 4x4 square with a 2x2 island hole, an open right side (with a midpoint) and one breakline:
//
//   o4 ------------- o3
//   |  h3 ------ h2 / |
//   |   |  hole  |    o2   (o1-o2-o3: open boundary)
//   |  h0 ------ h1   |
//   o0 ------------- o1     breakline o0-h0
inline mesh::MeshView sample_mesh() {
  mesh::MeshView m;
  m.origin = {500000.1, 6400000.3};
  m.vertices = {{0, 0}, {4, 0}, {4, 2}, {4, 4}, {0, 4}, {1, 1}, {3, 1}, {3, 3}, {1, 3}};
  m.triangles = {{0, 1, 6}, {0, 6, 5}, {1, 2, 6}, {2, 7, 6}, {2, 3, 7},
                 {3, 4, 8}, {3, 8, 7}, {4, 0, 5}, {4, 5, 8}};
  // Listed out of order and with mixed directions on purpose: chains must be rebuilt.
  m.edges = {{4, 0, mk(EdgeKind::kLand), 0},   {2, 3, mk(EdgeKind::kOpen), 1},  {0, 1, mk(EdgeKind::kLand), 0},
             {3, 4, mk(EdgeKind::kLand), 0},   {1, 2, mk(EdgeKind::kOpen), 1},  {6, 5, mk(EdgeKind::kIsland), 2},
             {7, 6, mk(EdgeKind::kIsland), 2}, {8, 7, mk(EdgeKind::kIsland), 2}, {5, 8, mk(EdgeKind::kIsland), 2},
             {0, 5, mk(EdgeKind::kBreakline), 3}};
  for (std::size_t v = 0; v < m.vertices.size(); ++v) {
    m.z.push_back(-0.1 * static_cast<double>(v + 1) - 1.0 / 3.0);
    m.f.push_back(1.0 + 0.1 * static_cast<double>(v));
  }
  OGRSpatialReference srs;
  srs.importFromEPSG(32633);
  char* wkt = nullptr;
  srs.exportToWkt(&wkt);
  m.crs_wkt = wkt;
  CPLFree(wkt);
  return m;
}

inline io::WriteOptions sample_options(const sizing::SizingField* f) {
  io::WriteOptions o;
  o.f = f;
  o.bound_B = 1.5;
  o.title = "io test mesh";
  o.metadata = {{"version", "0.1.0"}, {"command_line", "fdrmesh mesh -i a.gpkg -o b.gpkg"}, {"quality", "{\"n\":9}"}};
  o.repairs = {{"snap", 500001.0, 6400001.0, 0.01, "vertices closer than tolerance", 0},
               {"drop_sliver", 500002.0, 6400002.0, 1e-4, "sliver ring area below threshold", 5}};
  return o;
}

inline bool has_temp_leftover(const TmpDir& d) {
  for (const auto& n : d.entries())
    if (n.find(".tmp-") != std::string::npos) return true;
  return false;
}

using EdgeSet = std::set<std::tuple<Index, Index, std::int32_t>>;
inline EdgeSet edge_set(const mesh::MeshView& m, std::set<std::int32_t> kinds) {
  EdgeSet s;
  for (const auto& e : m.edges)
    if (kinds.count(e.marker)) s.insert({std::min(e.a, e.b), std::max(e.a, e.b), e.marker});
  return s;
}

// World coordinates, z and triangles must read back bit-exactly and in the same order.
inline void expect_same_geometry(const mesh::MeshView& a, const mesh::MeshView& b, bool check_z = true) {
  ASSERT_EQ(a.num_vertices(), b.num_vertices());
  ASSERT_EQ(a.num_triangles(), b.num_triangles());
  for (Index v = 0; v < a.num_vertices(); ++v) {
    EXPECT_EQ(a.world(v).x, b.world(v).x) << "vertex " << v;
    EXPECT_EQ(a.world(v).y, b.world(v).y) << "vertex " << v;
  }
  if (check_z) {
    ASSERT_EQ(b.z.size(), a.z.size());
    for (std::size_t v = 0; v < a.z.size(); ++v) EXPECT_EQ(a.z[v], b.z[v]) << "z of vertex " << v;
  }
  for (std::size_t t = 0; t < a.num_triangles(); ++t) EXPECT_EQ(a.triangles[t], b.triangles[t]) << "triangle " << t;
}

// Every file format, and the extension that selects it.
constexpr Format kEvery[] = {Format::kGpkg, Format::k2dm,   Format::kMsh, Format::kNode,   Format::kVtu, Format::kFort14,
                             Format::kUgrid, Format::kSelafin, Format::kGr3, Format::kLl, Format::kDflowfm};
inline std::string ext_of(Format f) {
  switch (f) {
    case Format::kGpkg: return ".gpkg";
    case Format::k2dm: return ".2dm";
    case Format::kMsh: return ".msh";
    case Format::kNode: return ".node";
    case Format::kVtu: return ".vtu";
    case Format::kFort14: return ".14";
    case Format::kUgrid: return ".nc";
    case Format::kSelafin: return ".slf";
    case Format::kGr3: return ".gr3";
    case Format::kLl: return ".ll";
    case Format::kDflowfm: return "_net.nc";
    case Format::kPostgis: return "";  // a database, not a file (postgis_test.cpp)
  }
  return "";
}

// A fresh temporary folder, the sample mesh and its write options for every test.
class IoRoundTrip : public ::testing::Test {
 protected:
  TmpDir tmp;
  mesh::MeshView m = sample_mesh();
  ConstantF f{2.0};
  io::WriteOptions opts = sample_options(&f);
};

}  // namespace fdr::io_testing
