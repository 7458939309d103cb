// Tests for the io writers/readers: round trips for every format, GDAL/netCDF/gmsh cross-checks, atomic writes.
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

namespace fs = std::filesystem;
using namespace fdr;
using fdr::io::Format;
using mesh::EdgeKind;

namespace {

class ConstantF : public sizing::SizingField {
 public:
  explicit ConstantF(double v) : v_(v) {}
  double operator()(Point2) const override { return v_; }
  std::string describe() const override { return "constant"; }

 private:
  double v_;
};

std::int32_t mk(EdgeKind k) { return static_cast<std::int32_t>(k); }

// A 4x4 square with a 2x2 island hole, an open right side (with a midpoint) and one breakline:
//
//   o4 ------------- o3
//   |  h3 ------ h2 / |
//   |   |  hole  |    o2   (o1-o2-o3: open boundary)
//   |  h0 ------ h1   |
//   o0 ------------- o1     breakline o0-h0
mesh::MeshView sample_mesh() {
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

io::WriteOptions sample_options(const sizing::SizingField* f) {
  io::WriteOptions o;
  o.f = f;
  o.bound_B = 1.5;
  o.title = "io test mesh";
  o.metadata = {{"version", "0.1.0"}, {"command_line", "fdrmesh mesh -i a.gpkg -o b.gpkg"}, {"quality", "{\"n\":9}"}};
  o.repairs = {{"snap", 500001.0, 6400001.0, 0.01, "vertices closer than tolerance", 0},
               {"drop_sliver", 500002.0, 6400002.0, 1e-4, "sliver ring area below threshold", 5}};
  return o;
}

struct TmpDir {
  fs::path dir;
  TmpDir() {
    std::string t = (fs::temp_directory_path() / "fdr_io_test_XXXXXX").string();
    dir = ::mkdtemp(t.data());
  }
  ~TmpDir() {
    std::error_code ec;
    fs::permissions(dir, fs::perms::owner_all, fs::perm_options::add, ec);
    fs::remove_all(dir, ec);
  }
  std::string operator/(const std::string& name) const { return (dir / name).string(); }
  std::vector<std::string> entries() const {
    std::vector<std::string> r;
    for (auto& e : fs::directory_iterator(dir)) r.push_back(e.path().filename().string());
    std::sort(r.begin(), r.end());
    return r;
  }
};

bool has_temp_leftover(const TmpDir& d) {
  for (const auto& n : d.entries())
    if (n.find(".tmp-") != std::string::npos) return true;
  return false;
}

std::string slurp(const std::string& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

using EdgeSet = std::set<std::tuple<Index, Index, std::int32_t>>;
EdgeSet edge_set(const mesh::MeshView& m, std::set<std::int32_t> kinds) {
  EdgeSet s;
  for (const auto& e : m.edges)
    if (kinds.count(e.marker)) s.insert({std::min(e.a, e.b), std::max(e.a, e.b), e.marker});
  return s;
}

// World coordinates, z and triangles must read back bit-exactly and in the same order.
void expect_same_geometry(const mesh::MeshView& a, const mesh::MeshView& b, bool check_z = true) {
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

}  // namespace

// ---------------------------------------------------------------- format selection

TEST(IoFormatFromPath, Extensions) {
  EXPECT_EQ(io::format_from_path("out/mesh.gpkg"), Format::kGpkg);
  EXPECT_EQ(io::format_from_path("mesh.GPKG"), Format::kGpkg);
  EXPECT_EQ(io::format_from_path("a.b/mesh.2dm"), Format::k2dm);
  EXPECT_EQ(io::format_from_path("mesh.msh"), Format::kMsh);
  EXPECT_EQ(io::format_from_path("mesh.node"), Format::kNode);
  EXPECT_EQ(io::format_from_path("mesh.ele"), Format::kNode);
  EXPECT_EQ(io::format_from_path("mesh.vtu"), Format::kVtu);
  EXPECT_EQ(io::format_from_path("mesh.14"), Format::kFort14);
  EXPECT_EQ(io::format_from_path("mesh.grd"), Format::kFort14);
  EXPECT_EQ(io::format_from_path("run/fort.14"), Format::kFort14);
  EXPECT_EQ(io::format_from_path("FORT.14"), Format::kFort14);
  EXPECT_EQ(io::format_from_path("mesh.nc"), Format::kUgrid);
}

TEST(IoFormatFromPath, OverrideIsCaseInsensitive) {
  EXPECT_EQ(io::format_from_path("x.gpkg", "2dm"), Format::k2dm);
  EXPECT_EQ(io::format_from_path("x", "GPKG"), Format::kGpkg);
  EXPECT_EQ(io::format_from_path("x", "msh"), Format::kMsh);
  EXPECT_EQ(io::format_from_path("x", "Node"), Format::kNode);
  EXPECT_EQ(io::format_from_path("x", "vtu"), Format::kVtu);
  EXPECT_EQ(io::format_from_path("x", "fort14"), Format::kFort14);
  EXPECT_EQ(io::format_from_path("x", "ugrid"), Format::kUgrid);
  for (Format f : {Format::kGpkg, Format::k2dm, Format::kMsh, Format::kNode, Format::kVtu, Format::kFort14, Format::kUgrid})
    EXPECT_EQ(io::format_from_path("x", io::format_name(f)), f);
}

TEST(IoFormatFromPath, UnknownIsUsageErrorListingFormats) {
  for (auto [path, of] : {std::pair<std::string, std::string>{"mesh.shp", ""}, {"mesh", ""}, {"mesh.gpkg", "shapefile"}}) {
    try {
      io::format_from_path(path, of);
      FAIL() << path << " / " << of;
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ExitCode::kUsage);
      std::string msg = e.what();
      for (const char* name : {"GPKG", "2DM", "MSH", "NODE", "VTU", "FORT14", "UGRID"})
        EXPECT_NE(msg.find(name), std::string::npos) << msg;
    }
  }
}

// ---------------------------------------------------------------- chains

TEST(IoChains, OrderedOrientedAndDeterministic) {
  mesh::MeshView m = sample_mesh();
  auto chains = io::detail::build_chains(m);
  ASSERT_EQ(chains.size(), 4u);
  // Sorted by (marker, part): land, island, open, breakline.
  EXPECT_EQ(chains[0].marker, mk(EdgeKind::kLand));
  EXPECT_FALSE(chains[0].closed);
  // Outer boundary counter-clockwise: o3 -> o4 -> o0 -> o1.
  EXPECT_EQ(chains[0].nodes, (std::vector<Index>{3, 4, 0, 1}));
  EXPECT_EQ(chains[1].marker, mk(EdgeKind::kIsland));
  EXPECT_TRUE(chains[1].closed);
  ASSERT_EQ(chains[1].nodes.size(), 4u);
  // Island ring runs clockwise (mesh on its left): negative signed area.
  double a2 = 0;
  for (std::size_t i = 0; i < 4; ++i) {
    Point2 p = m.vertices[chains[1].nodes[i]], q = m.vertices[chains[1].nodes[(i + 1) % 4]];
    a2 += p.x * q.y - q.x * p.y;
  }
  EXPECT_LT(a2, 0);
  EXPECT_EQ(chains[2].marker, mk(EdgeKind::kOpen));
  EXPECT_EQ(chains[2].nodes, (std::vector<Index>{1, 2, 3}));
  EXPECT_EQ(chains[3].marker, mk(EdgeKind::kBreakline));
  EXPECT_EQ(chains[3].nodes, (std::vector<Index>{0, 5}));  // stored direction of an interior edge
  // Deterministic: same input, same chains.
  auto again = io::detail::build_chains(m);
  for (std::size_t i = 0; i < chains.size(); ++i) EXPECT_EQ(chains[i].nodes, again[i].nodes);
}

TEST(IoChains, BranchesAndSplitPartsCoverEveryEdgeOnce) {
  // Grid 5x5 vertices (id = 5j + i); part 7 holds a T-shaped breakline plus a separate piece,
  // part 8 a ring; edges in scrambled order.
  mesh::MeshView m;
  for (Index j = 0; j < 5; ++j)
    for (Index i = 0; i < 5; ++i) m.vertices.push_back({double(i), double(j)});
  for (Index j = 0; j < 4; ++j)
    for (Index i = 0; i < 4; ++i) {
      Index a = 5 * j + i;
      m.triangles.push_back({a, a + 1, a + 6});
      m.triangles.push_back({a, a + 6, a + 5});
    }
  const std::int32_t bl = mk(EdgeKind::kBreakline);
  m.edges = {{11, 12, bl, 7}, {6, 11, bl, 7}, {12, 13, bl, 7}, {12, 17, bl, 7}, {3, 4, bl, 7},
             {6, 7, 1, 8},   {12, 7, 1, 8},  {11, 12, 1, 8},  {6, 11, 1, 8},  {16, 17, bl, 7}};
  auto chains = io::detail::build_chains(m);
  std::multiset<std::tuple<Index, Index, std::int32_t, std::int32_t>> seen, want;
  for (const auto& e : m.edges) want.insert({std::min(e.a, e.b), std::max(e.a, e.b), e.marker, e.part});
  for (const auto& c : chains) {
    ASSERT_GE(c.nodes.size(), 2u);
    std::size_t k = c.nodes.size();
    for (std::size_t s = 0; s < (c.closed ? k : k - 1); ++s) {
      Index a = c.nodes[s], b = c.nodes[(s + 1) % k];
      seen.insert({std::min(a, b), std::max(a, b), c.marker, c.part});
    }
  }
  EXPECT_EQ(seen, want);
  // The ring is one closed chain; the breakline part needs several open chains.
  int rings = 0, paths = 0;
  for (const auto& c : chains) (c.closed ? rings : paths) += 1;
  EXPECT_EQ(rings, 1);
  EXPECT_GE(paths, 3);
}

// ---------------------------------------------------------------- round trips

class IoRoundTrip : public ::testing::Test {
 protected:
  TmpDir tmp;
  mesh::MeshView m = sample_mesh();
  ConstantF f{2.0};
  io::WriteOptions opts = sample_options(&f);
};

TEST_F(IoRoundTrip, Sms2dm) {
  std::string p = tmp / "mesh.2dm";
  io::write_mesh(m, p, io::format_from_path(p), opts);
  std::string text = slurp(p);
  EXPECT_EQ(text.rfind("MESH2D\n", 0), 0u);
  EXPECT_NE(text.find("MESHNAME \"io test mesh\""), std::string::npos);
  // One nodestring per boundary run (io/boundaries.hpp), 1-based: the open run o1 o2 o3 first,
  // then the land run o3 o4 o0 o1, then the island h0 h3 h2 h1 (clockwise) split in two, since
  // SMS refuses a nodestring that starts and ends on the same node.
  EXPECT_NE(text.find("NS 2 3 -4\nNS 4 5 1 -2\nNS 6 9 -8\nNS 8 7 -6\n"), std::string::npos) << text;
  mesh::MeshView r = io::read_mesh(p);
  expect_same_geometry(m, r);
  // 2DM nodestrings carry no kind: the reader marks them all open; together they cover every
  // boundary edge.
  EdgeSet want;
  for (const auto& e : m.edges)
    if (e.marker != mk(EdgeKind::kBreakline)) want.insert({std::min(e.a, e.b), std::max(e.a, e.b), mk(EdgeKind::kOpen)});
  EXPECT_EQ(edge_set(r, {mk(EdgeKind::kOpen)}), want);
  EXPECT_EQ(r.edges.size(), 9u);
  EXPECT_EQ(tmp.entries(), std::vector<std::string>{"mesh.2dm"});
}

TEST_F(IoRoundTrip, Fort14) {
  std::string p = tmp / "fort.14";
  io::write_mesh(m, p, io::format_from_path(p), opts);
  std::string text = slurp(p);
  // Depth positive down: node 1 has z = -0.1 - 1/3, so DP = 0.1 + 1/3.
  std::istringstream ss(text);
  std::string title, line;
  std::getline(ss, title);
  EXPECT_EQ(title, "io test mesh");
  long ne, np;
  ss >> ne >> np;
  EXPECT_EQ(ne, 9);
  EXPECT_EQ(np, 9);
  std::getline(ss, line);
  long id;
  double x, y, dp;
  ss >> id >> x >> y >> dp;
  EXPECT_EQ(id, 1);
  EXPECT_EQ(dp, -m.z[0]);
  EXPECT_NE(text.find("1 = Number of open boundaries\n3 = Total number of open boundary nodes\n3 0 = "), std::string::npos) << text;
  // Land chain of 4 nodes (mainland, 0) and the island ring closed by repeating its first node (1).
  EXPECT_NE(text.find("2 = Number of land boundaries\n9 = Total number of land boundary nodes\n4 0 = "), std::string::npos) << text;
  EXPECT_NE(text.find("5 1 = Number of nodes for land boundary 2"), std::string::npos) << text;

  mesh::MeshView r = io::read_mesh(p);
  expect_same_geometry(m, r);
  std::set<std::int32_t> kinds{mk(EdgeKind::kLand), mk(EdgeKind::kIsland), mk(EdgeKind::kOpen)};
  EXPECT_EQ(edge_set(r, kinds), edge_set(m, kinds));
  EXPECT_EQ(r.edges.size(), 9u);  // the breakline is not an ADCIRC boundary

  // Depth convention switch: DP = z written and read back unchanged.
  opts.fort14_depth_positive_down = false;
  io::write_mesh(m, p, Format::kFort14, opts);
  io::ReadOptions ro;
  ro.fort14_depth_positive_down = false;
  expect_same_geometry(m, io::read_mesh(p, ro));
  mesh::MeshView neg = io::read_mesh(p);
  for (std::size_t v = 0; v < m.z.size(); ++v) EXPECT_EQ(neg.z[v], -m.z[v]);
}

TEST_F(IoRoundTrip, GmshMsh) {
  std::string p = tmp / "mesh.msh";
  io::write_mesh(m, p, io::format_from_path(p), opts);
  std::string text = slurp(p);
  EXPECT_EQ(text.rfind("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n", 0), 0u);
  for (const char* name : {"1 1 \"land\"", "1 2 \"island\"", "1 3 \"open\"", "1 4 \"breakline\"", "2 10 \"domain\""})
    EXPECT_NE(text.find(name), std::string::npos) << name;
  mesh::MeshView r = io::read_mesh(p);
  expect_same_geometry(m, r);
  std::set<std::int32_t> kinds{mk(EdgeKind::kLand), mk(EdgeKind::kIsland), mk(EdgeKind::kOpen), mk(EdgeKind::kBreakline)};
  EXPECT_EQ(edge_set(r, kinds), edge_set(m, kinds));
  EXPECT_EQ(r.edges.size(), m.edges.size());
}

TEST_F(IoRoundTrip, GmshLoadsMsh) {
  if (::access("/usr/bin/gmsh", X_OK) != 0) GTEST_SKIP() << "gmsh binary not installed";
  std::string p = tmp / "mesh.msh", out = tmp / "out.msh";
  io::write_mesh(m, p, Format::kMsh, opts);
  std::string cmd = "/usr/bin/gmsh " + p + " -0 -format msh41 -o " + out + " > " + (tmp / "gmsh.log") + " 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << slurp(tmp / "gmsh.log");
  std::string log = slurp(tmp / "gmsh.log");
  EXPECT_EQ(log.find("Error"), std::string::npos) << log;
  // gmsh's own re-export reads back with the same geometry and boundary kinds.
  mesh::MeshView r = io::read_mesh(out);
  EXPECT_EQ(r.num_vertices(), m.num_vertices());
  EXPECT_EQ(r.num_triangles(), m.num_triangles());
  std::set<std::int32_t> kinds{mk(EdgeKind::kLand), mk(EdgeKind::kIsland), mk(EdgeKind::kOpen), mk(EdgeKind::kBreakline)};
  EXPECT_EQ(edge_set(r, kinds).size(), edge_set(m, kinds).size());
}

TEST_F(IoRoundTrip, TriangleNodeEle) {
  std::string p = tmp / "mesh.ele";
  io::write_mesh(m, p, io::format_from_path(p), opts);
  EXPECT_EQ(tmp.entries(), (std::vector<std::string>{"mesh.ele", "mesh.node"}));
  mesh::MeshView r = io::read_mesh(tmp / "mesh.node");
  expect_same_geometry(m, r);
  ASSERT_EQ(r.f.size(), m.f.size());
  for (std::size_t v = 0; v < m.f.size(); ++v) EXPECT_EQ(r.f[v], m.f[v]);
  // Boundary markers: largest edge marker at the vertex (o0 has land and breakline -> 4).
  ASSERT_EQ(r.vertex_marker.size(), 9u);
  EXPECT_EQ(r.vertex_marker[0], mk(EdgeKind::kBreakline));
  EXPECT_EQ(r.vertex_marker[2], mk(EdgeKind::kOpen));
  EXPECT_EQ(r.vertex_marker[7], mk(EdgeKind::kIsland));
  EXPECT_EQ(r.vertex_marker[4], mk(EdgeKind::kLand));
}

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

TEST_F(IoRoundTrip, Ugrid) {
  std::string p = tmp / "mesh.nc";
  io::write_mesh(m, p, io::format_from_path(p), opts);
  int nc;
  ASSERT_EQ(nc_open(p.c_str(), NC_NOWRITE, &nc), NC_NOERR);
  auto att = [&](int var, const char* name) {
    size_t len = 0;
    if (nc_inq_attlen(nc, var, name, &len) != NC_NOERR) return std::string("<missing>");
    std::string s(len, '\0');
    nc_get_att_text(nc, var, name, s.data());
    return s;
  };
  auto var = [&](const char* name) {
    int v = -1;
    EXPECT_EQ(nc_inq_varid(nc, name, &v), NC_NOERR) << name;
    return v;
  };
  EXPECT_EQ(att(NC_GLOBAL, "Conventions"), "CF-1.8 UGRID-1.0");
  int mesh = var("mesh2d");
  EXPECT_EQ(att(mesh, "cf_role"), "mesh_topology");
  int td = 0;
  EXPECT_EQ(nc_get_att_int(nc, mesh, "topology_dimension", &td), NC_NOERR);
  EXPECT_EQ(td, 2);
  EXPECT_EQ(att(mesh, "node_coordinates"), "mesh2d_node_x mesh2d_node_y");
  EXPECT_EQ(att(mesh, "face_node_connectivity"), "mesh2d_face_nodes");
  EXPECT_EQ(att(mesh, "edge_node_connectivity"), "mesh2d_edge_nodes");
  int vx = var("mesh2d_node_x"), vy = var("mesh2d_node_y"), vz = var("mesh2d_node_z");
  EXPECT_EQ(att(vx, "standard_name"), "projection_x_coordinate");
  EXPECT_EQ(att(vy, "standard_name"), "projection_y_coordinate");
  EXPECT_EQ(att(vx, "grid_mapping"), "crs");
  EXPECT_EQ(att(vz, "location"), "node");
  int crs = var("crs");
  int epsg = 0;
  EXPECT_EQ(nc_get_att_int(nc, crs, "epsg", &epsg), NC_NOERR);
  EXPECT_EQ(epsg, 32633);
  EXPECT_NE(att(crs, "crs_wkt").find("UTM zone 33N"), std::string::npos);
  EXPECT_NE(att(crs, "spatial_ref").find("UTM zone 33N"), std::string::npos);
  EXPECT_NE(att(crs, "wkt").find("UTM zone 33N"), std::string::npos);
  int faces = var("mesh2d_face_nodes");
  int start = -1;
  EXPECT_EQ(nc_get_att_int(nc, faces, "start_index", &start), NC_NOERR);
  EXPECT_EQ(start, 0);
  std::vector<double> x(9), y(9), z(9);
  nc_get_var_double(nc, vx, x.data());
  nc_get_var_double(nc, vy, y.data());
  nc_get_var_double(nc, vz, z.data());
  for (Index v = 0; v < 9; ++v) {
    EXPECT_EQ(x[v], m.world(v).x);
    EXPECT_EQ(y[v], m.world(v).y);
    EXPECT_EQ(z[v], m.z[v]);
  }
  std::vector<int> fn(27);
  nc_get_var_int(nc, faces, fn.data());
  for (std::size_t t = 0; t < 9; ++t)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(static_cast<Index>(fn[3 * t + k]), m.triangles[t][k]);
  int dim_edge;
  size_t ne = 0;
  ASSERT_EQ(nc_inq_dimid(nc, "nmesh2d_edge", &dim_edge), NC_NOERR);
  nc_inq_dimlen(nc, dim_edge, &ne);
  EXPECT_EQ(ne, m.edges.size());
  std::vector<int> kind(ne);
  nc_get_var_int(nc, var("mesh2d_edge_kind"), kind.data());
  for (std::size_t e = 0; e < ne; ++e) EXPECT_EQ(kind[e], m.edges[e].marker);
  EXPECT_EQ(att(NC_GLOBAL, "fdrmesh_command_line"), "fdrmesh mesh -i a.gpkg -o b.gpkg");
  nc_close(nc);
}

TEST_F(IoRoundTrip, UgridGeographicUsesLonLat) {
  std::string p = tmp / "geo.nc";
  OGRSpatialReference srs;
  srs.importFromEPSG(4326);
  char* wkt = nullptr;
  srs.exportToWkt(&wkt);
  m.crs_wkt = wkt;
  CPLFree(wkt);
  m.origin = {10.5, 59.25};
  for (auto& v : m.vertices) v = 0.01 * v;
  io::write_mesh(m, p, Format::kUgrid, {});
  int nc, vx, crs, epsg = 0;
  ASSERT_EQ(nc_open(p.c_str(), NC_NOWRITE, &nc), NC_NOERR);
  ASSERT_EQ(nc_inq_varid(nc, "mesh2d_node_x", &vx), NC_NOERR);
  char buf[64] = {0};
  nc_get_att_text(nc, vx, "standard_name", buf);
  EXPECT_STREQ(buf, "longitude");
  ASSERT_EQ(nc_inq_varid(nc, "crs", &crs), NC_NOERR);
  nc_get_att_int(nc, crs, "epsg", &epsg);
  EXPECT_EQ(epsg, 4326);
  nc_close(nc);
}

TEST_F(IoRoundTrip, Vtu) {
  std::string p = tmp / "mesh.vtu";
  io::write_mesh(m, p, io::format_from_path(p), opts);
  std::string text = slurp(p);
  EXPECT_NE(text.find("NumberOfPoints=\"9\" NumberOfCells=\"9\""), std::string::npos);
  for (const char* name : {"Name=\"z\"", "Name=\"f\"", "Name=\"min_angle\"", "Name=\"R_over_f\"", "Name=\"connectivity\""})
    EXPECT_NE(text.find(name), std::string::npos) << name;
  // Cell types: nine VTK_TRIANGLE (5) values.
  auto types = text.find("Name=\"types\"");
  ASSERT_NE(types, std::string::npos);
  std::istringstream ss(text.substr(text.find('\n', types) + 1));
  int t, count = 0;
  while (ss >> t) {
    EXPECT_EQ(t, 5);
    ++count;
  }
  EXPECT_EQ(count, 9);
  // Points read back bit-exactly.
  auto pts = text.find("NumberOfComponents=\"3\"");
  std::istringstream ps(text.substr(text.find('\n', pts) + 1));
  for (Index v = 0; v < 9; ++v) {
    double x, y, z;
    ps >> x >> y >> z;
    EXPECT_EQ(x, m.world(v).x);
    EXPECT_EQ(y, m.world(v).y);
  }
  // Without a sizing field there is no R_over_f column.
  io::write_mesh(m, p, Format::kVtu, {});
  EXPECT_EQ(slurp(p).find("R_over_f"), std::string::npos);
}

TEST_F(IoRoundTrip, ExistingFileIsReplaced) {
  std::string p = tmp / "mesh.2dm";
  { std::ofstream(p) << "old content\n"; }
  io::write_mesh(m, p, Format::k2dm, opts);
  EXPECT_EQ(slurp(p).rfind("MESH2D", 0), 0u);
  EXPECT_FALSE(has_temp_leftover(tmp));
}

// ---------------------------------------------------------------- failures leave nothing behind

namespace {
constexpr Format kEvery[] = {Format::kGpkg, Format::k2dm,   Format::kMsh, Format::kNode,   Format::kVtu, Format::kFort14,
                             Format::kUgrid, Format::kSelafin, Format::kGr3, Format::kLl, Format::kDflowfm};
std::string ext_of(Format f) {
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
void expect_output_error(const std::function<void()>& fn, const std::string& path_in_message) {
  try {
    fn();
    ADD_FAILURE() << "no error for " << path_in_message;
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kOutputError) << e.what();
    EXPECT_EQ(std::string(e.what()).rfind(path_in_message + ": ", 0), 0u) << e.what();
  }
}
}  // namespace

TEST_F(IoRoundTrip, MissingFolderIsOutputError) {
  for (Format f : kEvery) {
    std::string p = tmp / ("no_such_dir/mesh" + ext_of(f));
    expect_output_error([&] { io::write_mesh(m, p, f, opts); }, f == Format::kNode ? tmp / "no_such_dir/mesh.node" : p);
  }
  EXPECT_TRUE(tmp.entries().empty());
}

TEST_F(IoRoundTrip, ReadOnlyLocationIsOutputError) {
  std::string dir;
  if (::geteuid() == 0) {
    dir = "/proc";  // root ignores permission bits; /proc refuses new files for everyone
  } else {
    dir = tmp / "ro";
    fs::create_directory(dir);
    fs::permissions(dir, fs::perms::owner_read | fs::perms::owner_exec);
  }
  for (Format f : kEvery) {
    std::string p = dir + "/fdr_io_test_mesh" + ext_of(f);
    expect_output_error([&] { io::write_mesh(m, p, f, opts); }, p);
    EXPECT_FALSE(fs::exists(p));
  }
  for (auto& e : fs::directory_iterator(dir)) EXPECT_EQ(e.path().filename().string().find("fdr_io_test"), std::string::npos);
}

TEST_F(IoRoundTrip, FailureAfterWritingRemovesTempFile) {
  // The target is an existing folder: everything is written, then the final rename fails.
  for (Format f : kEvery) {
    std::string p = tmp / ("blocked" + ext_of(f));
    fs::create_directory(p);
    expect_output_error([&] { io::write_mesh(m, p, f, opts); }, p);
    EXPECT_TRUE(fs::is_directory(p));
    EXPECT_FALSE(has_temp_leftover(tmp)) << io::format_name(f);
    fs::remove(p);
  }
  // .node/.ele: the .node rename succeeds, the .ele one fails -> the new .node is removed again.
  fs::create_directory(tmp / "pair.ele");
  expect_output_error([&] { io::write_mesh(m, tmp / "pair.node", Format::kNode, opts); }, tmp / "pair.ele");
  EXPECT_FALSE(fs::exists(tmp / "pair.node"));
  EXPECT_FALSE(has_temp_leftover(tmp));
}

TEST_F(IoRoundTrip, FailureMidWriteRemovesTempFileAndKeepsOldTarget) {
  std::string p = tmp / "kept.2dm";
  { std::ofstream(p) << "previous mesh\n"; }
  // A sizing field that throws half-way through the triangles (e.g. a raster read error).
  struct Throwing : sizing::SizingField {
    mutable int calls = 0;
    double operator()(Point2) const override {
      if (++calls > 4) throw std::runtime_error("raster read failed");
      return 1.0;
    }
    std::string describe() const override { return "throwing"; }
  } bad;
  io::WriteOptions o = opts;
  o.f = &bad;
  for (Format f : {Format::kGpkg, Format::kVtu, Format::kUgrid}) {
    std::string q = tmp / ("mid" + ext_of(f));
    bad.calls = 0;
    expect_output_error([&] { io::write_mesh(m, q, f, o); }, q);
    EXPECT_FALSE(fs::exists(q)) << io::format_name(f);
  }
  // Directly through the temp-file helper: bytes written, then an exception.
  try {
    io::detail::TempFile tf(p);
    io::detail::TextOut out(tf.stream(), p);
    out.str("MESH2D\nND 1 0 0 0\n").flush();
    throw std::runtime_error("simulated failure");
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(slurp(p), "previous mesh\n");
  EXPECT_EQ(tmp.entries(), std::vector<std::string>{"kept.2dm"});
}

TEST_F(IoRoundTrip, InvalidMeshIsRejectedBeforeWriting) {
  m.triangles.push_back({0, 1, 99});
  std::string p = tmp / "bad.gpkg";
  expect_output_error([&] { io::write_mesh(m, p, Format::kGpkg, opts); }, p);
  EXPECT_TRUE(tmp.entries().empty());
  m = sample_mesh();
  m.z.pop_back();
  expect_output_error([&] { io::write_mesh(m, p, Format::k2dm, opts); }, p);
}

// ---------------------------------------------------------------- reader errors

namespace {
void expect_read_error(const std::string& path, ExitCode code, const std::string& fragment) {
  try {
    io::read_mesh(path);
    ADD_FAILURE() << "no error reading " << path;
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), code) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}
}  // namespace

TEST(IoReaders, MissingFileIsUnreadable) {
  expect_read_error("/nonexistent/mesh.2dm", ExitCode::kInputUnreadable, "/nonexistent/mesh.2dm");
  expect_read_error("/nonexistent/mesh.gpkg", ExitCode::kInputUnreadable, "/nonexistent/mesh.gpkg");
  expect_read_error("/nonexistent/mesh.ele", ExitCode::kInputUnreadable, "/nonexistent/mesh.node");
}

TEST(IoReaders, MalformedContentNamesFileAndLine) {
  TmpDir tmp;
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(tmp / name) << text;
    return tmp / name;
  };
  expect_read_error(write("a.2dm", "MESH2D\nND 1 0 0 0\nND 2 1 zero 0\n"), ExitCode::kInputMalformed, "a.2dm:3: 'zero' is not a number");
  expect_read_error(write("b.2dm", "MESH2D\nND 1 0 0 0\nE3T 1 1 2 3 1\n"), ExitCode::kInputMalformed, "b.2dm:3: node id 2 is not defined");
  expect_read_error(write("c.2dm", "hello\n"), ExitCode::kInputMalformed, "c.2dm:1: expected the MESH2D card");
  expect_read_error(write("d.2dm", "MESH2D\nE4Q 1 1 2 3 4 1\n"), ExitCode::kInputMalformed, "d.2dm:2: element card E4Q");
  expect_read_error(write("e.14", "t\n1 3\n1 0 0 1\n2 1 0 1\n3 0 1 1\n1 3 1 2 4\n"), ExitCode::kInputMalformed, "e.14:6: node id 4 is not defined");
  expect_read_error(write("f.14", "t\n1 3\n1 0 0 1\n"), ExitCode::kInputMalformed, "f.14:3: unexpected end of file");
  expect_read_error(write("g.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"), ExitCode::kInputMalformed, "g.msh:2: msh version 2.2");
  expect_read_error(write("h.node", "3 2 0 0\n1 0 0\n2 1 0\n3 0 1\n"), ExitCode::kInputUnreadable, "h.ele");
  write("h.ele", "1 6 0\n1 1 2 3 4 5 6\n");
  expect_read_error(tmp / "h.node", ExitCode::kInputMalformed, "h.ele:1: 6 nodes per triangle");
  expect_read_error(write("i.gpkg", "not a database"), ExitCode::kInputUnreadable, "i.gpkg");
  expect_read_error(write("j.vtu", "<VTKFile/>"), ExitCode::kInputUnreadable, "j.vtu");
}

TEST(IoReaders, Fort14WithoutBoundariesAndFortranExponents) {
  TmpDir tmp;
  std::ofstream(tmp / "fort.14") << "grid\n 1 3\n 10 0.0 0.0 1.5D+00\n 20, 1.0, 0.0, 2.0\n 30 0.0 1.0 -1.0E+00\n 1 3 10 20 30\n";
  mesh::MeshView r = io::read_mesh(tmp / "fort.14");
  ASSERT_EQ(r.num_vertices(), 3u);
  EXPECT_EQ(r.z, (std::vector<double>{-1.5, -2.0, 1.0}));
  EXPECT_EQ(r.triangles[0], (std::array<Index, 3>{0, 1, 2}));
  EXPECT_TRUE(r.edges.empty());
}

TEST(IoReaders, ClockwiseFileIsReorientedAsAWhole) {
  TmpDir tmp;
  std::ofstream(tmp / "cw.2dm") << "MESH2D\nE3T 1 1 3 2 1\nND 1 0 0 0\nND 2 1 0 0\nND 3 0 1 0\n";
  mesh::MeshView r = io::read_mesh(tmp / "cw.2dm");
  ASSERT_EQ(r.num_triangles(), 1u);
  EXPECT_EQ(r.triangles[0], (std::array<Index, 3>{0, 1, 2}));
}

// QGIS reads UGRID through MDAL: the mesh, its CRS (from the crs variable) and node z must load.
TEST_F(IoRoundTrip, UgridLoadsInQgisMdal) {
  if (std::system("/usr/bin/python3 -c 'import qgis.core' > /dev/null 2>&1") != 0) GTEST_SKIP() << "QGIS Python not installed";
  std::string p = tmp / "mdal.nc", script = tmp / "mdal.py", log = tmp / "mdal.log";
  io::write_mesh(m, p, Format::kUgrid, opts);
  std::ofstream(script) << "import os\n"
                           "os.environ['QT_QPA_PLATFORM'] = 'offscreen'\n"
                           "from qgis.core import QgsApplication, QgsMeshLayer\n"
                           "app = QgsApplication([], False)\n"
                           "app.initQgis()\n"
                           "l = QgsMeshLayer('Ugrid:\"" << p << "\":mesh2d', 'm', 'mdal')\n"
                           "d = l.dataProvider()\n"
                           "print('RESULT', l.isValid(), l.crs().authid(), d.vertexCount(), d.faceCount(), d.datasetGroupCount())\n"
                           "app.exitQgis()\n";
  ASSERT_EQ(std::system(("/usr/bin/python3 " + script + " > " + log + " 2>&1").c_str()), 0) << slurp(log);
  std::string out = slurp(log);
  EXPECT_NE(out.find("RESULT True EPSG:32633 9 9"), std::string::npos) << out;
}

// An empty mesh is still a valid file in every format and reads back empty.
TEST_F(IoRoundTrip, EmptyMeshEveryFormat) {
  mesh::MeshView empty;
  for (Format f : kEvery) {
    std::string p = tmp / ("empty" + ext_of(f));
    io::write_mesh(empty, p, f, {});
    EXPECT_TRUE(fs::exists(p)) << io::format_name(f);
    if (f == Format::kVtu || f == Format::kUgrid || f == Format::kDflowfm) continue;
    mesh::MeshView r = io::read_mesh(p);
    EXPECT_EQ(r.num_vertices(), 0u) << io::format_name(f);
    EXPECT_EQ(r.num_triangles(), 0u) << io::format_name(f);
    EXPECT_TRUE(r.edges.empty()) << io::format_name(f);
  }
  if (::access("/usr/bin/gmsh", X_OK) == 0) {
    std::string cmd = "/usr/bin/gmsh " + (tmp / "empty.msh") + " -0 -o " + (tmp / "empty_out.msh") + " > /dev/null 2>&1";
    EXPECT_EQ(std::system(cmd.c_str()), 0);
  }
  int nc;
  ASSERT_EQ(nc_open((tmp / "empty.nc").c_str(), NC_NOWRITE, &nc), NC_NOERR);
  nc_close(nc);
  EXPECT_FALSE(has_temp_leftover(tmp));
}

// ---------------------------------------------------------------- boundaries and model formats

#include "io/boundaries.hpp"

namespace {
std::vector<Index> ids(std::initializer_list<Index> l) { return std::vector<Index>(l); }
}  // namespace

TEST(IoBoundaries, LoopsRunsOrderAndOrientation) {
  mesh::MeshView m = sample_mesh();
  io::Boundaries b = io::extract_boundaries(m, "sample");
  ASSERT_EQ(b.loops.size(), 2u);
  // Outer loop counter-clockwise, starting at the open run after the south-west node o0.
  EXPECT_TRUE(b.loops[0].outer);
  EXPECT_EQ(b.loops[0].nodes, ids({1, 2, 3, 4, 0}));
  EXPECT_EQ(b.loops[0].edge_open, (std::vector<char>{1, 1, 0, 0, 0}));
  EXPECT_GT(b.loops[0].signed_area, 0);
  // Island clockwise (mesh on the left), from its south-west node h0.
  EXPECT_FALSE(b.loops[1].outer);
  EXPECT_EQ(b.loops[1].nodes, ids({5, 8, 7, 6}));
  EXPECT_LT(b.loops[1].signed_area, 0);
  ASSERT_EQ(b.runs.size(), 3u);
  EXPECT_EQ(b.runs[0].kind, io::BoundaryKind::kOpen);
  EXPECT_EQ(b.runs[0].nodes, ids({1, 2, 3}));
  EXPECT_EQ(b.runs[1].kind, io::BoundaryKind::kLand);
  EXPECT_EQ(b.runs[1].nodes, ids({3, 4, 0, 1}));
  EXPECT_EQ(b.runs[2].kind, io::BoundaryKind::kIsland);
  EXPECT_TRUE(b.runs[2].closed);
  EXPECT_EQ(b.runs[2].nodes, ids({5, 8, 7, 6}));
  EXPECT_EQ(b.ordered_nodes(), ids({1, 2, 3, 4, 0, 5, 8, 7, 6}));
  EXPECT_EQ(io::pinch_node(b, m.vertices.size()), kNoId);
  // Renumbering the triangles does not change the lists.
  std::reverse(m.triangles.begin(), m.triangles.end());
  io::Boundaries b2 = io::extract_boundaries(m, "sample");
  EXPECT_EQ(b2.ordered_nodes(), b.ordered_nodes());
}

namespace {
// MeshView::neighbours by brute force (what the mesher fills): the half-edge running the other way.
std::vector<Index> brute_neighbours(const mesh::MeshView& m) {
  std::map<std::pair<Index, Index>, Index> he;
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) he[{m.triangles[t][k], m.triangles[t][(k + 1) % 3]}] = static_cast<Index>(3 * t + k);
  std::vector<Index> nb(3 * m.triangles.size(), kNoId);
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const auto it = he.find({m.triangles[t][(k + 1) % 3], m.triangles[t][k]});
      if (it != he.end()) nb[3 * t + k] = it->second;
    }
  return nb;
}
void expect_same_boundaries(const io::Boundaries& a, const io::Boundaries& b) {
  ASSERT_EQ(a.loops.size(), b.loops.size());
  for (std::size_t i = 0; i < a.loops.size(); ++i) {
    EXPECT_EQ(a.loops[i].nodes, b.loops[i].nodes);
    EXPECT_EQ(a.loops[i].edge_open, b.loops[i].edge_open);
    EXPECT_EQ(a.loops[i].outer, b.loops[i].outer);
  }
  ASSERT_EQ(a.runs.size(), b.runs.size());
  for (std::size_t i = 0; i < a.runs.size(); ++i) {
    EXPECT_EQ(a.runs[i].nodes, b.runs[i].nodes);
    EXPECT_EQ(a.runs[i].kind, b.runs[i].kind);
    EXPECT_EQ(a.runs[i].closed, b.runs[i].closed);
  }
}
}  // namespace

// The mesher's adjacency (MeshView::neighbours) and the table built from the triangles alone
// give the same loops and runs, pinch nodes included.
TEST(IoBoundaries, SameWithAndWithoutTheMeshersAdjacency) {
  // A 6x5 grid of squares with two holes (one square each) and an open edge, triangles shuffled.
  mesh::MeshView g;
  const int nx = 6, ny = 5;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) g.vertices.push_back({double(i), double(j)});
  auto id = [&](int i, int j) { return static_cast<Index>(j * (nx + 1) + i); };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      if ((i == 1 && j == 1) || (i == 4 && j == 3)) continue;
      g.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      g.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  std::reverse(g.triangles.begin() + 10, g.triangles.end());
  g.edges.push_back({id(0, 0), id(1, 0), static_cast<std::int32_t>(mesh::EdgeKind::kOpen), 0});
  g.edges.push_back({id(1, 0), id(2, 0), static_cast<std::int32_t>(mesh::EdgeKind::kOpen), 0});
  mesh::MeshView bow;  // two triangles touching at vertex 0
  bow.vertices = {{0, 0}, {1, 0}, {1, 1}, {-1, 0}, {-1, -1}};
  bow.triangles = {{0, 1, 2}, {0, 3, 4}};
  for (mesh::MeshView m : {sample_mesh(), g, bow}) {
    m.neighbours.clear();
    const io::Boundaries without = io::extract_boundaries(m, "m");
    m.neighbours = brute_neighbours(m);
    const io::Boundaries with = io::extract_boundaries(m, "m");
    expect_same_boundaries(without, with);
  }
  io::Boundaries gb = io::extract_boundaries(g, "g");
  EXPECT_EQ(gb.loops.size(), 3u);  // the outer loop and the two holes
}

TEST(IoBoundaries, PinchNodeIsFoundAndSelafinRefusesIt) {
  // Two triangles touching at vertex 0 (a bow-tie): two loops through node 0.
  mesh::MeshView m;
  m.vertices = {{0, 0}, {1, 0}, {1, 1}, {-1, 0}, {-1, -1}};
  m.triangles = {{0, 1, 2}, {0, 3, 4}};
  io::Boundaries b = io::extract_boundaries(m, "bowtie");
  EXPECT_EQ(b.loops.size(), 2u);
  EXPECT_EQ(io::pinch_node(b, m.vertices.size()), 0u);
  TmpDir tmp;
  try {
    io::write_mesh(m, tmp / "bowtie.slf", Format::kSelafin, {});
    ADD_FAILURE() << "pinched boundary accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kOutputError);
    EXPECT_NE(std::string(e.what()).find("node 1 at (0.000000, 0.000000) lies twice on the boundary"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(tmp.entries().empty());
}

// write_meshes shares one boundary extraction between the outputs that carry boundaries and
// starts the costliest outputs first: every file is the one write_mesh writes alone.
TEST_F(IoRoundTrip, WriteMeshesSharesBoundariesSameFiles) {
  opts.f = nullptr;  // concurrent writers: no sizing field evaluated
  const std::vector<std::string> names = {"a.2dm", "a.14", "a.gr3", "a.slf", "a.gpkg", "a_net.nc"};
  std::vector<std::string> many;
  std::vector<Format> formats;
  for (const auto& n : names) {
    many.push_back(tmp / ("many_" + n));
    formats.push_back(io::format_from_path(many.back()));
  }
  io::write_meshes(m, many, formats, opts, 2);
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (formats[i] == Format::kGpkg || formats[i] == Format::kDflowfm) continue;  // these hold times of writing
    const std::string one = tmp / ("one_" + names[i]);
    io::write_mesh(m, one, formats[i], opts);
    EXPECT_EQ(slurp(one), slurp(many[i])) << names[i];
  }
  EXPECT_EQ(slurp(tmp / "many_a.cli"), slurp(tmp / "one_a.cli"));
}

TEST_F(IoRoundTrip, Gr3AndLl) {
  std::string p = tmp / "hgrid.gr3";
  io::write_mesh(m, p, io::format_from_path(p), opts);
  std::string text = slurp(p);
  // Open boundary without IBTYPEE, land (0) and island (1, first node not repeated).
  EXPECT_NE(text.find("1 = Number of open boundaries\n3 = Total number of open boundary nodes\n"
                      "3 = Number of nodes for open boundary 1\n2\n3\n4\n"
                      "2 = Number of land boundaries\n8 = Total number of land boundary nodes\n"
                      "4 0 = Number of nodes for land boundary 1\n4\n5\n1\n2\n"
                      "4 1 = Number of nodes for land boundary 2\n6\n9\n8\n7\n"),
            std::string::npos) << text;
  mesh::MeshView r = io::read_mesh(p);
  expect_same_geometry(m, r);  // depth positive down in the file, z back
  std::set<std::int32_t> kinds{mk(EdgeKind::kLand), mk(EdgeKind::kIsland), mk(EdgeKind::kOpen)};
  EXPECT_EQ(edge_set(r, kinds), edge_set(m, kinds));

  std::string q = tmp / "hgrid.ll";
  io::write_mesh(m, q, io::format_from_path(q), opts);
  std::string lt = slurp(q);
  EXPECT_EQ(lt.substr(lt.find("= Number of open boundaries") - 2), text.substr(text.find("= Number of open boundaries") - 2));
  mesh::MeshView l = io::read_mesh(q);
  ASSERT_EQ(l.vertices.size(), m.vertices.size());
  // EPSG:32633 easting 500000 is the central meridian 15 E; northing 6400000 m is about 57.7 N.
  EXPECT_NEAR(l.vertices[0].x, 15.0, 1e-4);
  EXPECT_NEAR(l.vertices[0].y, 57.7, 0.1);
  EXPECT_EQ(l.z, r.z);
  // Without a CRS there is no lon/lat.
  mesh::MeshView nocrs = m;
  nocrs.crs_wkt.clear();
  try {
    io::write_mesh(nocrs, tmp / "x.ll", Format::kLl, opts);
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kCrsError);
  }
}

TEST_F(IoRoundTrip, SelafinAndCli) {
  for (bool dbl : {false, true}) {
    std::string p = tmp / (dbl ? "geo_d.slf" : "geo.slf");
    opts.slf_double = dbl;
    opts.telemac_open_codes = {4, 5, 5};
    io::write_mesh(m, p, io::format_from_path(p), opts);
    std::string bin = slurp(p);
    ASSERT_GE(bin.size(), 84u);
    EXPECT_EQ(bin.substr(0, 4), std::string("\0\0\0\x50", 4));
    EXPECT_EQ(bin.substr(4 + 72, 8), dbl ? "SERAFIND" : "SERAFIN ");
    EXPECT_EQ(bin.substr(84, 8), std::string("\0\0\0\x50\0\0\0\x08", 8));
    mesh::MeshView r = io::read_mesh(p);
    ASSERT_EQ(r.vertices.size(), m.vertices.size());
    EXPECT_EQ(r.triangles, m.triangles);
    for (std::size_t v = 0; v < m.vertices.size(); ++v) {
      const double tol = dbl ? 0.0 : 0.01;  // float offsets from the integer origin: < 1 cm here
      EXPECT_NEAR(r.vertices[v].x, m.world(static_cast<Index>(v)).x, tol);
      EXPECT_NEAR(r.vertices[v].y, m.world(static_cast<Index>(v)).y, tol);
      EXPECT_NEAR(r.z[v], m.z[v], dbl ? 0.0 : 1e-6);
    }
    // .cli: boundary nodes in IPOBO order, open nodes with the chosen codes.
    std::string cli = slurp(tmp / (dbl ? "geo_d.cli" : "geo.cli"));
    EXPECT_EQ(cli,
              "4 5 5 0.0 0.0 0.0 0.0 4 0.0 0.0 0.0 2 1\n"
              "4 5 5 0.0 0.0 0.0 0.0 4 0.0 0.0 0.0 3 2\n"
              "4 5 5 0.0 0.0 0.0 0.0 4 0.0 0.0 0.0 4 3\n"
              "2 2 2 0.0 0.0 0.0 0.0 2 0.0 0.0 0.0 5 4\n"
              "2 2 2 0.0 0.0 0.0 0.0 2 0.0 0.0 0.0 1 5\n"
              "2 2 2 0.0 0.0 0.0 0.0 2 0.0 0.0 0.0 6 6\n"
              "2 2 2 0.0 0.0 0.0 0.0 2 0.0 0.0 0.0 9 7\n"
              "2 2 2 0.0 0.0 0.0 0.0 2 0.0 0.0 0.0 8 8\n"
              "2 2 2 0.0 0.0 0.0 0.0 2 0.0 0.0 0.0 7 9\n");
  }
  EXPECT_EQ(io::parse_telemac_codes("5,4,4"), (std::array<int, 3>{5, 4, 4}));
  EXPECT_EQ(io::parse_telemac_codes("4 5 5"), (std::array<int, 3>{4, 5, 5}));
  for (const char* bad : {"5,4", "5,4,4,4", "5,4,x", "5,4,9", ""}) {
    try {
      io::parse_telemac_codes(bad);
      ADD_FAILURE() << bad;
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ExitCode::kUsage);
    }
  }
}

TEST_F(IoRoundTrip, DflowfmNetHasEveryEdgeAndEdgeTypes) {
  std::string p = tmp / "mesh_net.nc";
  ASSERT_EQ(io::format_from_path(p), Format::kDflowfm);
  io::write_mesh(m, p, io::format_from_path(p), opts);
  int nc;
  ASSERT_EQ(nc_open(p.c_str(), NC_NOWRITE, &nc), NC_NOERR);
  int d;
  std::size_t ne = 0, nf = 0, nn = 0;
  ASSERT_EQ(nc_inq_dimid(nc, "mesh2d_nEdges", &d), NC_NOERR);
  nc_inq_dimlen(nc, d, &ne);
  ASSERT_EQ(nc_inq_dimid(nc, "mesh2d_nFaces", &d), NC_NOERR);
  nc_inq_dimlen(nc, d, &nf);
  ASSERT_EQ(nc_inq_dimid(nc, "mesh2d_nNodes", &d), NC_NOERR);
  nc_inq_dimlen(nc, d, &nn);
  EXPECT_EQ(nn, 9u);
  EXPECT_EQ(nf, 9u);
  EXPECT_EQ(ne, 18u);  // Euler with one hole: E = V + F - 1 + 1; also 3F = 2 E_interior + E_boundary
  int v;
  ASSERT_EQ(nc_inq_varid(nc, "mesh2d_edge_type", &v), NC_NOERR);
  std::vector<int> type(ne);
  nc_get_var_int(nc, v, type.data());
  EXPECT_EQ(std::count(type.begin(), type.end(), 2), 2);  // open boundary edges o1-o2, o2-o3
  EXPECT_EQ(std::count(type.begin(), type.end(), 3), 7);  // 3 land + 4 island
  EXPECT_EQ(std::count(type.begin(), type.end(), 1), 9);
  ASSERT_EQ(nc_inq_varid(nc, "projected_coordinate_system", &v), NC_NOERR);
  int epsg = 0;
  nc_get_att_int(nc, v, "epsg", &epsg);
  EXPECT_EQ(epsg, 32633);
  std::size_t len = 0;
  nc_inq_attlen(nc, NC_GLOBAL, "Conventions", &len);
  std::string conv(len, ' ');
  nc_get_att_text(nc, NC_GLOBAL, "Conventions", conv.data());
  EXPECT_EQ(conv, "CF-1.8 UGRID-1.0 Deltares-0.10");
  nc_close(nc);
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
