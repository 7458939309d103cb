// UGRID-1.0 NetCDF writer (netCDF C API): 2D mesh topology, node z, constrained edges, CF grid mapping.
#include <netcdf.h>
#include <ogr_spatialref.h>

#include <climits>
#include <cmath>
#include <cstring>

#include "io/detail.hpp"
#include "io/netcdf_util.hpp"
#include "io/gdal_util.hpp"

namespace fdr::io::detail {

namespace {

// netCDF names: letters, digits and '_', starting with a letter.
std::string nc_name(const std::string& key) {
  std::string r = "fdrmesh_";
  for (char c : key) r.push_back(std::isalnum(static_cast<unsigned char>(c)) ? c : '_');
  return r;
}

}  // namespace

NcCrs nc_crs(const std::string& crs_wkt, const std::string& path) {
  NcCrs c;
  if (crs_wkt.empty()) return c;
  gdal_register_once();
  GdalErrors errs;
  OGRSpatialReference srs;
  if (srs.SetFromUserInput(crs_wkt.c_str()) != OGRERR_NONE)
    fail_output(path, errs.reason("the mesh CRS cannot be parsed"));
  c.geographic = srs.IsGeographic();
  char* s = nullptr;
  if (srs.exportToWkt(&s) == OGRERR_NONE && s) c.wkt1 = s;
  CPLFree(s);
  s = nullptr;
  const char* opts[] = {"FORMAT=WKT2_2019", nullptr};
  if (srs.exportToWkt(&s, opts) == OGRERR_NONE && s) c.wkt2 = s;
  CPLFree(s);
  if (c.wkt1.empty()) c.wkt1 = crs_wkt;
  if (c.wkt2.empty()) c.wkt2 = crs_wkt;
  OGRSpatialReference probe(srs);
  const char* auth = probe.GetAuthorityName(nullptr);
  if (!(auth && std::strcmp(auth, "EPSG") == 0)) {
    probe.AutoIdentifyEPSG();
    auth = probe.GetAuthorityName(nullptr);
  }
  if (auth && std::strcmp(auth, "EPSG") == 0 && probe.GetAuthorityCode(nullptr))
    c.epsg = std::atoi(probe.GetAuthorityCode(nullptr));
  c.semi_major = srs.GetSemiMajor();
  c.semi_minor = srs.GetSemiMinor();
  c.inverse_flattening = srs.GetInvFlattening();
  if (const char* n = srs.GetName()) c.name = n;
  return c;
}

namespace {

// The open file being defined: its dimensions and the id width, for the steps below.
struct Ugrid {
  const Nc& nc;
  int id;
  bool wide;  // node ids beyond NC_INT
  int d_node = -1, d_face = -1, d_edge = -1, d_three = -1, d_two = -1;
  int v_crs = -1;
  // The attributes tying a data variable to the mesh (and its CRS).
  void on_mesh(int var, const char* location) const {
    nc.text(id, var, "mesh", "mesh2d");
    nc.text(id, var, "location", location);
    if (v_crs >= 0) nc.text(id, var, "grid_mapping", "crs");
  }
};

// Variable ids; -1 for the ones this mesh does not have.
struct UgridVars {
  int x = -1, y = -1, faces = -1, edges = -1, kind = -1, part = -1, z = -1, f = -1, angle = -1, ratio = -1;
};

// Dimensions, global attributes, the mesh topology variable and the CRS variable.
void define_mesh(Ugrid& u, const mesh::MeshView& m, const WriteOptions& o, const NcCrs& crs) {
  const Nc& nc = u.nc;
  const int id = u.id;
  const std::size_t ne = m.edges.size();
  // A zero length would mean "unlimited" in netCDF, which is what an empty mesh needs.
  nc.check(nc_def_dim(id, "nmesh2d_node", m.vertices.size(), &u.d_node), "dimension nmesh2d_node");
  nc.check(nc_def_dim(id, "nmesh2d_face", m.triangles.size(), &u.d_face), "dimension nmesh2d_face");
  nc.check(nc_def_dim(id, "max_nmesh2d_face_nodes", 3, &u.d_three), "dimension max_nmesh2d_face_nodes");
  nc.check(nc_def_dim(id, "Two", 2, &u.d_two), "dimension Two");
  if (ne) nc.check(nc_def_dim(id, "nmesh2d_edge", ne, &u.d_edge), "dimension nmesh2d_edge");

  nc.text(id, NC_GLOBAL, "Conventions", "CF-1.8 UGRID-1.0");
  nc.text(id, NC_GLOBAL, "title", o.title.empty() ? "fdrmesh mesh" : o.title);
  nc.text(id, NC_GLOBAL, "source", "fdrmesh");
  for (const auto& [k, v] : o.metadata) nc.text(id, NC_GLOBAL, nc_name(k).c_str(), v);

  int v_mesh;
  nc.check(nc_def_var(id, "mesh2d", NC_INT, 0, nullptr, &v_mesh), "variable mesh2d");
  nc.text(id, v_mesh, "cf_role", "mesh_topology");
  nc.text(id, v_mesh, "long_name", "Topology data of 2D mesh");
  nc.integer(id, v_mesh, "topology_dimension", 2);
  nc.text(id, v_mesh, "node_coordinates", "mesh2d_node_x mesh2d_node_y");
  nc.text(id, v_mesh, "face_node_connectivity", "mesh2d_face_nodes");
  nc.text(id, v_mesh, "node_dimension", "nmesh2d_node");
  nc.text(id, v_mesh, "face_dimension", "nmesh2d_face");
  nc.text(id, v_mesh, "max_face_nodes_dimension", "max_nmesh2d_face_nodes");
  if (ne) {
    nc.text(id, v_mesh, "edge_node_connectivity", "mesh2d_edge_nodes");
    nc.text(id, v_mesh, "edge_dimension", "nmesh2d_edge");
  }

  if (!m.crs_wkt.empty()) {
    nc.check(nc_def_var(id, "crs", NC_INT, 0, nullptr, &u.v_crs), "variable crs");
    if (crs.geographic) nc.text(id, u.v_crs, "grid_mapping_name", "latitude_longitude");
    nc.text(id, u.v_crs, "crs_wkt", crs.wkt2);
    nc.text(id, u.v_crs, "spatial_ref", crs.wkt1);
    nc.text(id, u.v_crs, "wkt", crs.wkt1);
    if (crs.epsg > 0) {
      nc.integer(id, u.v_crs, "epsg", crs.epsg);
      nc.text(id, u.v_crs, "EPSG_code", "EPSG:" + std::to_string(crs.epsg));
    }
  }
}

// Node coordinates.
void define_coordinates(const Ugrid& u, bool geographic, UgridVars& v) {
  const Nc& nc = u.nc;
  const int id = u.id;
  nc.check(nc_def_var(id, "mesh2d_node_x", NC_DOUBLE, 1, &u.d_node, &v.x), "variable mesh2d_node_x");
  nc.check(nc_def_var(id, "mesh2d_node_y", NC_DOUBLE, 1, &u.d_node, &v.y), "variable mesh2d_node_y");
  nc.text(id, v.x, "standard_name", geographic ? "longitude" : "projection_x_coordinate");
  nc.text(id, v.y, "standard_name", geographic ? "latitude" : "projection_y_coordinate");
  nc.text(id, v.x, "long_name", "x-coordinate of mesh nodes");
  nc.text(id, v.y, "long_name", "y-coordinate of mesh nodes");
  nc.text(id, v.x, "units", geographic ? "degrees_east" : "m");
  nc.text(id, v.y, "units", geographic ? "degrees_north" : "m");
  u.on_mesh(v.x, "node");
  u.on_mesh(v.y, "node");
}

// Face and edge connectivity, edge kinds and parts.
void define_connectivity(const Ugrid& u, const mesh::MeshView& m, UgridVars& v) {
  const Nc& nc = u.nc;
  const int id = u.id;
  const nc_type id_type = u.wide ? NC_INT64 : NC_INT;
  int face_dims[2] = {u.d_face, u.d_three};
  nc.check(nc_def_var(id, "mesh2d_face_nodes", id_type, 2, face_dims, &v.faces), "variable mesh2d_face_nodes");
  nc.text(id, v.faces, "cf_role", "face_node_connectivity");
  nc.text(id, v.faces, "long_name", "Vertex nodes of mesh faces (counterclockwise)");
  nc.integer(id, v.faces, "start_index", 0);
  if (!u.wide) {
    int fill = -1;
    nc.check(nc_put_att_int(id, v.faces, "_FillValue", NC_INT, 1, &fill), "_FillValue");
  } else {
    long long fill = -1;
    nc.check(nc_put_att_longlong(id, v.faces, "_FillValue", NC_INT64, 1, &fill), "_FillValue");
  }
  if (!m.edges.empty()) {
    int edge_dims[2] = {u.d_edge, u.d_two};
    nc.check(nc_def_var(id, "mesh2d_edge_nodes", id_type, 2, edge_dims, &v.edges), "variable mesh2d_edge_nodes");
    nc.text(id, v.edges, "cf_role", "edge_node_connectivity");
    nc.text(id, v.edges, "long_name", "Nodes of the constrained (boundary and breakline) edges");
    nc.integer(id, v.edges, "start_index", 0);
    nc.check(nc_def_var(id, "mesh2d_edge_kind", NC_INT, 1, &u.d_edge, &v.kind), "variable mesh2d_edge_kind");
    nc.text(id, v.kind, "long_name", "kind of constrained edge");
    int flags[5] = {0, 1, 2, 3, 4};
    nc.check(nc_put_att_int(id, v.kind, "flag_values", NC_INT, 5, flags), "flag_values");
    nc.text(id, v.kind, "flag_meanings", "none land island open breakline");
    u.on_mesh(v.kind, "edge");
    nc.check(nc_def_var(id, "mesh2d_edge_part", NC_INT, 1, &u.d_edge, &v.part), "variable mesh2d_edge_part");
    nc.text(id, v.part, "long_name", "input ring or line id of the constrained edge");
    u.on_mesh(v.part, "edge");
  }
}

// Node z and f, per-face quality.
void define_values(const Ugrid& u, const mesh::MeshView& m, const WriteOptions& o, UgridVars& v) {
  const Nc& nc = u.nc;
  const int id = u.id;
  auto node_var = [&](const char* name, const char* long_name, const char* std_name) {
    int var;
    nc.check(nc_def_var(id, name, NC_DOUBLE, 1, &u.d_node, &var), name);
    if (std_name) nc.text(id, var, "standard_name", std_name);
    nc.text(id, var, "long_name", long_name);
    nc.text(id, var, "units", "m");
    nc.text(id, var, "coordinates", "mesh2d_node_x mesh2d_node_y");
    u.on_mesh(var, "node");
    return var;
  };
  if (!m.z.empty()) {
    v.z = node_var("mesh2d_node_z", "elevation of mesh nodes (positive up)", "altitude");
    nc.text(id, v.z, "positive", "up");
  }
  if (!m.f.empty()) v.f = node_var("mesh2d_node_f", "target spacing f at mesh nodes", nullptr);
  auto face_var = [&](const char* name, const char* long_name, const char* units) {
    int var;
    nc.check(nc_def_var(id, name, NC_DOUBLE, 1, &u.d_face, &var), name);
    nc.text(id, var, "long_name", long_name);
    nc.text(id, var, "units", units);
    u.on_mesh(var, "face");
    return var;
  };
  v.angle = face_var("mesh2d_face_min_angle", "smallest angle of the triangle", "degree");
  if (o.f || o.triangle_r_over_f)
    v.ratio = face_var("mesh2d_face_R_over_f", "circumradius over spacing f at the circumcentre", "1");
}

// Writes an id table of `rows` x `cols` through the file's integer width.
template <class Get>
void put_ids(const Ugrid& u, int var, std::size_t rows, std::size_t cols, Get get, const char* what) {
  std::size_t start[2] = {0, 0}, count[2] = {rows, cols};
  if (u.wide) {
    std::vector<long long> buf(rows * cols);
    for (std::size_t r = 0; r < rows; ++r)
      for (std::size_t c = 0; c < cols; ++c) buf[r * cols + c] = static_cast<long long>(get(r, c));
    u.nc.check(nc_put_vara_longlong(u.id, var, start, count, buf.data()), what);
  } else {
    std::vector<int> buf(rows * cols);
    for (std::size_t r = 0; r < rows; ++r)
      for (std::size_t c = 0; c < cols; ++c) buf[r * cols + c] = static_cast<int>(get(r, c));
    u.nc.check(nc_put_vara_int(u.id, var, start, count, buf.data()), what);
  }
}

void write_data(const Ugrid& u, const mesh::MeshView& m, const WriteOptions& o, const UgridVars& v) {
  const Nc& nc = u.nc;
  const int id = u.id;
  const std::size_t nv = m.vertices.size(), nt = m.triangles.size(), ne = m.edges.size();
  if (nv) {
    std::vector<double> x(nv), y(nv);
    for (std::size_t i = 0; i < nv; ++i) {
      Point2 p = m.world(static_cast<Index>(i));
      x[i] = p.x;
      y[i] = p.y;
    }
    nc.check(nc_put_var_double(id, v.x, x.data()), "write mesh2d_node_x");
    nc.check(nc_put_var_double(id, v.y, y.data()), "write mesh2d_node_y");
    if (v.z >= 0) nc.check(nc_put_var_double(id, v.z, m.z.data()), "write mesh2d_node_z");
    if (v.f >= 0) nc.check(nc_put_var_double(id, v.f, m.f.data()), "write mesh2d_node_f");
  }
  if (nt) {
    put_ids(u, v.faces, nt, 3, [&](std::size_t r, std::size_t c) { return m.triangles[r][c]; }, "write mesh2d_face_nodes");
    std::vector<double> ang(nt);
    for (std::size_t t = 0; t < nt; ++t)
      ang[t] = o.triangle_min_angle ? (*o.triangle_min_angle)[t] : triangle_min_angle_deg(m, t);
    nc.check(nc_put_var_double(id, v.angle, ang.data()), "write mesh2d_face_min_angle");
    if (v.ratio >= 0) {
      for (std::size_t t = 0; t < nt; ++t) {
        if (o.triangle_r_over_f) { ang[t] = (*o.triangle_r_over_f)[t]; continue; }
        Point2 c;
        double r = circumradius(m, t, c);
        ang[t] = r / (*o.f)(c);
      }
      nc.check(nc_put_var_double(id, v.ratio, ang.data()), "write mesh2d_face_R_over_f");
    }
  }
  if (ne) {
    put_ids(u, v.edges, ne, 2, [&](std::size_t r, std::size_t c) { return c == 0 ? m.edges[r].a : m.edges[r].b; },
            "write mesh2d_edge_nodes");
    std::vector<int> kind(ne), part(ne);
    for (std::size_t e = 0; e < ne; ++e) {
      kind[e] = m.edges[e].marker;
      part[e] = m.edges[e].part;
    }
    nc.check(nc_put_var_int(id, v.kind, kind.data()), "write mesh2d_edge_kind");
    nc.check(nc_put_var_int(id, v.part, part.data()), "write mesh2d_edge_part");
  }
}

}  // namespace

void write_ugrid(const mesh::MeshView& m, const std::string& path, const WriteOptions& o) {
  const Nc nc{path};
  const NcCrs crs = nc_crs(m.crs_wkt, path);
  const std::lock_guard<std::mutex> one_at_a_time(nc_mutex());
  TempFile tf(path);
  tf.release_for_library();
  NcFile f;
  nc.check(nc_create(tf.path().c_str(), NC_NETCDF4 | NC_NOCLOBBER, &f.id), "create");
  // Ids fit in NC_INT unless the mesh has more than 2^31-1 nodes.
  Ugrid u{nc, f.id, m.vertices.size() > static_cast<std::size_t>(INT_MAX)};
  UgridVars v;
  define_mesh(u, m, o, crs);
  define_coordinates(u, crs.geographic, v);
  define_connectivity(u, m, v);
  define_values(u, m, o, v);
  nc.check(nc_enddef(f.id), "enddef");
  write_data(u, m, o, v);
  const int status = nc_close(f.id);
  f.id = -1;
  nc.check(status, "close");
  tf.commit();
}

}  // namespace fdr::io::detail
