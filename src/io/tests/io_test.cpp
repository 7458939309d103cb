// Tests for the io writers and readers: format selection, boundary chains, round trips of every
// format but the GeoPackage, GDAL/netCDF/gmsh/MDAL cross-checks.
#include "io/tests/io_fixture.hpp"

using namespace fdr;
using namespace fdr::io_testing;

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