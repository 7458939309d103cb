// Long io test: a million-triangle grid mesh written in every format within a time budget.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include "io/reader.hpp"
#include "io/writer.hpp"

namespace fs = std::filesystem;
using namespace fdr;

namespace {
// n x n vertices, 2 (n-1)^2 CCW triangles, the outer ring as land edges.
mesh::MeshView grid_mesh(Index n) {
  mesh::MeshView m;
  m.origin = {400000.0, 5000000.0};
  for (Index j = 0; j < n; ++j)
    for (Index i = 0; i < n; ++i) {
      m.vertices.push_back({10.0 * i + 0.001 * j, 10.0 * j});
      m.z.push_back(-0.01 * i - 0.02 * j);
    }
  auto id = [n](Index i, Index j) { return j * n + i; };
  for (Index j = 0; j + 1 < n; ++j)
    for (Index i = 0; i + 1 < n; ++i) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  for (Index i = 0; i + 1 < n; ++i) {
    m.edges.push_back({id(i, 0), id(i + 1, 0), 1, 0});
    m.edges.push_back({id(n - 1, i), id(n - 1, i + 1), 3, 1});
    m.edges.push_back({id(i + 1, n - 1), id(i, n - 1), 1, 0});
    m.edges.push_back({id(0, i + 1), id(0, i), 1, 0});
  }
  return m;
}
}  // namespace

TEST(IoLong, MillionTrianglesEveryFormat) {
  mesh::MeshView m = grid_mesh(708);  // 999,698 triangles
  ASSERT_GT(m.num_triangles(), 999000u);
  std::string dir = (fs::temp_directory_path() / "fdr_io_long").string();
  fs::create_directories(dir);
  io::WriteOptions o;
  o.title = "grid";
  auto timed_write = [&](const std::string& p) {
    auto t0 = std::chrono::steady_clock::now();
    io::write_mesh(m, p, io::format_from_path(p), o);
    double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("write %-14s %6.2f s  %6.1f MB\n", fs::path(p).filename().c_str(), s, fs::file_size(p) / 1e6);
    return s;
  };
  o.gpkg_spatial_index = false;
  EXPECT_LT(timed_write(dir + "/noindex.gpkg"), 20.0);  // a few seconds on an idle machine
  o.gpkg_spatial_index = true;
  for (const char* name : {"m.gpkg", "m.2dm", "m.msh", "m.node", "m.vtu", "m.14", "m.nc", "m.gr3", "m.slf", "m_net.nc"}) {
    std::string p = dir + "/" + name;
    double s = timed_write(p);
    EXPECT_LT(s, std::string(name) == "m.gpkg" ? 20.0 : 10.0);  // gpkg: ~6 s on a loaded 2-core machine
    if (std::string(name) == "m.gpkg") {
      // The bulk-loaded R-tree of a million triangles passes SQLite's own consistency check.
      GDALAllRegister();
      GDALDataset* ds = static_cast<GDALDataset*>(GDALOpenEx(p.c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr));
      ASSERT_NE(ds, nullptr);
      OGRLayer* q = ds->ExecuteSQL("SELECT rtreecheck('rtree_triangles_geom')", nullptr, nullptr);
      ASSERT_NE(q, nullptr);
      std::unique_ptr<OGRFeature> row(q->GetNextFeature());
      EXPECT_STREQ(row->GetFieldAsString(0), "ok");
      ds->ReleaseResultSet(q);
      GDALClose(ds);
    }
    if (std::string(name) != "m.vtu" && std::string(name) != "m.nc" && std::string(name) != "m_net.nc") {
      auto t0 = std::chrono::steady_clock::now();
      mesh::MeshView r = io::read_mesh(p);
      s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::printf("read  %-14s %6.2f s\n", name, s);
      EXPECT_EQ(r.num_triangles(), m.num_triangles());
      EXPECT_EQ(r.num_vertices(), m.num_vertices());
    }
  }
  fs::remove_all(dir);
}
