// The GeoPackage writer: round trips through its own reader and OGR, the R-tree index, page sizes,
// the same bytes for every thread count and batch size, the GDAL validator.
#include "io/tests/io_fixture.hpp"

using namespace fdr;
using namespace fdr::io_testing;

TEST_F(IoRoundTrip, GeoPackageOwnReader) {
  std::string p = tmp / "mesh.gpkg";
  io::write_mesh(m, p, io::format_from_path(p), opts);
  EXPECT_EQ(tmp.entries(), std::vector<std::string>{"mesh.gpkg"});
  mesh::MeshView r = io::read_mesh(p);
  expect_same_geometry(m, r);
  std::set<std::int32_t> kinds{mk(EdgeKind::kLand), mk(EdgeKind::kIsland), mk(EdgeKind::kOpen), mk(EdgeKind::kBreakline)};
  EXPECT_EQ(edge_set(r, kinds), edge_set(m, kinds));
  // Parts survive: land 0, open 1, island 2, breakline 3.
  std::map<std::int32_t, std::int32_t> part_of{{mk(EdgeKind::kLand), 0}, {mk(EdgeKind::kOpen), 1},
                                               {mk(EdgeKind::kIsland), 2}, {mk(EdgeKind::kBreakline), 3}};
  for (const auto& e : r.edges) EXPECT_EQ(e.part, part_of[e.marker]);
  ASSERT_EQ(r.f.size(), m.f.size());
  for (std::size_t v = 0; v < m.f.size(); ++v) EXPECT_EQ(r.f[v], m.f[v]);
  OGRSpatialReference a, b;
  a.SetFromUserInput(m.crs_wkt.c_str());
  b.SetFromUserInput(r.crs_wkt.c_str());
  EXPECT_TRUE(a.IsSame(&b));
}

TEST_F(IoRoundTrip, GeoPackageThroughOgr) {
  std::string p = tmp / "mesh.gpkg";
  io::write_mesh(m, p, Format::kGpkg, opts);
  GDALAllRegister();
  GDALDataset* ds = static_cast<GDALDataset*>(GDALOpenEx(p.c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr));
  ASSERT_NE(ds, nullptr);
  std::map<std::string, GIntBig> counts;
  for (int i = 0; i < ds->GetLayerCount(); ++i) counts[ds->GetLayer(i)->GetName()] = ds->GetLayer(i)->GetFeatureCount();
  EXPECT_EQ(counts, (std::map<std::string, GIntBig>{
                        {"boundaries", 4}, {"metadata", 5}, {"nodes", 9}, {"repairs", 2}, {"triangles", 9}}));
  auto fields = [&](const char* layer) {
    std::vector<std::string> r;
    OGRFeatureDefn* d = ds->GetLayerByName(layer)->GetLayerDefn();
    for (int i = 0; i < d->GetFieldCount(); ++i) r.push_back(d->GetFieldDefn(i)->GetNameRef());
    return r;
  };
  EXPECT_EQ(fields("nodes"), (std::vector<std::string>{"id", "z", "f", "conformity", "marker"}));
  EXPECT_EQ(fields("triangles"), (std::vector<std::string>{"id", "n1", "n2", "n3", "area", "min_angle", "R_over_f", "quality"}));
  EXPECT_EQ(fields("boundaries"), (std::vector<std::string>{"id", "kind", "marker", "part", "closed", "num_nodes"}));
  EXPECT_EQ(fields("repairs"), (std::vector<std::string>{"kind", "size", "reason", "part"}));
  EXPECT_EQ(fields("metadata"), (std::vector<std::string>{"key", "value"}));
  EXPECT_EQ(ds->GetLayerByName("metadata")->GetGeomType(), wkbNone);
  EXPECT_EQ(ds->GetLayerByName("triangles")->GetGeomType(), wkbPolygon);
  const OGRSpatialReference* srs = ds->GetLayerByName("nodes")->GetSpatialRef();
  ASSERT_NE(srs, nullptr);
  EXPECT_STREQ(srs->GetAuthorityCode(nullptr), "32633");

  // Triangle 1 = (o0, o1, h1): area 2, R/f(c) with f = 2, quality 4 sqrt(3) area / sum of edges².
  OGRLayer* lt = ds->GetLayerByName("triangles");
  std::unique_ptr<OGRFeature> t1(lt->GetFeature(1));
  ASSERT_TRUE(t1);
  EXPECT_DOUBLE_EQ(t1->GetFieldAsDouble("area"), 2.0);
  EXPECT_EQ(t1->GetFieldAsInteger64("n3"), 7);
  // Circumcentre of (0,0),(4,0),(3,1) is (2,-1): R = sqrt(5).
  EXPECT_NEAR(t1->GetFieldAsDouble("R_over_f"), std::sqrt(5.0) / 2.0, 1e-12);
  EXPECT_NEAR(t1->GetFieldAsDouble("quality"), 2.0 * std::sqrt(3.0) / 7.0, 1e-12);  // edges² 16 + 2 + 10
  double min_angle = t1->GetFieldAsDouble("min_angle");
  EXPECT_NEAR(min_angle, std::atan2(1.0, 3.0) * 180 / M_PI, 1e-9);  // angle at o0
  // Node o0: nearest neighbour over triangle edges is h0 at sqrt(2); f = 1.0.
  std::unique_ptr<OGRFeature> n1(ds->GetLayerByName("nodes")->GetFeature(1));
  EXPECT_NEAR(n1->GetFieldAsDouble("conformity"), 1.0 / std::sqrt(2.0), 1e-12);
  EXPECT_EQ(n1->GetFieldAsDouble("z"), m.z[0]);
  // Repairs and metadata rows as given.
  std::unique_ptr<OGRFeature> r2(ds->GetLayerByName("repairs")->GetFeature(2));
  EXPECT_STREQ(r2->GetFieldAsString("kind"), "drop_sliver");
  EXPECT_EQ(r2->GetFieldAsInteger("part"), 5);
  EXPECT_EQ(r2->GetGeometryRef()->toPoint()->getX(), 500002.0);
  std::unique_ptr<OGRFeature> md(ds->GetLayerByName("metadata")->GetFeature(2));
  EXPECT_STREQ(md->GetFieldAsString("key"), "command_line");
  // Island chain closed in the boundaries layer.
  OGRLayer* lb = ds->GetLayerByName("boundaries");
  lb->SetAttributeFilter("kind = 'island'");
  std::unique_ptr<OGRFeature> isl(lb->GetNextFeature());
  ASSERT_TRUE(isl);
  EXPECT_EQ(isl->GetFieldAsInteger("closed"), 1);
  EXPECT_EQ(isl->GetGeometryRef()->toLineString()->getNumPoints(), 5);
  GDALClose(ds);
}

TEST_F(IoRoundTrip, GeoPackageSpatialIndexSwitch) {
  GDALAllRegister();
  for (bool with_index : {true, false}) {
    std::string p = tmp / (with_index ? "idx.gpkg" : "noidx.gpkg");
    opts.gpkg_spatial_index = with_index;
    io::write_mesh(m, p, Format::kGpkg, opts);
    GDALDataset* ds = static_cast<GDALDataset*>(GDALOpenEx(p.c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr));
    ASSERT_NE(ds, nullptr);
    OGRLayer* q = ds->ExecuteSQL("SELECT COUNT(*) FROM sqlite_master WHERE name = 'rtree_triangles_geom'", nullptr, nullptr);
    ASSERT_NE(q, nullptr);
    std::unique_ptr<OGRFeature> row(q->GetNextFeature());
    EXPECT_EQ(row->GetFieldAsInteger(0), with_index ? 1 : 0);
    ds->ReleaseResultSet(q);
    if (with_index) {
      // The index finds exactly the triangles touching a small window (o2 = (4,2) local).
      OGRLayer* lt = ds->GetLayerByName("triangles");
      lt->SetSpatialFilterRect(m.origin.x + 3.9, m.origin.y + 1.9, m.origin.x + 4.1, m.origin.y + 2.1);
      EXPECT_EQ(lt->GetFeatureCount(), 3);
    }
    GDALClose(ds);
  }
}

namespace {
// n x n grid of unit squares split into CCW triangles (a few thousand rows: a 3-level R-tree).
mesh::MeshView grid_mesh(Index n) {
  mesh::MeshView g;
  g.origin = {300000.0, 4000000.0};
  for (Index j = 0; j < n; ++j)
    for (Index i = 0; i < n; ++i) g.vertices.push_back({1.0 * i + 0.01 * (j % 3), 1.0 * j});
  for (Index j = 0; j + 1 < n; ++j)
    for (Index i = 0; i + 1 < n; ++i) {
      Index a = j * n + i;
      g.triangles.push_back({a, a + 1, a + n + 1});
      g.triangles.push_back({a, a + n + 1, a + n});
    }
  for (Index i = 0; i + 1 < n; ++i) g.edges.push_back({i, i + 1, mk(EdgeKind::kLand), 0});
  return g;
}
std::string sql_text(GDALDataset* ds, const std::string& sql) {
  OGRLayer* q = ds->ExecuteSQL(sql.c_str(), nullptr, nullptr);
  if (!q) return "<no result>";
  std::unique_ptr<OGRFeature> row(q->GetNextFeature());
  std::string r = row ? row->GetFieldAsString(0) : "<no row>";
  ds->ReleaseResultSet(q);
  return r;
}
}  // namespace

namespace {
// Every row of every table of a SQLite file (blobs as hex), table by table in name order,
// without gpkg_contents.last_change (the time of writing).
std::vector<std::string> all_rows(const std::string& path) {
  sqlite3* db = nullptr;
  std::vector<std::string> out;
  if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) return {"<cannot open>"};
  std::vector<std::string> tables;
  sqlite3_stmt* st = nullptr;
  sqlite3_prepare_v2(db, "SELECT name FROM sqlite_master WHERE type = 'table' ORDER BY name", -1, &st, nullptr);
  while (sqlite3_step(st) == SQLITE_ROW) tables.emplace_back(reinterpret_cast<const char*>(sqlite3_column_text(st, 0)));
  sqlite3_finalize(st);
  for (const std::string& t : tables) {
    // The rtree virtual tables are read through their shadow tables (_node, _parent, _rowid).
    if (t.rfind("rtree_", 0) == 0 && t.size() > 5 && t.compare(t.size() - 5, 5, "_geom") == 0) continue;
    const std::string sql = t == "gpkg_contents" ? "SELECT table_name, min_x, min_y, max_x, max_y FROM gpkg_contents"
                                                 : "SELECT * FROM \"" + t + "\"";
    sqlite3_prepare_v2(db, sql.c_str(), -1, &st, nullptr);
    while (sqlite3_step(st) == SQLITE_ROW) {
      std::string row = t + ":";
      for (int c = 0; c < sqlite3_column_count(st); ++c) {
        const auto* b = static_cast<const unsigned char*>(sqlite3_column_blob(st, c));
        const int n = sqlite3_column_bytes(st, c);
        row += '|';
        for (int k = 0; k < n; ++k) {
          char h[3];
          std::snprintf(h, sizeof h, "%02x", b[k]);
          row += h;
        }
      }
      out.push_back(std::move(row));
    }
    sqlite3_finalize(st);
  }
  sqlite3_close(db);
  return out;
}
}  // namespace

// BatchInsert writes every row with its types in order (the last partial batch through a
// statement of its own size), and a failing batch (here a UNIQUE violation) surfaces as
// kOutputError without the batches after it being written.
TEST(IoSqlite, BatchInsertSameRowsAndErrors) {
  TmpDir tmp;
  {
    const std::string p = tmp / "s.sqlite";
    {
      io::detail::SqliteDb db(p, p);
      db.exec("PRAGMA journal_mode = OFF; PRAGMA synchronous = OFF; CREATE TABLE t (k INTEGER, v REAL, b BLOB, s TEXT)");
      io::detail::BatchInsert ins(db, "t", {"k", "v", "b", "s"}, 16);
      std::string blob;
      for (int i = 0; i < 1000; ++i) {
        blob.assign(static_cast<std::size_t>(i % 7), static_cast<char>(i));
        ins.add_int(i).add_real_or_null(i % 5 ? 0.5 * i : std::nan("")).add_blob(blob.data(), blob.size());
        ins.add_text("row" + std::to_string(i));
        ins.end_row();
      }
      ins.finish();
      EXPECT_EQ(db.query_int("SELECT COUNT(*) FROM t"), 1000);
      EXPECT_EQ(db.query_int("SELECT SUM(k * rowid) FROM t"), 333333000);  // rowid = k + 1: sum of k (k + 1)
      EXPECT_EQ(db.query_int("SELECT COUNT(*) FROM t WHERE v IS NULL"), 200);
      EXPECT_EQ(db.query_int("SELECT SUM(length(b)) FROM t"), [] {
        std::int64_t n = 0;
        for (int i = 0; i < 1000; ++i) n += i % 7;
        return n;
      }());
      EXPECT_EQ(db.query_int("SELECT COUNT(*) FROM t WHERE s = 'row' || k"), 1000);
      db.exec("CREATE TABLE u (k INTEGER UNIQUE)");
      try {
        io::detail::BatchInsert bad(db, "u", {"k"}, 8);
        for (int i = 0; i < 200; ++i) {
          bad.add_int(i == 20 ? 3 : i);  // the third batch repeats 3
          bad.end_row();
        }
        bad.finish();
        ADD_FAILURE() << "duplicate accepted";
      } catch (const Error& e) {
        EXPECT_EQ(e.code(), ExitCode::kOutputError);
        EXPECT_NE(std::string(e.what()).find("cannot write rows of table 'u'"), std::string::npos) << e.what();
      }
      EXPECT_EQ(db.query_int("SELECT COUNT(*) FROM u"), 16);  // the two batches before the bad one
    }
  }
}

// FDR_THREADS=1 and 2 write the same rows in every table, the R-trees' shadow tables included,
// and files of the same size.
TEST_F(IoRoundTrip, GeoPackageSameForEveryThreadCount) {
  mesh::MeshView g = grid_mesh(90);  // 15842 triangles: three R-tree levels
  std::vector<std::string> rows[2];
  std::uintmax_t size[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    ThreadsEnv env(k + 1);
    const std::string p = tmp / ("t" + std::to_string(k + 1) + ".gpkg");
    io::write_mesh(g, p, Format::kGpkg, opts);
    rows[k] = all_rows(p);
    size[k] = fs::file_size(p);
  }
  EXPECT_GT(rows[0].size(), 3u * 15842u);
  EXPECT_TRUE(rows[0] == rows[1]);
  EXPECT_EQ(size[0], size[1]);
}

namespace {
std::string pragma_text(const std::string& path, const std::string& sql) {
  sqlite3* db = nullptr;
  if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) return "<cannot open>";
  sqlite3_stmt* st = nullptr;
  std::string r = "<no row>";
  if (sqlite3_prepare_v2(db, sql.c_str(), -1, &st, nullptr) == SQLITE_OK && sqlite3_step(st) == SQLITE_ROW)
    r = reinterpret_cast<const char*>(sqlite3_column_text(st, 0));
  sqlite3_finalize(st);
  sqlite3_close(db);
  return r;
}
}  // namespace

// Files of every size (empty triangles table, one page per table, several B-tree levels with
// 4 KiB pages, 64 KiB pages) pass SQLite's integrity and R-tree checks, hold the values given
// with their types, and are the same bytes whatever the thread count (but for the time of
// writing in gpkg_contents.last_change).
TEST_F(IoRoundTrip, GeoPackageValidAndSameBytesForEverySize) {
  struct SharedF : sizing::SizingField {
    double operator()(Point2 p) const override { return 1.5 + 0.001 * p.x; }
    bool thread_safe() const override { return true; }
    std::string describe() const override { return "shared"; }
  } shared_f;
  for (const Index n : {Index{0}, Index{5}, Index{90}, Index{140}}) {
    mesh::MeshView g = grid_mesh(std::max<Index>(n, 2));
    if (n == 0) g.triangles.clear();  // nodes without triangles: an empty table and R-tree
    g.z.assign(g.vertices.size(), 0.0);
    for (std::size_t v = 0; v < g.vertices.size(); ++v) g.z[v] = v % 5 == 0 ? std::nan("") : -3.25 * static_cast<double>(v);
    std::vector<double> area(g.triangles.size()), angle(g.triangles.size()), rf(g.triangles.size());
    for (std::size_t t = 0; t < g.triangles.size(); ++t) {
      area[t] = t % 7 == 0 ? 1.0 : 0.5;  // an integral real, which SQLite stores as an integer
      angle[t] = 45.0 + 1e-9 * static_cast<double>(t);
      rf[t] = t % 11 == 0 ? std::numeric_limits<double>::infinity() : 0.25 + 1e-6 * static_cast<double>(t);
    }
    io::WriteOptions o = opts;
    o.f = &shared_f;
    o.triangle_area = &area;
    o.triangle_min_angle = &angle;
    o.triangle_r_over_f = &rf;
    std::string files[2];
    for (int k = 0; k < 2; ++k) {
      ThreadsEnv threads(k + 1);
      files[k] = tmp / ("sized" + std::to_string(n) + "_" + std::to_string(k + 1) + ".gpkg");
      io::write_mesh(g, files[k], Format::kGpkg, o);
    }
    const std::string& p = files[1];
    EXPECT_EQ(pragma_text(p, "PRAGMA integrity_check"), "ok") << n;
    for (const char* t : {"nodes", "triangles", "boundaries", "repairs"}) {
      EXPECT_EQ(pragma_text(p, std::string("SELECT rtreecheck('rtree_") + t + "_geom')"), "ok") << n << " " << t;
      EXPECT_EQ(pragma_text(p, std::string("SELECT COUNT(*) FROM rtree_") + t + "_geom"),
                pragma_text(p, std::string("SELECT COUNT(*) FROM ") + t)) << n << " " << t;
    }
    const auto nt = static_cast<std::int64_t>(g.triangles.size()), nv = static_cast<std::int64_t>(g.vertices.size());
    EXPECT_EQ(pragma_text(p, "SELECT COUNT(*) FROM triangles WHERE fid = id AND typeof(area) = 'real'"), std::to_string(nt));
    std::int64_t unit = 0, infinite = 0;
    for (std::int64_t t = 0; t < nt; ++t) unit += t % 7 == 0, infinite += t % 11 == 0;
    EXPECT_EQ(pragma_text(p, "SELECT COUNT(*) FROM triangles WHERE area = 1.0"), std::to_string(unit)) << n;
    EXPECT_EQ(pragma_text(p, "SELECT COUNT(*) FROM triangles WHERE R_over_f IS NULL AND quality IS NOT NULL"),
              std::to_string(infinite)) << n;
    EXPECT_EQ(pragma_text(p, "SELECT COUNT(*) FROM nodes WHERE fid = id AND (z IS NULL) = ((id - 1) % 5 = 0)"),
              std::to_string(nv)) << n;
    EXPECT_EQ(pragma_text(p, "SELECT seq FROM sqlite_sequence WHERE name = 'triangles'"),
              n == 0 ? "<no row>" : std::to_string(nt));  // as SQLite: no row before the first insert
    EXPECT_EQ(pragma_text(p, "PRAGMA page_size"), nt >= 32768 ? "65536" : "4096") << n;
    EXPECT_TRUE(all_rows(files[0]) == all_rows(files[1])) << n;
    std::string bytes[2] = {slurp(files[0]), slurp(files[1])};
    for (std::string& b : bytes)
      for (std::size_t i = 0; i + 24 <= b.size(); ++i)
        if (b[i + 4] == '-' && b[i + 7] == '-' && b[i + 10] == 'T' && b[i + 13] == ':' && b[i + 16] == ':' &&
            b[i + 19] == '.' && b[i + 23] == 'Z')
          std::fill(b.begin() + static_cast<std::ptrdiff_t>(i), b.begin() + static_cast<std::ptrdiff_t>(i + 24), 'X');
    EXPECT_EQ(bytes[0].size(), bytes[1].size()) << n;
    EXPECT_TRUE(bytes[0] == bytes[1]) << n;
    // GDAL reads it back whole.
    mesh::MeshView back = io::read_mesh(p);
    EXPECT_EQ(back.num_triangles(), g.num_triangles());
    EXPECT_EQ(back.num_vertices(), g.num_vertices());
  }
}

// The Hilbert curve of the 2^16 grid starts with the 16 x 16 square at the origin, cell by
// neighbouring cell; rtree_insert_order follows it over box centres and leaves out rows
// without a box.
TEST(GpkgIndex, HilbertKeyWalksNeighbouringCells) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> at(256, {~0u, ~0u});
  for (std::uint32_t x = 0; x < 16; ++x)
    for (std::uint32_t y = 0; y < 16; ++y) {
      const std::uint32_t k = io::detail::hilbert_key(x, y);
      ASSERT_LT(k, 256u) << x << " " << y;
      EXPECT_EQ(at[k].first, ~0u) << "key " << k << " given twice";
      at[k] = {x, y};
    }
  EXPECT_EQ(io::detail::hilbert_key(0, 0), 0u);
  for (std::size_t k = 1; k < at.size(); ++k) {
    const auto dx = static_cast<int>(at[k].first) - static_cast<int>(at[k - 1].first);
    const auto dy = static_cast<int>(at[k].second) - static_cast<int>(at[k - 1].second);
    EXPECT_EQ(std::abs(dx) + std::abs(dy), 1) << "keys " << k - 1 << " and " << k;
  }
  EXPECT_EQ(io::detail::hilbert_key(65535, 0), 0xFFFFFFFFu);  // the curve ends at the other bottom corner
}

// Box centres on whole cells of the grid (the first two rows span it), so the expected order
// is the one of their Hilbert keys, rows in order on equal keys.
TEST(GpkgIndex, InsertOrderFollowsTheCurveAndSkipsEmptyRows) {
  const std::size_t n = 500;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> cell(n);
  cell[0] = {0, 65535};
  cell[1] = {65535, 0};
  std::uint32_t r = 12345;
  for (std::size_t i = 2; i < n; ++i) {
    r = r * 1103515245u + 12345u;
    const std::uint32_t x = (r >> 8) & 0xFFFF;
    cell[i] = i % 10 == 7 ? cell[i - 1] : std::make_pair(x, (x * 7919u + static_cast<std::uint32_t>(i)) & 0xFFFF);
  }
  const io::detail::BoxOf box = [&](std::size_t i, io::detail::IndexBox& b) {
    const double x = cell[i].first, y = cell[i].second;
    b = {x - 0.25, x + 0.25, y - 0.5, y + 0.5};
    return i % 5 != 3;
  };
  std::vector<std::uint32_t> want;
  for (std::uint32_t i = 0; i < n; ++i)
    if (i % 5 != 3) want.push_back(i);
  std::stable_sort(want.begin(), want.end(), [&](std::uint32_t a, std::uint32_t b) {
    return io::detail::hilbert_key(cell[a].first, cell[a].second) < io::detail::hilbert_key(cell[b].first, cell[b].second);
  });
  EXPECT_EQ(io::detail::rtree_insert_order(n, box), want);
  EXPECT_TRUE(io::detail::rtree_insert_order(0, box).empty());
  // One centre for every row: the order of the rows.
  const io::detail::BoxOf same = [](std::size_t, io::detail::IndexBox& b) {
    b = {1, 2, 3, 4};
    return true;
  };
  EXPECT_EQ(io::detail::rtree_insert_order(3, same), (std::vector<std::uint32_t>{0, 1, 2}));
}

TEST_F(IoRoundTrip, GeoPackageSpatialIndexIsValidAndMaintained) {
  mesh::MeshView g = grid_mesh(60);  // 6962 triangles, 3600 nodes
  std::string p = tmp / "grid.gpkg";
  io::write_mesh(g, p, Format::kGpkg, opts);
  GDALAllRegister();
  GDALDataset* ds = static_cast<GDALDataset*>(GDALOpenEx(p.c_str(), GDAL_OF_VECTOR | GDAL_OF_UPDATE, nullptr, nullptr, nullptr));
  ASSERT_NE(ds, nullptr);
  for (const char* t : {"nodes", "triangles", "boundaries", "repairs"}) {
    std::string rt = std::string("rtree_") + t + "_geom";
    EXPECT_EQ(sql_text(ds, "SELECT rtreecheck('" + rt + "')"), "ok") << t;
    EXPECT_EQ(sql_text(ds, "SELECT COUNT(*) FROM sqlite_master WHERE type = 'trigger' AND name LIKE '" + rt + "%'"), "6") << t;
    EXPECT_EQ(sql_text(ds, "SELECT scope FROM gpkg_extensions WHERE table_name = '" + std::string(t) +
                               "' AND extension_name = 'gpkg_rtree_index'"), "write-only") << t;
    EXPECT_EQ(sql_text(ds, "SELECT COUNT(*) FROM \"" + rt + "\""), sql_text(ds, std::string("SELECT COUNT(*) FROM ") + t)) << t;
  }
  EXPECT_EQ(sql_text(ds, "SELECT MAX(substr(hex(data), 1, 4)) FROM rtree_triangles_geom_node WHERE nodeno = 1"), "0002");  // depth 2
  // Every triangle whose envelope meets a window is found by the index (float boxes are rounded
  // outwards, so the index may add candidates but never lose one), and OGR's spatial filter gives
  // the same answer as on a copy written without an index.
  std::string p2 = tmp / "grid_noindex.gpkg";
  opts.gpkg_spatial_index = false;
  io::write_mesh(g, p2, Format::kGpkg, opts);
  GDALDataset* ds2 = static_cast<GDALDataset*>(GDALOpenEx(p2.c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr));
  ASSERT_NE(ds2, nullptr);
  OGRLayer* lt = ds->GetLayerByName("triangles");
  OGRLayer* lt2 = ds2->GetLayerByName("triangles");
  ASSERT_TRUE(lt->TestCapability(OLCFastSpatialFilter));
  EXPECT_FALSE(lt2->TestCapability(OLCFastSpatialFilter));
  for (auto [x0, y0, x1, y1] : {std::array<double, 4>{3.2, 4.1, 7.9, 9.3}, {0, 0, 0.5, 0.5}, {40.2, 10.7, 41.1, 58.2}, {-5, -5, 100, 100}}) {
    double wx0 = g.origin.x + x0, wy0 = g.origin.y + y0, wx1 = g.origin.x + x1, wy1 = g.origin.y + y1;
    std::set<long long> candidates;
    OGRLayer* q = ds->ExecuteSQL(("SELECT id FROM rtree_triangles_geom WHERE maxx >= " + std::to_string(wx0) + " AND minx <= " +
                                  std::to_string(wx1) + " AND maxy >= " + std::to_string(wy0) + " AND miny <= " + std::to_string(wy1)).c_str(),
                                 nullptr, nullptr);
    ASSERT_NE(q, nullptr);
    for (auto& f : *q) candidates.insert(f->GetFieldAsInteger64(0));
    ds->ReleaseResultSet(q);
    long brute = 0;
    for (std::size_t t = 0; t < g.num_triangles(); ++t) {
      Box2 b;
      for (Index v : g.triangles[t]) b.add(g.world(v));
      if (b.lo.x <= wx1 && b.hi.x >= wx0 && b.lo.y <= wy1 && b.hi.y >= wy0) {
        ++brute;
        EXPECT_TRUE(candidates.count(static_cast<long long>(t + 1))) << "triangle " << t << " missing from the index";
      }
    }
    EXPECT_GT(brute, 0);
    lt->SetSpatialFilterRect(wx0, wy0, wx1, wy1);
    lt2->SetSpatialFilterRect(wx0, wy0, wx1, wy1);
    EXPECT_EQ(lt->GetFeatureCount(), lt2->GetFeatureCount()) << x0 << " " << y0;
  }
  GDALClose(ds2);
  lt->SetSpatialFilter(nullptr);
  // The maintenance triggers keep the index up to date on edits.
  OGRLayer* lr = ds->GetLayerByName("repairs");
  OGRFeature nf(lr->GetLayerDefn());
  nf.SetField("kind", "manual");
  nf.SetGeometryDirectly(new OGRPoint(g.origin.x + 1000, g.origin.y + 1000));
  ASSERT_EQ(lr->CreateFeature(&nf), OGRERR_NONE);
  ASSERT_EQ(lt->DeleteFeature(1), OGRERR_NONE);
  EXPECT_EQ(sql_text(ds, "SELECT COUNT(*) FROM rtree_repairs_geom WHERE id = " + std::to_string(nf.GetFID()) +
                             " AND minx > " + std::to_string(g.origin.x + 999)), "1");
  EXPECT_EQ(sql_text(ds, "SELECT COUNT(*) FROM rtree_triangles_geom WHERE id = 1"), "0");
  EXPECT_EQ(sql_text(ds, "SELECT rtreecheck('rtree_triangles_geom')"), "ok");
  GDALClose(ds);
}

// GDAL's own GeoPackage validator accepts the file (tables, triggers, extensions, R-tree).
TEST_F(IoRoundTrip, GeoPackagePassesGdalValidator) {
  const char* validator = "/usr/lib/python3/dist-packages/osgeo_utils/samples/validate_gpkg.py";
  if (::access(validator, R_OK) != 0) GTEST_SKIP() << "validate_gpkg.py not installed";
  std::string p = tmp / "valid.gpkg", log = tmp / "validate.log";
  io::write_mesh(grid_mesh(12), p, Format::kGpkg, opts);
  int rc = std::system(("/usr/bin/python3 " + std::string(validator) + " " + p + " > " + log + " 2>&1").c_str());
  EXPECT_EQ(rc, 0) << slurp(log);
  // With an EPSG CRS, repairs and metadata rows (the SQLite writer builds every table itself).
  std::string p2 = tmp / "valid_crs.gpkg";
  ASSERT_FALSE(m.crs_wkt.empty());
  ASSERT_FALSE(opts.repairs.empty());
  io::write_mesh(m, p2, Format::kGpkg, opts);
  rc = std::system(("/usr/bin/python3 " + std::string(validator) + " " + p2 + " > " + log + " 2>&1").c_str());
  EXPECT_EQ(rc, 0) << slurp(log);
  // And a CRS without an authority code (stored as a custom srs_id).
  mesh::MeshView custom = m;
  custom.crs_wkt = "+proj=tmerc +lat_0=43.3 +lon_0=-67.25 +k=1 +x_0=0 +y_0=0 +datum=WGS84 +units=m +no_defs";
  std::string p3 = tmp / "valid_custom.gpkg";
  io::write_mesh(custom, p3, Format::kGpkg, opts);
  rc = std::system(("/usr/bin/python3 " + std::string(validator) + " " + p3 + " > " + log + " 2>&1").c_str());
  EXPECT_EQ(rc, 0) << slurp(log);
  mesh::MeshView back = io::read_mesh(p3);
  OGRSpatialReference a, b;
  a.SetFromUserInput(custom.crs_wkt.c_str());
  b.SetFromUserInput(back.crs_wkt.c_str());
  EXPECT_TRUE(a.IsSame(&b)) << back.crs_wkt;
}

// Large meshes get SQLite's largest pages (64 KiB: fewer B-tree balances and file writes); the
// file stays valid for GDAL, reads back whole, and its R-tree answers window queries exactly.
TEST_F(IoRoundTrip, LargeGeoPackageHas64KiBPagesAndStaysValid) {
  const mesh::MeshView big = grid_mesh(130);  // 2 x 129^2 = 33 282 triangles
  ASSERT_GE(big.triangles.size(), 32768u);
  const std::string p = tmp / "big.gpkg", small = tmp / "small.gpkg", log = tmp / "validate_big.log";
  io::write_mesh(big, p, Format::kGpkg, opts);
  io::write_mesh(grid_mesh(12), small, Format::kGpkg, opts);
  auto page_size = [](const std::string& path) {
    sqlite3* db = nullptr;
    sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr);
    sqlite3_stmt* st = nullptr;
    sqlite3_prepare_v2(db, "PRAGMA page_size", -1, &st, nullptr);
    const int v = sqlite3_step(st) == SQLITE_ROW ? sqlite3_column_int(st, 0) : -1;
    sqlite3_finalize(st);
    sqlite3_close(db);
    return v;
  };
  EXPECT_EQ(page_size(p), 65536);
  EXPECT_EQ(page_size(small), 4096);
  const char* validator = "/usr/lib/python3/dist-packages/osgeo_utils/samples/validate_gpkg.py";
  if (::access(validator, R_OK) == 0) {
    const int rc = std::system(("/usr/bin/python3 " + std::string(validator) + " " + p + " > " + log + " 2>&1").c_str());
    EXPECT_EQ(rc, 0) << slurp(log);
  }
  const mesh::MeshView back = io::read_mesh(p);
  EXPECT_EQ(back.triangles.size(), big.triangles.size());
  EXPECT_EQ(back.vertices.size(), big.vertices.size());
  // Triangles inside a window, by the R-tree and by brute force over the mesh (world coordinates).
  GDALDataset* ds = static_cast<GDALDataset*>(GDALOpenEx(p.c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr));
  ASSERT_NE(ds, nullptr);
  const double x0 = big.origin.x + 40.5, x1 = big.origin.x + 60.5, y0 = big.origin.y + 70.5, y1 = big.origin.y + 90.5;
  std::ostringstream q;
  q.precision(17);
  q << "SELECT COUNT(*) FROM rtree_triangles_geom WHERE minx >= " << x0 << " AND maxx <= " << x1 << " AND miny >= " << y0
    << " AND maxy <= " << y1;
  std::size_t expect = 0;
  for (const auto& t : big.triangles) {
    bool in = true;
    for (Index v : t) {
      const Point2 w = big.world(v);
      in = in && w.x >= x0 && w.x <= x1 && w.y >= y0 && w.y <= y1;
    }
    expect += in;
  }
  EXPECT_GT(expect, 0u);
  EXPECT_EQ(sql_text(ds, q.str()), std::to_string(expect));
  GDALClose(ds);
}

TEST_F(IoRoundTrip, GeoPackageWithoutSizingHasNullQuality) {
  std::string p = tmp / "plain.gpkg";
  mesh::MeshView plain = m;
  plain.f.clear();
  plain.z.clear();
  plain.crs_wkt.clear();
  io::write_mesh(plain, p, Format::kGpkg, {});
  GDALAllRegister();
  GDALDataset* ds = static_cast<GDALDataset*>(GDALOpenEx(p.c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr));
  ASSERT_NE(ds, nullptr);
  std::unique_ptr<OGRFeature> t(ds->GetLayerByName("triangles")->GetFeature(1));
  EXPECT_TRUE(t->IsFieldNull(t->GetFieldIndex("R_over_f")));
  EXPECT_FALSE(t->IsFieldNull(t->GetFieldIndex("min_angle")));
  std::unique_ptr<OGRFeature> n(ds->GetLayerByName("nodes")->GetFeature(1));
  EXPECT_TRUE(n->IsFieldNull(n->GetFieldIndex("z")));
  EXPECT_TRUE(n->IsFieldNull(n->GetFieldIndex("conformity")));
  {
    OGRLayer* q = ds->ExecuteSQL("SELECT srs_id FROM gpkg_contents WHERE table_name = 'nodes'", nullptr, nullptr);
    ASSERT_NE(q, nullptr);
    std::unique_ptr<OGRFeature> row(q->GetNextFeature());
    EXPECT_EQ(row->GetFieldAsInteger(0), -1);  // undefined Cartesian SRS
    ds->ReleaseResultSet(q);
  }
  GDALClose(ds);
  mesh::MeshView r = io::read_mesh(p);
  expect_same_geometry(plain, r, false);
  EXPECT_TRUE(r.z.empty());
  EXPECT_TRUE(r.crs_wkt.empty());
}


// Packing: full nodes of `cap` cells level by level (the last of a level may hold fewer), each
// cell one level up numbered in creation order from 2 and holding the union of its node's boxes,
// and rows without a box left out.
TEST(GpkgIndex, PackedTreeLevelsAndBoxes) {
  const std::size_t n = 100, cap = 4;
  const io::detail::BoxOf box = [](std::size_t i, io::detail::IndexBox& b) {
    const double x = static_cast<double>(i % 10) + 0.1, y = static_cast<double>(i / 10) + 0.2;
    b = {x, x + 0.5, y, y + 0.25};
    return i != 42;
  };
  const io::detail::PackedRtree t = io::detail::pack_rtree(n, box, cap);
  ASSERT_EQ(t.levels.size(), 4u);  // 99 cells: 25 leaves, 7 nodes, 2 nodes, the root's 2 cells
  EXPECT_EQ(t.levels[0].size(), 99u);
  EXPECT_EQ(t.levels[1].size(), 25u);
  EXPECT_EQ(t.levels[2].size(), 7u);
  EXPECT_EQ(t.levels[3].size(), 2u);
  const std::vector<std::uint32_t> order = io::detail::rtree_insert_order(n, box);
  std::uint32_t next_no = 2;
  for (std::size_t l = 0; l + 1 < t.levels.size(); ++l)
    for (std::size_t j = 0; j * cap < t.levels[l].size(); ++j) {
      const io::detail::RtreeCell& up = t.levels[l + 1][j];
      EXPECT_EQ(up.id, next_no++);
      for (std::size_t k = j * cap; k < std::min(t.levels[l].size(), (j + 1) * cap); ++k) {
        const io::detail::RtreeCell& c = t.levels[l][k];
        EXPECT_TRUE(up.box[0] <= c.box[0] && up.box[1] >= c.box[1] && up.box[2] <= c.box[2] && up.box[3] >= c.box[3]);
        if (l == 0) {
          EXPECT_EQ(c.id, order[k] + 1);
        }
      }
    }
  // Leaf boxes contain the doubles they stand for (rounded outwards).
  for (std::size_t k = 0; k < order.size(); ++k) {
    io::detail::IndexBox b{};
    box(order[k], b);
    const io::detail::RtreeCell& c = t.levels[0][k];
    EXPECT_TRUE(c.box[0] <= b.minx && c.box[1] >= b.maxx && c.box[2] <= b.miny && c.box[3] >= b.maxy) << k;
  }
  EXPECT_TRUE(io::detail::pack_rtree(0, box, cap).levels.empty());
  EXPECT_EQ(io::detail::pack_rtree(3, box, cap).levels.size(), 1u);  // a leaf root
}
