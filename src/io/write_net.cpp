// Delft3D FM (D-Flow FM) UGRID-1.0 net file: mesh2d with every edge, face circumcentres, edge
// types from the shared boundary extraction, and the CRS as Deltares tools expect it.
#include <array>
#include <climits>
#include <cmath>
#include <unordered_map>

#include "io/boundaries.hpp"
#include "io/detail.hpp"
#include "io/netcdf_util.hpp"

namespace fdr::io::detail {

namespace {
std::uint64_t ukey(Index a, Index b) {
  return a < b ? (static_cast<std::uint64_t>(a) << 32 | b) : (static_cast<std::uint64_t>(b) << 32 | a);
}

// Every triangle edge once, in order of first appearance, with its mesh2d_edge_type.
struct NetEdges {
  std::vector<std::array<Index, 2>> nodes;
  std::vector<int> type;
};

NetEdges net_edges(const mesh::MeshView& m, const std::string& path, const WriteOptions& o) {
  NetEdges e;
  std::unordered_map<std::uint64_t, std::size_t> seen;
  seen.reserve(3 * m.triangles.size() / 2 + m.vertices.size() + 16);
  for (const auto& tr : m.triangles)
    for (int k = 0; k < 3; ++k) {
      const Index a = tr[k], b = tr[(k + 1) % 3];
      if (seen.emplace(ukey(a, b), e.nodes.size()).second) {
        e.nodes.push_back({a, b});
        e.type.push_back(1);
      }
    }
  Boundaries own;
  const Boundaries& bnd = boundaries_for(m, path, o.boundary_cache, own);
  for (const auto& l : bnd.loops)
    for (std::size_t i = 0; i < l.nodes.size(); ++i) {
      auto it = seen.find(ukey(l.nodes[i], l.nodes[(i + 1) % l.nodes.size()]));
      if (it != seen.end()) e.type[it->second] = l.edge_open[i] ? 2 : 3;
    }
  return e;
}

// The open file being defined: dimensions, CRS variable, variable ids.
struct NetFile {
  const Nc& nc;
  int id;
  bool geographic;
  int d_node = -1, d_edge = -1, d_face = -1, d_max = -1, d_two = -1;
  int v_crs = -1;
  std::string crs_var = {};
  int nx = -1, ny = -1, ex = -1, ey = -1, fx = -1, fy = -1, z = -1, en = -1, et = -1, fn = -1;
  // The attributes tying a data variable to the mesh (and its CRS).
  void on_mesh(int var, const char* location, const char* coords) const {
    nc.text(id, var, "mesh", "mesh2d");
    nc.text(id, var, "location", location);
    if (coords) nc.text(id, var, "coordinates", coords);
    if (v_crs >= 0) nc.text(id, var, "grid_mapping", crs_var);
  }
};

// Dimensions, global attributes, the mesh topology variable and the CRS variable.
void define_net_mesh(NetFile& n, const mesh::MeshView& m, std::size_t ne, const WriteOptions& o, const NcCrs& crs) {
  const Nc& nc = n.nc;
  const int id = n.id;
  nc.check(nc_def_dim(id, "mesh2d_nNodes", m.vertices.size(), &n.d_node), "dimension mesh2d_nNodes");
  nc.check(nc_def_dim(id, "mesh2d_nEdges", ne, &n.d_edge), "dimension mesh2d_nEdges");
  nc.check(nc_def_dim(id, "mesh2d_nFaces", m.triangles.size(), &n.d_face), "dimension mesh2d_nFaces");
  nc.check(nc_def_dim(id, "mesh2d_nMax_face_nodes", 3, &n.d_max), "dimension mesh2d_nMax_face_nodes");
  nc.check(nc_def_dim(id, "Two", 2, &n.d_two), "dimension Two");

  nc.text(id, NC_GLOBAL, "Conventions", "CF-1.8 UGRID-1.0 Deltares-0.10");
  nc.text(id, NC_GLOBAL, "title", o.title.empty() ? "fdrmesh mesh" : o.title);
  nc.text(id, NC_GLOBAL, "institution", "fdrmesh");
  nc.text(id, NC_GLOBAL, "source", "fdrmesh (Functional Delaunay Refinement)");
  for (const auto& [k, v] : o.metadata)
    if (k == "software" || k == "command_line") nc.text(id, NC_GLOBAL, ("fdrmesh_" + k).c_str(), v);

  int v_mesh;
  nc.check(nc_def_var(id, "mesh2d", NC_INT, 0, nullptr, &v_mesh), "variable mesh2d");
  nc.text(id, v_mesh, "cf_role", "mesh_topology");
  nc.text(id, v_mesh, "long_name", "Topology data of 2D mesh");
  nc.integer(id, v_mesh, "topology_dimension", 2);
  nc.text(id, v_mesh, "node_coordinates", "mesh2d_node_x mesh2d_node_y");
  nc.text(id, v_mesh, "node_dimension", "mesh2d_nNodes");
  nc.text(id, v_mesh, "edge_node_connectivity", "mesh2d_edge_nodes");
  nc.text(id, v_mesh, "edge_dimension", "mesh2d_nEdges");
  nc.text(id, v_mesh, "edge_coordinates", "mesh2d_edge_x mesh2d_edge_y");
  nc.text(id, v_mesh, "face_node_connectivity", "mesh2d_face_nodes");
  nc.text(id, v_mesh, "face_dimension", "mesh2d_nFaces");
  nc.text(id, v_mesh, "max_face_nodes_dimension", "mesh2d_nMax_face_nodes");
  nc.text(id, v_mesh, "face_coordinates", "mesh2d_face_x mesh2d_face_y");

  // Deltares names the CRS variable projected_coordinate_system (or wgs84 for lon/lat).
  if (crs.wkt1.empty()) return;
  n.crs_var = crs.geographic ? "wgs84" : "projected_coordinate_system";
  nc.check(nc_def_var(id, n.crs_var.c_str(), NC_INT, 0, nullptr, &n.v_crs), "variable projected_coordinate_system");
  nc.text(id, n.v_crs, "name", crs.name.empty() ? "Unknown projected" : crs.name);
  nc.integer(id, n.v_crs, "epsg", crs.epsg);
  nc.text(id, n.v_crs, "grid_mapping_name", crs.geographic ? "latitude_longitude" : "Unknown projected");
  nc.real(id, n.v_crs, "longitude_of_prime_meridian", 0.0);
  nc.real(id, n.v_crs, "semi_major_axis", crs.semi_major);
  nc.real(id, n.v_crs, "semi_minor_axis", crs.semi_minor);
  nc.real(id, n.v_crs, "inverse_flattening", crs.inverse_flattening);
  if (crs.epsg > 0) nc.text(id, n.v_crs, "EPSG_code", "EPSG:" + std::to_string(crs.epsg));
  nc.text(id, n.v_crs, "value", "value is equal to EPSG code");
  nc.text(id, n.v_crs, "wkt", crs.wkt1);
  nc.text(id, n.v_crs, "crs_wkt", crs.wkt2);
}

// Coordinates of nodes, edges and faces, then node z.
void define_net_coordinates(NetFile& n) {
  const Nc& nc = n.nc;
  const int id = n.id;
  auto coord_var = [&](const char* name, int dim, bool is_x, const char* long_name, const char* location) {
    int v;
    nc.check(nc_def_var(id, name, NC_DOUBLE, 1, &dim, &v), name);
    if (n.geographic) {
      nc.text(id, v, "standard_name", is_x ? "longitude" : "latitude");
      nc.text(id, v, "units", is_x ? "degrees_east" : "degrees_north");
    } else {
      nc.text(id, v, "standard_name", is_x ? "projection_x_coordinate" : "projection_y_coordinate");
      nc.text(id, v, "units", "m");
    }
    nc.text(id, v, "long_name", long_name);
    n.on_mesh(v, location, nullptr);
    return v;
  };
  n.nx = coord_var("mesh2d_node_x", n.d_node, true, "x-coordinate of mesh nodes", "node");
  n.ny = coord_var("mesh2d_node_y", n.d_node, false, "y-coordinate of mesh nodes", "node");
  n.ex = coord_var("mesh2d_edge_x", n.d_edge, true, "Characteristic x-coordinate of the mesh edge (e.g. midpoint)", "edge");
  n.ey = coord_var("mesh2d_edge_y", n.d_edge, false, "Characteristic y-coordinate of the mesh edge (e.g. midpoint)", "edge");
  n.fx = coord_var("mesh2d_face_x", n.d_face, true, "Characteristic x-coordinate of mesh face (circumcentre)", "face");
  n.fy = coord_var("mesh2d_face_y", n.d_face, false, "Characteristic y-coordinate of mesh face (circumcentre)", "face");

  nc.check(nc_def_var(id, "mesh2d_node_z", NC_DOUBLE, 1, &n.d_node, &n.z), "variable mesh2d_node_z");
  nc.text(id, n.z, "standard_name", "altitude");
  nc.text(id, n.z, "long_name", "z-coordinate of mesh nodes");
  nc.text(id, n.z, "units", "m");
  nc.text(id, n.z, "positive", "up");
  n.on_mesh(n.z, "node", "mesh2d_node_x mesh2d_node_y");
  const double fill = -999.0;
  nc.check(nc_put_att_double(id, n.z, "_FillValue", NC_DOUBLE, 1, &fill), "_FillValue");
}

// Edge nodes and types, face nodes.
// A UGRID <location>_node_connectivity variable (1-based, fill -999) of dimensions (rows, cols).
void connectivity_var(NetFile& n, const char* name, int rows, int cols, const char* location, const char* long_name,
                      int* var) {
  const Nc& nc = n.nc;
  const int id = n.id, fill_id = -999;
  int dims[2] = {rows, cols};
  nc.check(nc_def_var(id, name, NC_INT, 2, dims, var), (std::string("variable ") + name).c_str());
  nc.text(id, *var, "cf_role", std::string(location) + "_node_connectivity");
  nc.text(id, *var, "mesh", "mesh2d");
  nc.text(id, *var, "location", location);
  nc.text(id, *var, "long_name", long_name);
  nc.integer(id, *var, "start_index", 1);
  nc.check(nc_put_att_int(id, *var, "_FillValue", NC_INT, 1, &fill_id), "_FillValue");
}

void define_net_connectivity(NetFile& n) {
  const Nc& nc = n.nc;
  const int id = n.id;
  connectivity_var(n, "mesh2d_edge_nodes", n.d_edge, n.d_two, "edge", "Start and end nodes of mesh edges", &n.en);

  nc.check(nc_def_var(id, "mesh2d_edge_type", NC_INT, 1, &n.d_edge, &n.et), "variable mesh2d_edge_type");
  nc.text(id, n.et, "long_name", "edge type (relation between edge and flow geometry)");
  n.on_mesh(n.et, "edge", "mesh2d_edge_x mesh2d_edge_y");
  const int flags[4] = {0, 1, 2, 3};
  nc.check(nc_put_att_int(id, n.et, "flag_values", NC_INT, 4, flags), "flag_values");
  nc.text(id, n.et, "flag_meanings", "internal_closed internal boundary boundary_closed");

  connectivity_var(n, "mesh2d_face_nodes", n.d_face, n.d_max, "face", "Vertex nodes of mesh faces (counterclockwise)",
                   &n.fn);
}

void write_net_data(const NetFile& n, const mesh::MeshView& m, const NetEdges& edges) {
  const Nc& nc = n.nc;
  const int id = n.id;
  const std::size_t nv = m.vertices.size(), nt = m.triangles.size(), ne = edges.nodes.size();
  if (nv) {
    std::vector<double> x(nv), y(nv), z(nv, 0.0);
    for (std::size_t v = 0; v < nv; ++v) {
      const Point2 p = m.world(static_cast<Index>(v));
      x[v] = p.x;
      y[v] = p.y;
      if (!m.z.empty()) z[v] = m.z[v];
    }
    nc.check(nc_put_var_double(id, n.nx, x.data()), "write mesh2d_node_x");
    nc.check(nc_put_var_double(id, n.ny, y.data()), "write mesh2d_node_y");
    nc.check(nc_put_var_double(id, n.z, z.data()), "write mesh2d_node_z");
  }
  if (ne) {
    std::vector<int> en(2 * ne);
    std::vector<double> ex(ne), ey(ne);
    for (std::size_t e = 0; e < ne; ++e) {
      en[2 * e] = static_cast<int>(edges.nodes[e][0]) + 1;
      en[2 * e + 1] = static_cast<int>(edges.nodes[e][1]) + 1;
      const Point2 a = m.world(edges.nodes[e][0]), b = m.world(edges.nodes[e][1]);
      ex[e] = 0.5 * (a.x + b.x);
      ey[e] = 0.5 * (a.y + b.y);
    }
    nc.check(nc_put_var_int(id, n.en, en.data()), "write mesh2d_edge_nodes");
    nc.check(nc_put_var_int(id, n.et, edges.type.data()), "write mesh2d_edge_type");
    nc.check(nc_put_var_double(id, n.ex, ex.data()), "write mesh2d_edge_x");
    nc.check(nc_put_var_double(id, n.ey, ey.data()), "write mesh2d_edge_y");
  }
  if (nt) {
    std::vector<int> fn(3 * nt);
    std::vector<double> fx(nt), fy(nt);
    for (std::size_t t = 0; t < nt; ++t) {
      for (int k = 0; k < 3; ++k) fn[3 * t + k] = static_cast<int>(m.triangles[t][k]) + 1;
      Point2 c;
      circumradius(m, t, c);  // local frame; a degenerate triangle gives its first vertex
      fx[t] = m.origin.x + c.x;
      fy[t] = m.origin.y + c.y;
    }
    nc.check(nc_put_var_int(id, n.fn, fn.data()), "write mesh2d_face_nodes");
    nc.check(nc_put_var_double(id, n.fx, fx.data()), "write mesh2d_face_x");
    nc.check(nc_put_var_double(id, n.fy, fy.data()), "write mesh2d_face_y");
  }
}

}  // namespace

// Dimensions mesh2d_nNodes, mesh2d_nEdges, mesh2d_nFaces, mesh2d_nMax_face_nodes (3), Two.
// Edges: every triangle edge once, in order of first appearance (triangle by triangle), stored
// as in the first triangle that uses it; mesh2d_edge_type 1 internal, 2 open boundary, 3 closed
// boundary (land, island). Ids are 1-based (start_index 1), as D-Flow FM writes them.
void write_dflowfm_net(const mesh::MeshView& m, const std::string& path, const WriteOptions& o) {
  const Nc nc{path};
  const std::size_t nv = m.vertices.size(), nt = m.triangles.size();
  if (nv >= static_cast<std::size_t>(INT_MAX) || 3 * nt >= static_cast<std::size_t>(INT_MAX))
    fail_output(path, "mesh too large for a D-Flow FM net file (32-bit ids)");
  const NcCrs crs = nc_crs(m.crs_wkt, path);
  const NetEdges edges = net_edges(m, path, o);

  const std::lock_guard<std::mutex> one_at_a_time(nc_mutex());
  TempFile tf(path);
  tf.release_for_library();
  NcFile f;
  nc.check(nc_create(tf.path().c_str(), NC_NETCDF4 | NC_NOCLOBBER, &f.id), "create");
  NetFile n{nc, f.id, crs.geographic};
  define_net_mesh(n, m, edges.nodes.size(), o, crs);
  define_net_coordinates(n);
  define_net_connectivity(n);
  nc.check(nc_enddef(f.id), "enddef");
  write_net_data(n, m, edges);
  const int status = nc_close(f.id);
  f.id = -1;
  nc.check(status, "close");
  tf.commit();
}

}  // namespace fdr::io::detail
